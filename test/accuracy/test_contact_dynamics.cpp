// Contact-consistent dynamics (algorithms/contact_dynamics.hpp) and the centroidal quantities
// (algorithms/centroidal.hpp) against an independent solution in float128:
//  - frame poses from the reference's 6×6 transforms (reference/joint_model.hpp); J_c and J̇_c q̇ by
//    central differences of the contact frames' poses along q(t) = q ⊕ t q̇ (a free joint's screw
//    motion at constant body twist), so q̈ = 0 along it;
//  - inverse dynamics with contacts: the reference's ID, λ by a dense pseudo-inverse of
//    the base rows, τ = ID − J_cᵀ λ; forward dynamics: the reference's M and h, the KKT system
//    [M J_cᵀ; J_c 0] solved densely by its pseudo-inverse (the minimum-norm λ when contacts are redundant),
//    with the contacts at rest (q̇ projected onto J_c q̇ = 0, so that redundant constraints agree);
//  - the centre of mass from the body poses, J_com and A_G from central differences of the body poses;
// on talos (two surface feet; and a redundant set), solo12 (four point feet; two diagonal ones), a
// floating double pendulum (one point), random states; ID and FD also with random external forces on
// every body (the reference's ID(q, q̇, q̈, f_ext)).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "spatial_dynamics/algorithms/centroidal.hpp"
#include "spatial_dynamics/algorithms/contact_dynamics.hpp"
#include "spatial_dynamics/algorithms/crba.hpp"
#include "spatial_dynamics/algorithms/rnea.hpp"
#include "spatial_dynamics/reduction/couple_mimic_joints.hpp"
#include "spatial_dynamics/reference/high_precision.hpp"
#include "spatial_dynamics/reference/inverse_dynamics.hpp"
#include "spatial_dynamics/reference/joint_model.hpp"
#include "spatial_dynamics/reference/mass_matrix.hpp"
#include "spatial_dynamics/reference/pseudo_inverse.hpp"
#include "configuration_path.hpp"
#include "contact_oracle.hpp"
#include "exact_rotations.hpp"
#include "test_utils.hpp"

namespace sd = spatial_dynamics;
namespace ref = spatial_dynamics::reference;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using sd::Quad;
using VecQ = ref::VecX<Quad>;
using MatQ = ref::MatX<Quad>;
using Vec3Q = ref::Vec3<Quad>;
using Mat3Q = ref::Mat3<Quad>;
using Mat6Q = ref::Mat6<Quad>;
using sd_test::body_transforms;
using sd_test::contact_jacobian_by_differences;
using sd_test::frame_transform;
using sd_test::kStep;
using sd_test::pose_of;
using sd_test::pseudo_inverse_solve;
using sd_test::velocity_from;

namespace {

struct Scene {
  std::string name;
  std::string urdf;
  std::vector<std::string> frames, kinds;
};

std::vector<Scene> scenes() {
  return {{"talos two surface feet", "talos.urdf", {"left_sole_link", "right_sole_link"}, {"surface", "surface"}},
          {"talos redundant", "talos.urdf", {"left_sole_link", "leg_left_6_link", "right_sole_link"}, {"surface", "point", "surface"}},
          {"solo12 four point feet", "solo12.urdf", {"FL_FOOT", "FR_FOOT", "HL_FOOT", "HR_FOOT"}, {"point", "point", "point", "point"}},
          {"solo12 two diagonal feet", "solo12.urdf", {"FL_FOOT", "HR_FOOT"}, {"point", "point"}},
          {"floating double pendulum", "double_pendulum.urdf", {"link2"}, {"point"}}};
}

sd::Model<double> floating_robot(const std::string& file) {
  sd::ModelBuildOptions options;
  options.floating_base = true;
  return sd::build_model_from_urdf_file(sd_test::robot_path(file), options);
}

struct State {
  VectorXd q, qd, qdd, tau;
  VecQ Q, Qd, Qdd, Tau;
  std::vector<sd::ForceVector<double>> f_ext;  // on every body but the base (empty: none)
  std::vector<sd::ForceVector<Quad>> F_ext;
};

/// Random external forces on every body, ‖f‖ ~ 20 N and N m (body coordinates), into x.f_ext and x.F_ext.
void add_external_forces(const sd::Model<double>& model, std::mt19937& rng, State& x) {
  x.f_ext.assign(model.nbodies(), sd::ForceVector<double>::Zero());
  for (int i = 1; i < model.nbodies(); ++i)
    x.f_ext[i] = sd::ForceVector<double>(sd::Vector6<double>(sd_test::random_vector(6, rng, 20.0)));
  x.F_ext.resize(x.f_ext.size());
  for (std::size_t i = 0; i < x.f_ext.size(); ++i) x.F_ext[i] = x.f_ext[i].cast<Quad>();
}

State random_state(const sd::Model<double>& model, std::mt19937& rng) {
  State s;
  s.Q = sd::to_quad(sd_test::random_configuration(model, rng));
  for (int i = 1; i < model.nbodies(); ++i)
    if (model.joints[i].type == sd::JointType::Free) s.Q.segment<4>(model.joints[i].idx_q + 3).normalize();
  s.q = s.Q.cast<double>();
  s.Q = sd::to_quad(s.q);
  s.qd = sd_test::random_vector(model.nv, rng);
  s.qdd = sd_test::random_vector(model.nv, rng);
  s.tau = sd_test::random_vector(model.nv, rng, 5.0);
  s.tau.head(6).setZero();  // the floating base is not actuated
  s.Qd = sd::to_quad(s.qd);
  s.Qdd = sd::to_quad(s.qdd);
  s.Tau = sd::to_quad(s.tau);
  return s;
}

}  // namespace

TEST(ContactJacobian, MatchesDifferencesOfTheFramePoses) {
  unsigned seed = 1;
  for (const Scene& scene : scenes()) {
    const sd::Model<double> model = floating_robot(scene.urdf);
    const sd::Model<Quad> oracle = sd_test::with_exact_rotations(model);
    const sd::ContactSet<double> contacts(model, scene.frames, scene.kinds);
    sd::Data<double> data(model);
    sd::ContactData<double> cd(model, contacts);
    std::mt19937 rng(seed++);
    double worst_J = 0, worst_Jdot = 0;
    for (int s = 0; s < 3; ++s) {
      const State x = random_state(model, rng);
      sd::contact_jacobian(model, data, contacts, cd, x.q, x.qd);
      MatQ J;
      VecQ Jdot_qd;
      contact_jacobian_by_differences(oracle, contacts, x.Q, x.Qd, J, Jdot_qd);
      worst_J = std::max(worst_J, sd::relative_error_to(cd.J, J));
      worst_Jdot = std::max(worst_Jdot, sd::relative_error_to(cd.acceleration, Jdot_qd));
    }
    std::printf("[%s] J_c: %.3g, J̇_c q̇: %.3g\n", scene.name.c_str(), worst_J, worst_Jdot);
    EXPECT_LT(worst_J, 1e-12) << scene.name;
    EXPECT_LT(worst_Jdot, 1e-10) << scene.name;
  }
}

/// Inverse dynamics with contacts (and with random external forces on every body) against the
/// reference's ID(q, q̇, q̈, f_ext), λ by a dense pseudo-inverse of the base rows.
static void check_inverse_dynamics_with_contacts(bool with_external_forces) {
  unsigned seed = with_external_forces ? 51 : 11;
  for (const Scene& scene : scenes()) {
    const sd::Model<double> model = floating_robot(scene.urdf);
    const sd::Model<Quad> oracle = sd_test::with_exact_rotations(model);
    const sd::ContactSet<double> contacts(model, scene.frames, scene.kinds);
    sd::Data<double> data(model);
    sd::ContactData<double> cd(model, contacts);
    std::mt19937 rng(seed++);
    double worst_tau = 0, worst_lambda = 0, worst_base = 0, worst_violation = 0;
    for (int s = 0; s < 3; ++s) {
      State x = random_state(model, rng);
      if (with_external_forces) add_external_forces(model, rng, x);
      MatQ J;
      VecQ Jdot_qd;
      contact_jacobian_by_differences(oracle, contacts, x.Q, x.Qd, J, Jdot_qd);
      const VecQ id = ref::inverse_dynamics(oracle, x.Q, x.Qd, x.Qdd, x.F_ext);
      const VecQ lambda = pseudo_inverse_solve(J.leftCols(6).transpose(), id.head(6));
      const VecQ tau = id - J.transpose() * lambda;
      if (with_external_forces)
        sd::inverse_dynamics_with_contacts(model, data, contacts, cd, x.q, x.qd, x.qdd, x.f_ext);
      else
        sd::inverse_dynamics_with_contacts(model, data, contacts, cd, x.q, x.qd, x.qdd);
      worst_tau = std::max(worst_tau, sd::relative_error_to(cd.tau.tail(model.nv - 6), VecQ(tau.tail(model.nv - 6))));
      worst_lambda = std::max(worst_lambda, sd::relative_error_to(cd.lambda, lambda));
      // The base rows: the wrench left over, relative to the base's part of ID.
      const VecQ base_difference = sd::to_quad(VectorXd(cd.tau.head(6))) - tau.head(6);
      worst_base = std::max(worst_base, static_cast<double>(base_difference.norm() / id.head(6).norm()));
      const VecQ violation = J * x.Qdd + Jdot_qd;
      worst_violation = std::max(worst_violation, sd::relative_error_to(cd.acceleration, violation));
    }
    std::printf("[%s%s] τ: %.3g, λ: %.3g, base rows: %.3g, J_c q̈ + J̇_c q̇: %.3g\n", scene.name.c_str(),
                with_external_forces ? ", external forces" : "", worst_tau,
                worst_lambda, worst_base, worst_violation);
    EXPECT_LT(worst_tau, 1e-12) << scene.name;
    EXPECT_LT(worst_lambda, 1e-12) << scene.name;
    EXPECT_LT(worst_base, 1e-12) << scene.name;
    EXPECT_LT(worst_violation, 1e-10) << scene.name;
  }
}

TEST(InverseDynamicsWithContacts, MatchesTheReferenceAndTheMinimumNormWrenches) { check_inverse_dynamics_with_contacts(false); }

TEST(InverseDynamicsWithContacts, WithExternalForcesMatchesTheReference) { check_inverse_dynamics_with_contacts(true); }

/// Forward dynamics with contacts (and with random external forces on every body) against the dense
/// KKT system of the reference's M and ID(q, q̇, 0, f_ext).
static void check_forward_dynamics_with_contacts(bool with_external_forces) {
  unsigned seed = with_external_forces ? 61 : 21;
  for (const Scene& scene : scenes()) {
    const sd::Model<double> model = floating_robot(scene.urdf);
    const sd::Model<Quad> oracle = sd_test::with_exact_rotations(model);
    const sd::ContactSet<double> contacts(model, scene.frames, scene.kinds);
    sd::Data<double> data(model);
    sd::ContactData<double> cd(model, contacts);
    std::mt19937 rng(seed++);
    double worst_qdd = 0, worst_lambda = 0, worst_violation = 0;
    for (int s = 0; s < 3; ++s) {
      State x = random_state(model, rng);
      if (with_external_forces) add_external_forces(model, rng, x);
      // Contacts at rest (J_c q̇ = 0): redundant contacts' constraints are then consistent.
      // (with Data of its own: forward_dynamics_with_contacts must not rely on poses another call left)
      sd::Data<double> projection(model);
      const MatrixXd J_c = sd::contact_jacobian(model, projection, contacts, cd, x.q, x.qd);
      x.qd -= J_c.completeOrthogonalDecomposition().solve(VectorXd(J_c * x.qd));
      x.Qd = sd::to_quad(x.qd);
      MatQ J;
      VecQ Jdot_qd;
      contact_jacobian_by_differences(oracle, contacts, x.Q, x.Qd, J, Jdot_qd);
      const int n = model.nv, m = contacts.rows;
      MatQ kkt = MatQ::Zero(n + m, n + m);
      kkt.topLeftCorner(n, n) = ref::mass_matrix(oracle, x.Q);
      kkt.topRightCorner(n, m) = -J.transpose();
      kkt.bottomLeftCorner(m, n) = J;
      VecQ rhs(n + m);
      rhs << x.Tau - ref::inverse_dynamics(oracle, x.Q, x.Qd, VecQ(VecQ::Zero(n)), x.F_ext), -Jdot_qd;
      const VecQ solution = pseudo_inverse_solve(kkt, rhs);  // (q̈ ; λ), λ of minimum norm
      if (with_external_forces)
        sd::forward_dynamics_with_contacts(model, data, contacts, cd, x.q, x.qd, x.tau, x.f_ext);
      else
        sd::forward_dynamics_with_contacts(model, data, contacts, cd, x.q, x.qd, x.tau);
      worst_qdd = std::max(worst_qdd, sd::relative_error_to(cd.qdd, VecQ(solution.head(n))));
      worst_lambda = std::max(worst_lambda, sd::relative_error_to(cd.lambda, VecQ(solution.tail(m))));
      worst_violation = std::max(worst_violation, cd.acceleration.norm() / std::max(1.0, static_cast<double>(Jdot_qd.norm())));
    }
    std::printf("[%s%s] q̈: %.3g, λ: %.3g, ‖J_c q̈ + J̇_c q̇‖: %.3g\n", scene.name.c_str(),
                with_external_forces ? ", external forces" : "", worst_qdd, worst_lambda, worst_violation);
    EXPECT_LT(worst_qdd, 1e-12) << scene.name;
    EXPECT_LT(worst_lambda, 1e-12) << scene.name;
    EXPECT_LT(worst_violation, 1e-10) << scene.name;
  }
}

TEST(ForwardDynamicsWithContacts, MatchesTheDenseKktSolution) { check_forward_dynamics_with_contacts(false); }

TEST(ForwardDynamicsWithContacts, WithExternalForcesMatchesTheDenseKktSolution) { check_forward_dynamics_with_contacts(true); }

// Which solver each scene's λ goes through (contact_dynamics.hpp): the small Cholesky factors where the
// contacts are independent, the complete orthogonal decomposition (minimum-norm λ) where they are
// redundant or too few, so that the two tests above check both.
TEST(ContactSolvers, RedundantOrTooFewContactsTakeTheDecomposition) {
  struct Expected {
    const char* scene;
    bool id_gram, fd_cholesky;
  };
  const std::vector<Expected> expected = {{"talos two surface feet", true, true},
                                          {"talos redundant", true, false},  // B: full row rank; K: singular
                                          {"solo12 four point feet", true, true},
                                          {"solo12 two diagonal feet", false, true},  // B: rank 5
                                          {"floating double pendulum", false, true}};  // three rows
  unsigned seed = 41;
  for (const Scene& scene : scenes()) {
    const sd::Model<double> model = floating_robot(scene.urdf);
    const sd::ContactSet<double> contacts(model, scene.frames, scene.kinds);
    sd::Data<double> data(model);
    sd::ContactData<double> cd(model, contacts);
    std::mt19937 rng(seed++);
    const State x = random_state(model, rng);
    sd::inverse_dynamics_with_contacts(model, data, contacts, cd, x.q, x.qd, x.qdd);
    Eigen::Matrix<double, 6, 6> L6 = Eigen::Matrix<double, 6, 6>::Zero();
    const bool id_gram = contacts.rows >= 6 && sd::detail::gram_factor(cd.gram, L6, sd::detail::InertiaPattern{});
    sd::forward_dynamics_with_contacts(model, data, contacts, cd, x.q, x.qd, x.tau);
    MatrixXd L = MatrixXd::Zero(contacts.rows, contacts.rows);
    const bool fd_cholesky = sd::detail::gram_factor(cd.K, L, sd::detail::ChainPattern{contacts.rows});
    for (const Expected& e : expected) {
      if (scene.name != e.scene) continue;
      EXPECT_EQ(id_gram, e.id_gram) << scene.name;
      EXPECT_EQ(fd_cholesky, e.fd_cholesky) << scene.name;
    }
  }
}

TEST(Centroidal, CenterOfMassJacobianAndMomentumMatrixMatchDifferences) {
  unsigned seed = 31;
  for (const char* file : {"talos.urdf", "solo12.urdf", "double_pendulum.urdf"}) {
    const sd::Model<double> model = floating_robot(file);
    const sd::Model<Quad> oracle = sd_test::with_exact_rotations(model);
    sd::Data<double> data(model);
    std::mt19937 rng(seed++);
    auto com = [&](const std::vector<Mat6Q>& X0) { return sd_test::center_of_mass(oracle, X0); };
    double worst_c = 0, worst_J = 0, worst_A = 0, worst_cdot = 0;
    const Quad h(kStep);
    for (int s = 0; s < 3; ++s) {
      const State x = random_state(model, rng);
      const std::vector<Mat6Q> X0 = body_transforms(oracle, x.Q);
      const Vec3Q c = com(X0);
      MatQ J_com(3, model.nv);
      ref::Mat6X<Quad> A_G(6, model.nv);
      for (int k = 0; k < model.nv; ++k) {
        const VecQ e = VecQ::Unit(model.nv, k);
        const std::vector<Mat6Q> Xm = body_transforms(oracle, sd_test::advance(oracle, x.Q, e, -h));
        const std::vector<Mat6Q> Xp = body_transforms(oracle, sd_test::advance(oracle, x.Q, e, h));
        J_com.col(k) = (com(Xp) - com(Xm)) / (2 * h);
        ref::Vec6<Quad> h_0 = ref::Vec6<Quad>::Zero();  // Σ ^0X_i* I_i v_i, about the base origin
        for (int i = 1; i < oracle.nbodies(); ++i)
          h_0 += X0[i].transpose() * (ref::body_inertia(oracle, i) * velocity_from(Xm[i], X0[i], Xp[i], h));
        A_G.col(k) << h_0.head<3>() - c.cross(Vec3Q(h_0.tail<3>())), h_0.tail<3>();
      }
      worst_c = std::max(worst_c, sd::relative_error_to(sd::center_of_mass(model, data, x.q), c));
      worst_J = std::max(worst_J, sd::relative_error_to(sd::center_of_mass_jacobian(model, data, x.q), J_com));
      worst_A = std::max(worst_A, sd::relative_error_to(sd::centroidal_momentum_matrix(model, data, x.q), A_G));
      worst_cdot = std::max(worst_cdot, sd::relative_error_to(sd::center_of_mass_velocity(model, data, x.q, x.qd),
                                                              VecQ(J_com * x.Qd)));
      const sd::ForceVector<double> h_G = sd::centroidal_momentum(model, data, x.q, x.qd);
      EXPECT_LT(sd::relative_error_to(h_G.toVector(), VecQ(A_G * x.Qd)), 1e-10) << file;
    }
    std::printf("[%s floating] c: %.3g, J_com: %.3g, A_G: %.3g, ċ: %.3g\n", file, worst_c, worst_J, worst_A, worst_cdot);
    EXPECT_LT(worst_c, 1e-12) << file;
    EXPECT_LT(worst_J, 1e-10) << file;
    EXPECT_LT(worst_A, 1e-10) << file;
    EXPECT_LT(worst_cdot, 1e-10) << file;
  }
}

// Coupled joints (the Panda's second finger following the first) make M = Gᵀ M_free G, which the
// sparse factor does not take: forward dynamics with contacts then factors M densely. Its answer must
// satisfy the KKT system built from the library's own M, h and J_c (each checked against float128
// elsewhere): M q̈ + h = τ + J_cᵀ λ and J_c q̈ + J̇_c q̇ = 0.
TEST(ForwardDynamicsWithContacts, CoupledJointsSatisfyTheKktSystem) {
  sd::ModelBuildOptions options;
  options.floating_base = true;
  const sd::Model<double> model =
      sd::couple_mimic_joints(sd::build_model_from_urdf_file(sd_test::robot_path("panda.urdf"), options));
  ASSERT_TRUE(model.has_coupled_joints);
  const sd::ContactSet<double> contacts(model, {"panda_rightfinger"}, {"surface"});  // on the coupled finger
  sd::Data<double> data(model), check(model);
  sd::ContactData<double> cd(model, contacts), cd_check(model, contacts);
  std::mt19937 rng(41);
  double worst_dynamics = 0, worst_constraint = 0;
  for (int s = 0; s < 3; ++s) {
    const State x = random_state(model, rng);
    const VectorXd qdd = sd::forward_dynamics_with_contacts(model, data, contacts, cd, x.q, x.qd, x.tau);
    const VectorXd lambda = cd.lambda;
    const MatrixXd M = sd::crba(model, check, x.q);
    const VectorXd h = sd::nonlinear_effects(model, check, x.q, x.qd);
    const MatrixXd J = sd::contact_jacobian(model, check, contacts, cd_check, x.q, x.qd);
    worst_dynamics = std::max(worst_dynamics, (M * qdd + h - x.tau - J.transpose() * lambda).norm() /
                                                  (x.tau.norm() + h.norm() + (J.transpose() * lambda).norm()));
    worst_constraint = std::max(worst_constraint, (J * qdd + cd_check.acceleration).norm() /
                                                      std::max(1.0, cd_check.acceleration.norm()));
  }
  std::printf("[panda, coupled fingers] M q̈ + h − τ − J_cᵀ λ: %.3g, J_c q̈ + J̇_c q̇: %.3g\n", worst_dynamics,
              worst_constraint);
  EXPECT_LT(worst_dynamics, 1e-12);
  EXPECT_LT(worst_constraint, 1e-10);
}

TEST(Contacts, BadInputIsNamed) {
  const sd::Model<double> model = floating_robot("solo12.urdf");
  auto message = [&](const std::vector<std::string>& frames, const std::vector<std::string>& kinds,
                     const std::vector<double>& frictions) {
    try {
      sd::ContactSet<double> contacts(model, frames, kinds, frictions);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message({"FL_TOE"}, {"point"}, {}).find("unknown frame 'FL_TOE'"), std::string::npos);
  EXPECT_NE(message({"FL_FOOT"}, {"edge"}, {}).find("unknown kind 'edge'"), std::string::npos);
  EXPECT_NE(message({"FL_FOOT", "HR_FOOT"}, {"point"}, {}).find("2 frames but 1 kinds"), std::string::npos);
  EXPECT_NE(message({"FL_FOOT"}, {"point"}, {-0.5}).find("'FL_FOOT': the friction coefficient"), std::string::npos);
  EXPECT_NE(message({"FL_FOOT", "FL_FOOT"}, {"point", "point"}, {}).find("named twice"), std::string::npos);
  EXPECT_EQ(message({"FL_FOOT", "HR_FOOT"}, {"point", "surface"}, {0.7, 0.0}), "accepted");
}
