// The reference implementation (include/spatial_dynamics/reference/: RNEA, CRBA and ABA on 6×6
// matrices, RBDA Tables 5.1, 6.2 and 7.1) that the accuracy tests take as their float128 oracle:
//  - in float128 it agrees with the library's own algorithms in float128 to 1e-28 relative on
//    every bundled robot (fixed base; talos and solo12 also floating) and on synthetic models,
//    coupled mimic joints included: two independent implementations of the same equations (on
//    the model with its rotations made orthogonal in float128, with_exact_rotations);
//  - the library in double is within 4e-15 of it for RNEA and CRBA, and its ABA within the
//    bounds test_gravity_split.cpp sets on the robots it lists;
//  - its own identities hold: ID(FD(τ)) = τ, M symmetric positive definite and M q̈ = ID(q, q̇, q̈) −
//    ID(q, q̇, 0), and closed forms of a one-link pendulum and of a free-flying body.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "random_states.hpp"  // bench/: the benchmark's states, on which test_gravity_split's bounds are set
#include "spatial_dynamics/reduction/couple_mimic_joints.hpp"
#include "spatial_dynamics/reference/forward_dynamics.hpp"
#include "spatial_dynamics/reference/high_precision.hpp"
#include "spatial_dynamics/reference/inverse_dynamics.hpp"
#include "spatial_dynamics/reference/mass_matrix.hpp"
#include "spatial_dynamics/synthetic/random_robot.hpp"
#include "synthetic_robots.hpp"
#include "exact_rotations.hpp"
#include "test_utils.hpp"

namespace sd = spatial_dynamics;
namespace ref = spatial_dynamics::reference;
using sd::Quad;
using Eigen::VectorXd;
using VectorQ = sd::VectorX<Quad>;
using MatrixQ = sd::MatrixX<Quad>;

namespace {

constexpr double kAgreement = 1e-28;  // two float128 implementations (ε = 1.9e-34)
constexpr double kDouble = 4e-15;     // the library's RNEA and CRBA in double

struct Case {
  std::string name;
  sd::Model<double> model;
};

sd::Model<double> robot(const std::string& file, bool floating) {
  sd::ModelBuildOptions options;
  options.floating_base = floating;
  return sd::build_model_from_urdf_file(sd_test::robot_path(file), options);
}

/// Every bundled robot with a fixed base, talos and solo12 also with a floating one.
std::vector<Case> bundled_robots() {
  std::vector<Case> cases;
  for (const std::string& file : sd_test::robot_files()) cases.push_back({file + " fixed", robot(file, false)});
  for (const char* file : {"talos.urdf", "solo12.urdf"})
    cases.push_back({std::string(file) + " floating", robot(file, true)});
  return cases;
}

/// Random external forces on every body but the base, ‖f‖ ~ `scale`.
std::vector<sd::ForceVector<Quad>> random_forces(int nbodies, std::mt19937& rng, double scale) {
  std::vector<sd::ForceVector<Quad>> f(nbodies, sd::ForceVector<Quad>::Zero());
  for (int i = 1; i < nbodies; ++i)
    f[i] = sd::ForceVector<Quad>(sd::Vector6<Quad>(sd::to_quad(sd_test::random_vector(6, rng, scale))));
  return f;
}

/// A random state (q within the joint limits, q̇ and q̈ in (−1, 1)), converted exactly; with
/// `unit_quaternions`, a free joint's quaternion is normalised again in float128.
struct StateQ {
  VectorQ q, qd, qdd;
};
StateQ random_state(const sd::Model<double>& model, std::mt19937& rng, bool unit_quaternions = false) {
  StateQ x;
  x.q = sd::to_quad(sd_test::random_configuration(model, rng));
  x.qd = sd::to_quad(sd_test::random_vector(model.nv, rng));
  x.qdd = sd::to_quad(sd_test::random_vector(model.nv, rng));
  for (int i = 1; unit_quaternions && i < model.nbodies(); ++i)
    if (model.joints[i].type == sd::JointType::Free) x.q.segment<4>(model.joints[i].idx_q + 3).normalize();
  return x;
}

using sd_test::with_exact_rotations;

struct Agreement {
  double rnea = 0, rnea_ext = 0, crba = 0, aba = 0, aba_ext = 0;
};

/// The reference against the library, both in float128, over `states` random states.
Agreement agreement_in_float128(const sd::Model<double>& model_d, int states, unsigned seed) {
  const sd::Model<Quad> model = with_exact_rotations(model_d);
  sd::Data<Quad> data(model);
  std::mt19937 rng(seed);
  Agreement w;
  for (int s = 0; s < states; ++s) {
    const StateQ x = random_state(model_d, rng, true);
    const std::vector<sd::ForceVector<Quad>> f_ext = random_forces(model.nbodies(), rng, 5.0);
    const VectorQ tau = ref::inverse_dynamics(model, x.q, x.qd, x.qdd);
    w.rnea = std::max(w.rnea, sd::relative_error_to(sd::rnea(model, data, x.q, x.qd, x.qdd), tau));
    const VectorQ tau_ext = ref::inverse_dynamics(model, x.q, x.qd, x.qdd, f_ext);
    w.rnea_ext = std::max(w.rnea_ext, sd::relative_error_to(sd::rnea(model, data, x.q, x.qd, x.qdd, f_ext), tau_ext));
    w.crba = std::max(w.crba, sd::relative_error_to(sd::crba(model, data, x.q), ref::mass_matrix(model, x.q)));
    if (model.has_coupled_joints) {
      EXPECT_THROW(ref::forward_dynamics(model, x.q, x.qd, tau), std::invalid_argument);
      continue;
    }
    const VectorQ qdd = ref::forward_dynamics(model, x.q, x.qd, tau);
    w.aba = std::max(w.aba, sd::relative_error_to(sd::aba(model, data, x.q, x.qd, tau), qdd));
    const VectorQ qdd_ext = ref::forward_dynamics(model, x.q, x.qd, tau, f_ext);
    w.aba_ext = std::max(w.aba_ext, sd::relative_error_to(sd::aba(model, data, x.q, x.qd, tau, f_ext), qdd_ext));
  }
  return w;
}

void expect_agreement(const std::string& name, const sd::Model<double>& model, int states, unsigned seed) {
  const Agreement w = agreement_in_float128(model, states, seed);
  std::printf("[float128 agreement] %-36s RNEA %8.2g  with f_ext %8.2g  CRBA %8.2g  ABA %8.2g  with f_ext %8.2g\n",
              name.c_str(), w.rnea, w.rnea_ext, w.crba, w.aba, w.aba_ext);
  EXPECT_LE(w.rnea, kAgreement) << name;
  EXPECT_LE(w.rnea_ext, kAgreement) << name;
  EXPECT_LE(w.crba, kAgreement) << name;
  EXPECT_LE(w.aba, kAgreement) << name;
  EXPECT_LE(w.aba_ext, kAgreement) << name;
}

sd::Model<double> from_links(const std::string& name, const std::vector<sd::synthetic::Link>& links, bool floating) {
  sd::ModelBuildOptions options;
  options.floating_base = floating;
  return sd::build_model_from_urdf_string(sd::synthetic::to_urdf(name, links), options);
}

}  // namespace

TEST(ReferenceInFloat128, AgreesWithTheLibraryOnTheBundledRobots) {
  unsigned seed = 1;
  for (const Case& c : bundled_robots()) expect_agreement(c.name, c.model, 20, seed++);
  // panda's fingers mimic each other: coupled, one coordinate for both (ABA refused by both).
  expect_agreement("panda.urdf coupled fingers", sd::couple_mimic_joints(robot("panda.urdf", false)), 20, 10);
}

TEST(ReferenceInFloat128, AgreesWithTheLibraryOnSyntheticModels) {
  // The mobile manipulator (prismatic lift and fingers, random axes, a finger mimicking the other
  // with multiplier −1), independent and coupled; a 30-body random chain; a floating random tree.
  const sd::Model<double> manipulator = sd::build_model_from_urdf_string(sd_test::mobile_manipulator_urdf(7));
  expect_agreement("mobile manipulator", manipulator, 20, 21);
  expect_agreement("mobile manipulator coupled", sd::couple_mimic_joints(manipulator), 20, 22);
  std::mt19937 rng(23);
  expect_agreement("30-body random chain", from_links("chain", sd::synthetic::random_chain(30, rng), false), 10, 24);
  expect_agreement("20-body floating random tree", from_links("tree", sd::synthetic::random_tree(20, rng), true), 10,
                   25);
}

TEST(LibraryInDouble, RneaAndCrbaWithin4e15OfTheReference) {
  unsigned seed = 31;
  for (const Case& c : bundled_robots()) {
    const sd::Model<Quad> model_q = c.model.cast<Quad>();
    sd::Data<double> data(c.model);
    std::mt19937 rng(seed++);
    double rnea = 0, crba = 0;
    for (int s = 0; s < 100; ++s) {
      const VectorXd q = sd_test::random_configuration(c.model, rng);
      const VectorXd qd = sd_test::random_vector(c.model.nv, rng), qdd = sd_test::random_vector(c.model.nv, rng);
      const VectorQ Q = sd::to_quad(q);
      const VectorQ tau = ref::inverse_dynamics(model_q, Q, sd::to_quad(qd), sd::to_quad(qdd));
      rnea = std::max(rnea, sd::relative_error_to(sd::rnea(c.model, data, q, qd, qdd), tau));
      crba = std::max(crba, sd::relative_error_to(sd::crba(c.model, data, q), ref::mass_matrix(model_q, Q)));
    }
    std::printf("[double against the reference] %-22s RNEA %8.2g  CRBA %8.2g  (bound %.0e)\n", c.name.c_str(), rnea,
                crba, kDouble);
    EXPECT_LE(rnea, kDouble) << c.name;
    EXPECT_LE(crba, kDouble) << c.name;
  }
}

TEST(LibraryInDouble, AbaWithinTheGravitySplitBounds) {
  // The robots and bounds of test_gravity_split.cpp (the anchors' FD errors on the benchmark's
  // states), on the same benchmark states.
  struct Row {
    const char* file;
    bool floating;
    double bound;
  };
  const std::vector<Row> rows = {{"panda.urdf", false, 3.9e-14},  {"ur5.urdf", false, 1.8e-14},
                                 {"talos.urdf", false, 9.2e-14},  {"solo12.urdf", true, 1.35e-13},
                                 {"talos.urdf", true, 8.2e-13}};
  for (const Row& r : rows) {
    const sd::Model<double> model = robot(r.file, r.floating);
    const sd::Model<Quad> model_q = model.cast<Quad>();
    sd::Data<double> data(model);
    double worst = 0;
    for (const bench::State& st : bench::random_states(model, 300, 12345)) {
      const VectorQ expected =
          ref::forward_dynamics(model_q, sd::to_quad(st.q), sd::to_quad(st.qd), sd::to_quad(st.tau));
      worst = std::max(worst, sd::relative_error_to(sd::aba(model, data, st.q, st.qd, st.tau), expected));
    }
    std::printf("[double against the reference] %s %s: ABA %8.2g (bound %.3g)\n", r.file,
                r.floating ? "floating" : "fixed", worst, r.bound);
    EXPECT_LE(worst, r.bound) << r.file;
  }
}

TEST(ReferenceIdentities, InverseDynamicsUndoesForwardDynamics) {
  std::vector<Case> cases = bundled_robots();
  std::mt19937 tree_rng(41);
  cases.push_back({"20-body floating random tree", from_links("tree", sd::synthetic::random_tree(20, tree_rng), true)});
  unsigned seed = 42;
  for (const Case& c : cases) {
    const sd::Model<Quad> model = c.model.cast<Quad>();
    std::mt19937 rng(seed++);
    double worst = 0, worst_ext = 0;
    for (int s = 0; s < 10; ++s) {
      const StateQ x = random_state(c.model, rng);
      const VectorQ tau = sd::to_quad(sd_test::random_vector(c.model.nv, rng, 10.0));
      const VectorQ qdd = ref::forward_dynamics(model, x.q, x.qd, tau);
      worst = std::max(worst, sd::relative_error_to(ref::inverse_dynamics(model, x.q, x.qd, qdd), tau));
      const std::vector<sd::ForceVector<Quad>> f_ext = random_forces(model.nbodies(), rng, 5.0);
      const VectorQ qdd_ext = ref::forward_dynamics(model, x.q, x.qd, tau, f_ext);
      const VectorQ tau_ext = ref::inverse_dynamics(model, x.q, x.qd, qdd_ext, f_ext);
      worst_ext = std::max(worst_ext, sd::relative_error_to(tau_ext, tau));
    }
    std::printf("[ID(FD(tau)) = tau] %-36s %8.2g  with f_ext %8.2g\n", c.name.c_str(), worst, worst_ext);
    EXPECT_LE(worst, kAgreement) << c.name;
    EXPECT_LE(worst_ext, kAgreement) << c.name;
  }
}

TEST(ReferenceIdentities, MassMatrixIsSymmetricPositiveDefiniteAndMatchesInverseDynamics) {
  std::vector<Case> cases = bundled_robots();
  cases.push_back({"panda.urdf coupled fingers", sd::couple_mimic_joints(robot("panda.urdf", false))});
  const sd::Model<double> manipulator = sd::build_model_from_urdf_string(sd_test::mobile_manipulator_urdf(7));
  cases.push_back({"mobile manipulator coupled", sd::couple_mimic_joints(manipulator)});
  unsigned seed = 51;
  for (const Case& c : cases) {
    const sd::Model<Quad> model = c.model.cast<Quad>();
    std::mt19937 rng(seed++);
    double asymmetry = 0, consistency = 0, smallest = 1e300;
    for (int s = 0; s < 10; ++s) {
      const StateQ x = random_state(c.model, rng);
      const MatrixQ M = ref::mass_matrix(model, x.q);
      asymmetry = std::max(asymmetry, sd::relative_error_to(M.transpose(), M));
      EXPECT_EQ(Eigen::LLT<MatrixQ>(M).info(), Eigen::Success) << c.name;
      const Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic> Ml = M.cast<long double>();
      const auto lambda = Eigen::SelfAdjointEigenSolver<decltype(Ml)>(Ml, Eigen::EigenvaluesOnly).eigenvalues();
      smallest = std::min(smallest, static_cast<double>(lambda.minCoeff() / lambda.maxCoeff()));
      // M q̈ = ID(q, q̇, q̈) − ID(q, q̇, 0): the CRBA against the RNEA (RBDA eq. 5.1).
      const VectorQ Mqdd = ref::inverse_dynamics(model, x.q, x.qd, x.qdd) - ref::nonlinear_effects(model, x.q, x.qd);
      consistency = std::max(consistency, sd::relative_error_to(VectorQ(M * x.qdd), Mqdd));
    }
    std::printf("[M] %-36s asymmetry %8.2g  M q̈ against ID %8.2g  smallest λ/largest %8.2g\n", c.name.c_str(),
                asymmetry, consistency, smallest);
    EXPECT_LE(asymmetry, kAgreement) << c.name;
    EXPECT_LE(consistency, kAgreement) << c.name;
    EXPECT_GT(smallest, 0.0) << c.name;
  }
}

TEST(ReferenceClosedForms, OneLinkPendulum) {
  // A link of mass m on a revolute joint about y, its centre of mass a distance l below the axis
  // (c = (0, 0, −l) at θ = 0) and rotational inertia I_yy about it; gravity (0, 0, −g). Rotating by
  // θ about y puts c at (−l sin θ, 0, −l cos θ): potential V = −m g l cos θ, kinetic energy
  // ½ (I_yy + m l²) θ̇², so Lagrange's equation is τ = (I_yy + m l²) θ̈ + m g l sin θ, with no
  // velocity term for one degree of freedom.
  const std::string urdf =
      "<robot name='pendulum'><link name='base'/>"
      "<link name='bob'><inertial><origin xyz='0 0 -0.75'/><mass value='2.5'/>"
      "<inertia ixx='0.0625' ixy='0' ixz='0' iyy='0.0625' iyz='0' izz='0.03125'/></inertial></link>"
      "<joint name='hinge' type='continuous'><parent link='base'/><child link='bob'/><axis xyz='0 1 0'/></joint>"
      "</robot>";
  const sd::Model<Quad> model = sd::build_model_from_urdf_string(urdf).cast<Quad>();
  ASSERT_EQ(model.nv, 1);
  const Quad m = 2.5, l = 0.75, Iyy = 0.0625, g = -model.gravity.z();
  const Quad inertia = Iyy + m * l * l;
  std::mt19937 rng(61);
  double worst = 0;
  for (int s = 0; s < 20; ++s) {
    const VectorQ theta = sd::to_quad(sd_test::random_vector(1, rng, M_PI));
    const VectorQ theta_d = sd::to_quad(sd_test::random_vector(1, rng, 3.0));
    const VectorQ theta_dd = sd::to_quad(sd_test::random_vector(1, rng, 3.0));
    const Quad gravity_term = m * g * l * sin(theta[0]);
    const VectorQ tau = VectorQ::Constant(1, inertia * theta_dd[0] + gravity_term);
    worst = std::max(worst, sd::relative_error_to(ref::inverse_dynamics(model, theta, theta_d, theta_dd), tau));
    worst = std::max(worst, sd::relative_error_to(ref::mass_matrix(model, theta), MatrixQ::Constant(1, 1, inertia)));
    worst = std::max(worst, sd::relative_error_to(ref::forward_dynamics(model, theta, theta_d, tau), theta_dd));
  }
  std::printf("[pendulum] worst relative error of ID, M and FD against the closed form %.2g\n", worst);
  EXPECT_LE(worst, kAgreement);
}

TEST(ReferenceClosedForms, FreeFlyingBody) {
  // A free body with its centre of mass at its origin and rotational inertia J, left to gravity
  // (τ = 0): in body coordinates q̇ = (ω; v) and R the body's orientation, Euler's and Newton's
  // equations J ω̇ + ω × J ω = 0 and v̇ + ω × v = Rᵀ g give q̈ = (J⁻¹(−ω × J ω); Rᵀ g − ω × v).
  const std::string urdf =
      "<robot name='brick'><link name='brick'><inertial><mass value='3'/>"
      "<inertia ixx='0.5' ixy='0.0625' ixz='-0.125' iyy='0.75' iyz='0.03125' izz='1'/></inertial></link></robot>";
  sd::ModelBuildOptions options;
  options.floating_base = true;
  const sd::Model<double> model_d = sd::build_model_from_urdf_string(urdf, options);
  const sd::Model<Quad> model = model_d.cast<Quad>();
  ASSERT_EQ(model.nv, 6);
  const sd::Matrix3<Quad> J = model.inertia[1].rotational_inertia;
  std::mt19937 rng(62);
  double worst = 0;
  for (int s = 0; s < 20; ++s) {
    const VectorQ q = random_state(model_d, rng, true).q;  // a unit quaternion in float128
    const VectorQ qd = sd::to_quad(sd_test::random_vector(6, rng, 2.0));
    const Eigen::Quaternion<Quad> orientation(q[6], q[3], q[4], q[5]);
    const sd::Vector3<Quad> w = qd.head<3>(), v = qd.tail<3>();
    VectorQ expected(6);
    expected.head<3>() = J.llt().solve(sd::Vector3<Quad>(-w.cross(J * w)));
    expected.tail<3>() = orientation.toRotationMatrix().transpose() * model.gravity - w.cross(v);
    const VectorQ zero = VectorQ::Zero(6);
    worst = std::max(worst, sd::relative_error_to(ref::forward_dynamics(model, q, qd, zero), expected));
    worst = std::max(worst, static_cast<double>(ref::inverse_dynamics(model, q, qd, expected).norm()));
  }
  std::printf("[free body] worst error of FD (relative) and ID (absolute, N and N m) %.2g\n", worst);
  EXPECT_LE(worst, kAgreement);
}
