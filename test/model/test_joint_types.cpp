// Every joint type (model/joints/, through the one dispatch) against its own transform, in
// float128: S q̇ against the relative velocity v_J from a central difference of X_J along q̇
// (crm(v_J) = −Ẋ_J X_J⁻¹, RBDA §4.4), c_J against the difference of S q̇ along q̇, S̊ (column_rate)
// against the difference of each column along q̇ and its sum Σ S̊_k q̇_k against c_J, and every
// other method against the dense S formed from `column`: Sᵀ f, I S, c_J + v × S q̇, and S q̇ = S q̇
// column by column. X_J itself against the reference's joint transform (reference/joint_model.hpp).
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <type_traits>

#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/reference/high_precision.hpp"
#include "spatial_dynamics/reference/joint_model.hpp"
#include "spatial_dynamics/reference/spatial_matrices.hpp"

namespace sd = spatial_dynamics;
using Quad = sd::Quad;
using V3 = sd::Vector3<Quad>;

namespace {

/// The joints: every kind, along x, y, z and tilted axes (a planar joint's normal likewise).
std::vector<sd::Joint<Quad>> joints() {
  std::vector<sd::Joint<Quad>> out;
  const V3 tilted = V3(Quad(1), Quad(-2), Quad(0.5)).normalized();
  for (const sd::JointType type : {sd::JointType::Revolute, sd::JointType::Prismatic})
    for (const V3& axis : {V3(V3::UnitX()), V3(V3::UnitY()), V3(V3::UnitZ()), V3(-V3::UnitY()), tilted}) {
      sd::Joint<Quad> j;
      j.type = type;
      j.axis = axis;
      j.nq = j.nv = 1;
      out.push_back(j);
    }
  sd::Joint<Quad> free;
  free.type = sd::JointType::Free;
  free.nq = 7;
  free.nv = 6;
  out.push_back(free);
  for (const V3& normal : {V3(V3::UnitZ()), tilted}) {
    sd::Joint<Quad> planar;
    planar.type = sd::JointType::Planar;
    planar.axis = normal;
    planar.plane_x = (normal.cross(V3::UnitX()).norm() > Quad(0.5) ? V3(V3::UnitX()) : V3(V3::UnitY()));
    planar.plane_x = (planar.plane_x - normal * normal.dot(planar.plane_x)).normalized();
    planar.plane_y = normal.cross(planar.plane_x);
    planar.nq = planar.nv = 3;
    out.push_back(planar);
  }
  for (const V3& axis : {V3(V3::UnitZ()), tilted}) {  // a screw, pitch 0.3 m/rad
    sd::Joint<Quad> helical;
    helical.type = sd::JointType::Helical;
    helical.axis = axis;
    helical.pitch = Quad("0.3");
    out.push_back(helical);
  }
  for (sd::Joint<Quad>& j : out) j.update_model();
  return out;
}

sd::VectorX<Quad> random_vector(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  sd::VectorX<Quad> x(n);
  for (int k = 0; k < n; ++k) x[k] = Quad(u(rng));
  return x;
}

/// A joint's configuration; a free joint's quaternion of unit norm.
sd::VectorX<Quad> random_configuration(const sd::Joint<Quad>& j, std::mt19937& rng) {
  sd::VectorX<Quad> q = random_vector(j.nq, rng);
  if (j.type == sd::JointType::Free) q.tail<4>().normalize();
  return q;
}

Quad angle_of(const sd::Joint<Quad>& j, const sd::VectorX<Quad>& q) {
  const int angle = sd::angle_coordinate(j);
  return angle >= 0 ? q[angle] : Quad(0);
}

/// X_J(q) X_tree as a motion matrix, from the joint type.
sd::Matrix6<Quad> up_transform(const sd::Joint<Quad>& j, const sd::PluckerTransform<Quad>& X_tree,
                               const sd::VectorX<Quad>& q) {
  const std::string name = "j";
  const Quad theta = angle_of(j, q);
  return sd::visit_joint(j, [&](const auto& joint) {
    return joint.transform(X_tree, q.data(), sin(theta), cos(theta), sd::JointLabel{name, 0}).toMotionMatrix();
  });
}

double max_abs(const sd::MatrixX<Quad>& x) { return static_cast<double>(x.cwiseAbs().maxCoeff()); }

}  // namespace

TEST(JointTypes, AgainstTheirTransformAndDenseSubspace) {
  std::mt19937 rng(17);
  const Quad h("1e-12");
  for (const sd::Joint<Quad>& j : joints()) {
    const std::string what = "joint kind " + std::to_string(static_cast<int>(j.type)) + " (variant alternative " +
                             std::to_string(j.model.index()) + "), axis " + std::to_string(static_cast<double>(j.axis.x())) +
                             " " + std::to_string(static_cast<double>(j.axis.y())) + " " +
                             std::to_string(static_cast<double>(j.axis.z()));
    for (int trial = 0; trial < 5; ++trial) {
      const sd::PluckerTransform<Quad> X_tree(sd::coordinate_rotation<Quad>(V3(random_vector(3, rng)).normalized(), Quad(0.7)),
                                              V3(random_vector(3, rng)));
      const sd::VectorX<Quad> q = random_configuration(j, rng), qd = random_vector(j.nv, rng);
      const Quad theta = angle_of(j, q), s = sin(theta), c = cos(theta);
      // X_J against the reference's.
      const sd::Matrix6<Quad> X = up_transform(j, X_tree, q);
      EXPECT_LE(max_abs(X - sd::reference::joint_transform(j, q) * X_tree.toMotionMatrix()), 1e-30) << what;
      sd::visit_joint(j, [&](const auto& joint) {
        constexpr int nv = std::decay_t<decltype(joint)>::nv;
        Eigen::Matrix<Quad, 6, nv> S;
        for (int k = 0; k < nv; ++k) S.col(k) = joint.column(k, s, c).toVector();
        const sd::Vector6<Quad> vJ = joint.motion(qd.data(), s, c).toVector();
        EXPECT_LE(max_abs(vJ - S * qd), 1e-30) << what;
        if (j.type != sd::JointType::Free) {  // q̇ = d/dt q: S q̇ from X_J(q + t q̇)
          const sd::Matrix6<Quad> dX = (up_transform(j, X_tree, q + h * qd) - up_transform(j, X_tree, q - h * qd)) / (2 * h);
          const sd::Matrix6<Quad> crm_vJ = -dX * X.inverse();
          EXPECT_LE(max_abs(crm_vJ - sd::motion_cross_matrix(sd::MotionVector<Quad>(vJ))), 1e-20) << what;
        }
        // c_J = d/dt (S(q) q̇) along q̇ (q̈ = 0), and c_J + v × S q̇.
        const auto motion_at = [&](const Quad& t) {
          const Quad angle = angle_of(j, sd::VectorX<Quad>(q + t * qd));
          return joint.motion(qd.data(), sin(angle), cos(angle)).toVector();
        };
        const sd::Vector6<Quad> cJ = j.type == sd::JointType::Free ? sd::Vector6<Quad>::Zero()
                                                                   : sd::Vector6<Quad>((motion_at(h) - motion_at(-h)) / (2 * h));
        const sd::MotionVector<Quad> v(random_vector(6, rng));
        const sd::Vector6<Quad> expected = cJ + sd::motion_cross_matrix(v) * vJ;
        EXPECT_LE(max_abs(joint.velocity_product(v, qd.data(), s, c).toVector() - expected), 1e-20) << what;
        // S̊ column by column: the difference of S's column along q̇ (a free joint's q̇ is not
        // dq/dt, but its S is constant), and Σ S̊_k q̇_k = c_J.
        sd::Vector6<Quad> rate_sum = sd::Vector6<Quad>::Zero();
        for (int k = 0; k < nv; ++k) {
          const auto column_at = [&](const Quad& t) {
            const Quad angle = angle_of(j, sd::VectorX<Quad>(q + t * qd));
            return joint.column(k, sin(angle), cos(angle)).toVector();
          };
          const sd::Vector6<Quad> numeric = j.type == sd::JointType::Free ? sd::Vector6<Quad>::Zero()
                                                                          : sd::Vector6<Quad>((column_at(h) - column_at(-h)) / (2 * h));
          const sd::Vector6<Quad> rate = joint.column_rate(k, qd.data(), s, c).toVector();
          EXPECT_LE(max_abs(rate - numeric), 1e-20) << what << ", column " << k;
          rate_sum += rate * qd[k];
        }
        EXPECT_LE(max_abs(rate_sum - cJ), 1e-20) << what;
        // Sᵀ f.
        const sd::ForceVector<Quad> f(random_vector(6, rng));
        EXPECT_LE(max_abs(joint.project(f, s, c) - S.transpose() * f.toVector()), 1e-30) << what;
      });
    }
  }
}

// The dispatch picks the axis-aligned types for +x, +y, +z and the general ones otherwise.
TEST(JointTypes, AxisAlignedJointsAreTypesOfTheirOwn) {
  const std::vector<sd::Joint<Quad>> all = joints();
  EXPECT_TRUE((std::holds_alternative<sd::RevoluteAxisJoint<Quad, 0>>(all[0].model)));
  EXPECT_TRUE((std::holds_alternative<sd::RevoluteAxisJoint<Quad, 2>>(all[2].model)));
  EXPECT_TRUE((std::holds_alternative<sd::RevoluteJoint<Quad>>(all[3].model)));  // −y
  EXPECT_TRUE((std::holds_alternative<sd::PrismaticAxisJoint<Quad, 1>>(all[6].model)));
  EXPECT_TRUE((std::holds_alternative<sd::PrismaticJoint<Quad>>(all[9].model)));
  EXPECT_TRUE((std::holds_alternative<sd::FreeJoint<Quad>>(all[10].model)));
  EXPECT_TRUE((std::holds_alternative<sd::PlanarJoint<Quad>>(all[11].model)));
}
