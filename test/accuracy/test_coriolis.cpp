// The Coriolis matrix, the generalized momentum and Cᵀ q̇ (algorithms/coriolis.hpp) against
// oracles in float128 built on the reference (reference/: CRBA and RNEA on 6×6 matrices):
//  - Ṁ = C + Cᵀ, with Ṁ the central difference of the reference's M along q̇ (≤ 1e-12 relative);
//  - C q̇ = h − g = ID(q, q̇, 0) − ID(q, 0, 0) (≤ 1e-14 relative);
//  - C equal to the Christoffel-symbol construction C_ij = Σ_k ½ (∂_k M_ij + ∂_j M_ik − ∂_i M_jk) q̇_k,
//    O(n³) from central differences of M, on the double pendulum and the panda (≤ 1e-13);
//  - p = M q̇ and Cᵀ q̇ = Ṁ q̇ − (h − g);
// on every bundled robot (fixed base; talos and solo12 also floating), the panda with coupled
// fingers, the mobile manipulator (prismatic joints, random axes) coupled, with armature, and a
// planar joint (checked as the same robot written with its elementary joints, which have the
// same coordinates and so the same C). The library in float128 meets the same identities to 1e-20.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "spatial_dynamics/algorithms/coriolis.hpp"
#include "spatial_dynamics/algorithms/crba.hpp"
#include "spatial_dynamics/reduction/couple_mimic_joints.hpp"
#include "spatial_dynamics/reference/high_precision.hpp"
#include "spatial_dynamics/reference/inverse_dynamics.hpp"
#include "spatial_dynamics/reference/mass_matrix.hpp"
#include "synthetic_robots.hpp"
#include "configuration_path.hpp"
#include "exact_rotations.hpp"
#include "test_utils.hpp"

namespace sd = spatial_dynamics;
namespace ref = spatial_dynamics::reference;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using sd::Quad;
using VectorQ = sd::VectorX<Quad>;
using MatrixQ = sd::MatrixX<Quad>;

namespace {

struct Case {
  std::string name;
  sd::Model<double> model;
  sd::Model<double> oracle;  // the same coordinates in joint types the reference knows
  bool christoffel;          // also against the O(n³) Christoffel construction
  bool planar = false;       // `oracle` is another model: no float128 run of the library on `model`
};

sd::Model<double> robot(const std::string& file, bool floating) {
  sd::ModelBuildOptions options;
  options.floating_base = floating;
  return sd::build_model_from_urdf_file(sd_test::robot_path(file), options);
}

/// world —planar (normal n)→ cart —fixed→ panda_link0, or the same planar joint as two prismatic
/// joints and a revolute one between massless links (its definition).
std::string panda_on_cart(bool elementary, const sd::Joint<double>* planar) {
  const std::string cart =
      "<link name=\"world\"/><link name=\"cart\"><inertial><origin xyz=\"0.05 -0.02 0.1\" rpy=\"0.1 -0.2 0.3\"/>"
      "<mass value=\"25\"/><inertia ixx=\"0.3\" ixy=\"0.01\" ixz=\"-0.02\" iyy=\"0.25\" iyz=\"0.015\" izz=\"0.4\"/>"
      "</inertial></link><joint name=\"cart_mount\" type=\"fixed\"><parent link=\"cart\"/><child link=\"panda_link0\"/>"
      "<origin xyz=\"0.1 -0.2 0.3\" rpy=\"0.2 0 -0.4\"/></joint>\n";
  const std::string origin = "<origin xyz=\"0.5 0.2 -0.1\" rpy=\"0.3 -0.1 0.7\"/>";
  std::string joints;
  if (!elementary) {
    joints = "<joint name=\"cart_joint\" type=\"planar\"><parent link=\"world\"/><child link=\"cart\"/>" + origin +
             "<axis xyz=\"0.3 -0.4 0.5\"/></joint>\n";
  } else {
    auto text = [](const Eigen::Vector3d& v) {
      char s[96];
      std::snprintf(s, sizeof s, "%.17g %.17g %.17g", v.x(), v.y(), v.z());
      return std::string(s);
    };
    const std::string limit = "<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>";
    joints = "<link name=\"cart_x_link\"/><link name=\"cart_y_link\"/>"
             "<joint name=\"cart_x\" type=\"prismatic\"><parent link=\"world\"/><child link=\"cart_x_link\"/>" + origin +
             "<axis xyz=\"" + text(planar->plane_x) + "\"/>" + limit + "</joint>\n"
             "<joint name=\"cart_y\" type=\"prismatic\"><parent link=\"cart_x_link\"/><child link=\"cart_y_link\"/>"
             "<axis xyz=\"" + text(planar->plane_y) + "\"/>" + limit + "</joint>\n"
             "<joint name=\"cart_yaw\" type=\"continuous\"><parent link=\"cart_y_link\"/><child link=\"cart\"/>"
             "<axis xyz=\"" + text(planar->axis) + "\"/></joint>\n";
  }
  return sd_test::with_extra_elements(sd_test::robot_text("panda.urdf"), cart + joints);
}

std::vector<Case> cases() {
  std::vector<Case> out;
  for (const std::string& file : sd_test::robot_files()) {
    const sd::Model<double> m = robot(file, false);
    out.push_back({file + " fixed", m, m, file == "double_pendulum.urdf" || file == "panda.urdf"});
  }
  for (const char* file : {"talos.urdf", "solo12.urdf"}) {
    const sd::Model<double> m = robot(file, true);
    out.push_back({std::string(file) + " floating", m, m, false});
  }
  const sd::Model<double> fingers = sd::couple_mimic_joints(robot("panda.urdf", false));
  out.push_back({"panda.urdf coupled fingers", fingers, fingers, false});
  sd::Model<double> manipulator = sd::couple_mimic_joints(sd::build_model_from_urdf_string(sd_test::mobile_manipulator_urdf(7)));
  for (int k = 0; k < manipulator.nv; ++k) manipulator.armature[k] = 0.05 * (k + 1);
  manipulator.finalize();
  out.push_back({"mobile manipulator coupled, armature", manipulator, manipulator, false});
  const sd::Model<double> planar = sd::build_model_from_urdf_string(panda_on_cart(false, nullptr));
  const sd::Joint<double>& joint = planar.joints[planar.jointBody("cart_joint")];
  EXPECT_EQ(joint.type, sd::JointType::Planar);
  out.push_back({"panda on a planar cart", planar, sd::build_model_from_urdf_string(panda_on_cart(true, &joint)), false, true});
  return out;
}

using sd_test::with_exact_rotations;

/// Ṁ along q̇ by central differences of the reference's M in float128 (step 1e-11: truncation
/// ~1e-22, rounding ~1e-23).
MatrixQ mass_matrix_rate(const sd::Model<Quad>& model, const VectorQ& q, const VectorQ& qd) {
  const Quad h("1e-11");
  return (ref::mass_matrix(model, sd_test::advance(model, q, qd, h)) - ref::mass_matrix(model, sd_test::advance(model, q, qd, -h))) / (2 * h);
}

/// C_ij = Σ_k Γ_ijk q̇_k with Γ_ijk = ½ (∂_k M_ij + ∂_j M_ik − ∂_i M_jk) (Christoffel symbols of the
/// first kind), the partial derivatives by central differences in float128. For models whose q̇
/// is dq/dt (no free joint).
MatrixQ christoffel_coriolis(const sd::Model<Quad>& model, const VectorQ& q, const VectorQ& qd) {
  const int n = model.nv;
  std::vector<MatrixQ> dM(n);
  for (int k = 0; k < n; ++k) {
    VectorQ e = VectorQ::Zero(n);
    e[k] = 1;
    dM[k] = mass_matrix_rate(model, q, e);
  }
  MatrixQ C = MatrixQ::Zero(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) C(i, j) += (dM[k](i, j) + dM[j](i, k) - dM[i](j, k)) * qd[k] / 2;
  return C;
}

struct Errors {
  double rate = 0, coriolis_velocity = 0, christoffel = 0, momentum = 0, transpose_velocity = 0;
  double quad_rate = 0, quad_coriolis_velocity = 0;
};

Errors errors(const Case& c, int states, unsigned seed) {
  const sd::Model<Quad> oracle = with_exact_rotations(c.oracle);
  const sd::Model<Quad> model_q = with_exact_rotations(c.model);
  sd::Data<double> data(c.model);
  sd::Data<Quad> data_q(model_q);
  std::mt19937 rng(seed);
  Errors e;
  auto worst = [](double& w, double x) { w = std::max(w, x); };
  for (int s = 0; s < states; ++s) {
    const VectorXd q = sd_test::random_configuration(c.model, rng), qd = sd_test::random_vector(c.model.nv, rng);
    VectorQ Q = sd::to_quad(q);
    for (int i = 1; i < model_q.nbodies(); ++i)  // a unit quaternion in float128
      if (model_q.joints[i].type == sd::JointType::Free) Q.segment<4>(model_q.joints[i].idx_q + 3).normalize();
    const VectorXd q_used = Q.cast<double>();  // the same configuration in double (within 1e-16)
    const VectorQ Qd = sd::to_quad(qd);
    const MatrixQ M_rate = mass_matrix_rate(oracle, Q, Qd);
    const VectorQ h_less_g = ref::inverse_dynamics(oracle, Q, Qd, VectorQ::Zero(c.model.nv)) -
                             ref::inverse_dynamics(oracle, Q, VectorQ::Zero(c.model.nv), VectorQ::Zero(c.model.nv));
    const MatrixQ C = sd::coriolis_matrix(c.model, data, q_used, qd).cast<Quad>();
    worst(e.rate, sd::relative_error_to(C + C.transpose(), M_rate));
    worst(e.coriolis_velocity, sd::relative_error_to(C * Qd, h_less_g));
    if (c.christoffel) worst(e.christoffel, sd::relative_error_to(C, christoffel_coriolis(oracle, Q, Qd)));
    worst(e.momentum, sd::relative_error_to(sd::generalized_momentum(c.model, data, q_used, qd), ref::mass_matrix(oracle, Q) * Qd));
    worst(e.transpose_velocity, sd::relative_error_to(sd::coriolis_transpose_times_velocity(c.model, data, q_used, qd),
                                                      VectorQ(M_rate * Qd - h_less_g)));
    if (c.planar) continue;
    const MatrixQ C_q = sd::coriolis_matrix(model_q, data_q, Q, Qd);
    worst(e.quad_rate, sd::relative_error_to(C_q + C_q.transpose(), M_rate));
    worst(e.quad_coriolis_velocity, sd::relative_error_to(C_q * Qd, h_less_g));
  }
  return e;
}

}  // namespace

TEST(CoriolisMatrix, AgainstTheReferenceInFloat128) {
  unsigned seed = 1;
  for (const Case& c : cases()) {
    const Errors e = errors(c, c.model.nv > 30 ? 3 : 10, seed++);
    std::printf("[coriolis] %-40s Ṁ=C+Cᵀ %8.2g  Cq̇=h−g %8.2g  Christoffel %8.2g  p %8.2g  Cᵀq̇ %8.2g  | float128: %8.2g %8.2g\n",
                c.name.c_str(), e.rate, e.coriolis_velocity, e.christoffel, e.momentum, e.transpose_velocity,
                e.quad_rate, e.quad_coriolis_velocity);
    EXPECT_LE(e.rate, 1e-12) << c.name;
    EXPECT_LE(e.coriolis_velocity, 1e-14) << c.name;
    EXPECT_LE(e.christoffel, 1e-13) << c.name;
    EXPECT_LE(e.momentum, 4e-15) << c.name;
    EXPECT_LE(e.transpose_velocity, 1e-12) << c.name;
    EXPECT_LE(e.quad_rate, 1e-20) << c.name;
    EXPECT_LE(e.quad_coriolis_velocity, 1e-28) << c.name;
  }
}

TEST(CoriolisMatrix, StructuralZerosAndNoResultForBadInput) {
  const sd::Model<double> model = robot("talos.urdf", false);
  sd::Data<double> data(model);
  std::mt19937 rng(3);
  const VectorXd q = sd_test::random_configuration(model, rng), qd = sd_test::random_vector(model.nv, rng);
  const MatrixXd C = sd::coriolis_matrix(model, data, q, qd);
  const MatrixXd M = sd::crba(model, data, q);
  for (int r = 0; r < model.nv; ++r)  // entries between branches are zero in M and in C
    for (int k = 0; k < model.nv; ++k)
      if (M(r, k) == 0.0) EXPECT_EQ(C(r, k), 0.0) << r << ", " << k;
  EXPECT_THROW(sd::coriolis_matrix(model, data, q, VectorXd::Zero(model.nv + 1)), std::invalid_argument);
  VectorXd bad = qd;
  bad[3] = std::numeric_limits<double>::quiet_NaN();
  try {
    sd::coriolis_matrix(model, data, q, bad);
    ADD_FAILURE() << "a NaN velocity gave a result";
  } catch (const std::domain_error& error) {
    EXPECT_NE(std::string(error.what()).find("Coriolis matrix"), std::string::npos) << error.what();
  }
}
