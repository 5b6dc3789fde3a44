// Actuator-level dynamics (algorithms/actuator_dynamics.hpp; the model's armature, damping,
// friction and friction_velocity): the friction law and a one-joint model against their written-out
// formulas; ID(FD(τ)) = τ with all four terms on every shared robot, fixed and floating, with
// coupled mimic joints and in a scene with locked joints; armature in RNEA, CRBA and ABA against
// the reference in float128; the URDF's <dynamics> and how reduction carries the terms; and zero
// terms that change nothing.
#include <gtest/gtest.h>

#include <cstdio>

#include <random>
#include <string>

#include "spatial_dynamics/algorithms/aba_refined.hpp"
#include "spatial_dynamics/algorithms/rnea_batch.hpp"
#include "spatial_dynamics/reduction/couple_mimic_joints.hpp"
#include "spatial_dynamics/reduction/reduce_model.hpp"
#include "spatial_dynamics/reference/forward_dynamics.hpp"
#include "spatial_dynamics/reference/high_precision.hpp"
#include "spatial_dynamics/reference/inverse_dynamics.hpp"
#include "spatial_dynamics/reference/mass_matrix.hpp"
#include "benchmark_actuators.hpp"  // bench/: random actuator terms
#include "test_utils.hpp"

namespace {

namespace sd = spatial_dynamics;
using Eigen::VectorXd;
using sd::Quad;

/// One revolute joint about z carrying a link whose centre of mass is on the axis: gravity (along
/// z) does no work, so τ = (I_zz + armature) q̈ + damping q̇ + friction ramp(q̇ / v_f).
const char* kOneJoint =
    "<robot name='one'><link name='base'/>"
    "<link name='arm'><inertial><origin xyz='0 0 0.2'/><mass value='2'/>"
    "<inertia ixx='0.2' iyy='0.2' izz='0.3' ixy='0' ixz='0' iyz='0'/></inertial></link>"
    "<joint name='j' type='continuous'><parent link='base'/><child link='arm'/><axis xyz='0 0 1'/>"
    "<dynamics damping='0.7' friction='1.5'/></joint></robot>";

TEST(ActuatorDynamics, CoulombFrictionFollowsTheWrittenOutLaw) {
  sd::Model<double> model = sd::build_model_from_urdf_string(kOneJoint);
  ASSERT_EQ(model.nv, 1);
  EXPECT_EQ(model.damping[0], 0.7);  // from <dynamics>
  EXPECT_EQ(model.friction[0], 1.5);
  EXPECT_EQ(model.friction_velocity[0], 1e-3);  // the default
  model.armature[0] = 0.2;
  model.friction_velocity[0] = 0.01;
  model.finalize();
  sd::Data<double> data(model);
  const double inertia = 0.3 + 0.2, b = 0.7, fc = 1.5, vf = 0.01, qdd = 1.3;
  VectorXd q(1), qd(1), a(1);
  q << 0.4;
  a << qdd;
  // Below v_f the friction ramps linearly through zero; at and above it, it is ±friction.
  for (const double v : {-2.0, -0.01, -0.004, 0.0, 0.003, 0.0099, 0.01, 0.5}) {
    qd << v;
    const double ramp = std::abs(v) >= vf ? (v > 0 ? 1.0 : -1.0) : v / vf;
    const double friction_and_damping = b * v + fc * ramp;
    EXPECT_NEAR(sd::actuator_forces(model, data, qd)[0], friction_and_damping, 1e-15) << "q̇ = " << v;
    EXPECT_NEAR(sd::actuator_effort(model, data, qd, a)[0], 0.2 * qdd + friction_and_damping, 1e-15) << "q̇ = " << v;
    const double tau = inertia * qdd + friction_and_damping;
    EXPECT_NEAR(sd::inverse_dynamics_actuated(model, data, q, qd, a)[0], tau, 1e-14) << "q̇ = " << v;
    VectorXd effort(1);
    effort << tau;
    EXPECT_NEAR(sd::forward_dynamics_actuated(model, data, q, qd, effort)[0], qdd, 1e-14) << "q̇ = " << v;
    // The rigid-body functions keep the armature only.
    EXPECT_NEAR(sd::rnea(model, data, q, qd, a)[0], inertia * qdd, 1e-14) << "q̇ = " << v;
  }
  // Continuous at ±v_f: the ramp meets the constant.
  qd << vf * (1 - 1e-12);
  const double below = sd::actuator_forces(model, data, qd)[0];
  qd << vf * (1 + 1e-12);
  EXPECT_NEAR(sd::actuator_forces(model, data, qd)[0], below, 1e-10);
}

using bench::randomize_actuators;  // armature 0–0.5, damping 0–2, friction 0–1, friction_velocity 1e-3–0.1

/// max over random states of ‖ID_actuated(q, q̇, FD_actuated(q, q̇, τ)) − τ‖ / ‖τ‖.
double worst_round_trip(const sd::Model<double>& model, std::mt19937& rng, int states = 20) {
  sd::Data<double> data(model);
  double worst = 0;
  for (int s = 0; s < states; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const VectorXd qd = sd_test::random_vector(model.nv, rng, 0.2);  // through the friction ramp and beyond
    const VectorXd tau = sd_test::random_vector(model.nv, rng, 20.0);
    const VectorXd qdd = sd::forward_dynamics_actuated(model, data, q, qd, tau);
    const VectorXd back = sd::inverse_dynamics_actuated(model, data, q, qd, qdd);
    worst = std::max(worst, sd_test::relative_error(back, tau));
  }
  return worst;
}

TEST(ActuatorDynamics, InverseOfForwardIsIdentityOnEveryRobot) {
  std::mt19937 rng(19);
  for (const std::string& file : sd_test::robot_files()) {
    for (const bool floating : {false, true}) {
      sd::ModelBuildOptions options;
      options.floating_base = floating;
      sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path(file), options);
      randomize_actuators(model, rng);
      const double worst = worst_round_trip(model, rng);
      std::printf("[actuators] %-22s %-8s ID(FD(tau)) vs tau, all four terms: %.2e\n", file.c_str(),
                  floating ? "floating" : "fixed", worst);
      EXPECT_LE(worst, 1e-12) << file << (floating ? " floating" : " fixed");
    }
  }
}

TEST(ActuatorDynamics, InverseOfForwardIsIdentityWithCoupledMimicJoints) {
  std::mt19937 rng(20);
  for (const char* file : {"panda.urdf", "talos.urdf"}) {
    sd::Model<double> model = sd::couple_mimic_joints(sd::build_model_from_urdf_file(sd_test::robot_path(file)));
    ASSERT_TRUE(model.has_coupled_joints) << file;
    randomize_actuators(model, rng);
    const double worst = worst_round_trip(model, rng);
    std::printf("[actuators] %-22s coupled  ID(FD(tau)) vs tau, all four terms: %.2e\n", file, worst);
    EXPECT_LE(worst, 1e-12) << file;
  }
}

TEST(ActuatorDynamics, InverseOfForwardIsIdentityInASceneWithLockedJoints) {
  std::mt19937 rng(21);
  sd::ModelBuildOptions options;
  options.floating_base = true;
  sd::Model<double> full = sd::build_model_from_urdf_file(sd_test::robot_path("talos.urdf"), options);
  randomize_actuators(full, rng);
  sd::Scene scene;
  for (int i = 2; i < full.nbodies(); ++i) {
    const std::string& name = full.joint_names[i];
    if (name.rfind("arm_left_", 0) == 0) scene.kept_joints.push_back(name);
    else if (name.rfind("leg_", 0) == 0) scene.locked_positions[name] = 0.1;
  }
  const sd::Model<double> reduced = sd::reduce_model(full, scene);
  ASSERT_GT(reduced.nv, 6);
  ASSERT_LT(reduced.nv, full.nv);
  // The kept joints keep their terms; the root's stay zero.
  for (const std::string& name : scene.kept_joints) {
    const int kept = reduced.joints[reduced.jointBody(name)].idx_v, original = full.joints[full.jointBody(name)].idx_v;
    EXPECT_EQ(reduced.armature[kept], full.armature[original]) << name;
    EXPECT_EQ(reduced.damping[kept], full.damping[original]) << name;
    EXPECT_EQ(reduced.friction[kept], full.friction[original]) << name;
    EXPECT_EQ(reduced.friction_velocity[kept], full.friction_velocity[original]) << name;
  }
  EXPECT_TRUE(reduced.has_armature);
  const double worst = worst_round_trip(reduced, rng);
  std::printf("[actuators] talos left-arm scene, legs locked: ID(FD(tau)) vs tau, all four terms: %.2e\n", worst);
  EXPECT_LE(worst, 1e-12);
}

TEST(ActuatorDynamics, ArmatureAgreesWithTheReferenceInFloat128) {
  std::mt19937 rng(22);
  for (const std::string& file : sd_test::robot_files()) {
    sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path(file));
    randomize_actuators(model, rng);
    const sd::Model<Quad> model_q = model.cast<Quad>();
    sd::Data<double> data(model);
    double worst_id = 0, worst_m = 0, worst_fd = 0;
    for (int s = 0; s < 10; ++s) {
      const VectorXd q = sd_test::random_configuration(model, rng);
      const VectorXd qd = sd_test::random_vector(model.nv, rng);
      const VectorXd qdd = sd_test::random_vector(model.nv, rng);
      const VectorXd tau = sd_test::random_vector(model.nv, rng, 20.0);
      const auto q_q = sd::to_quad(q), qd_q = sd::to_quad(qd);
      worst_id = std::max(worst_id, sd::relative_error_to(sd::rnea(model, data, q, qd, qdd),
                                                          sd::reference::inverse_dynamics(model_q, q_q, qd_q, sd::to_quad(qdd))));
      worst_m = std::max(worst_m, sd::relative_error_to(sd::crba(model, data, q), sd::reference::mass_matrix(model_q, q_q)));
      worst_fd = std::max(worst_fd, sd::relative_error_to(sd::aba(model, data, q, qd, tau),
                                                          sd::reference::forward_dynamics(model_q, q_q, qd_q, sd::to_quad(tau))));
    }
    EXPECT_LE(worst_id, 4e-15) << file;
    EXPECT_LE(worst_m, 4e-15) << file;
    EXPECT_LE(worst_fd, 1e-12) << file;
  }
}

TEST(ActuatorDynamics, ArmatureIsPartOfTheMassMatrixAndTheKineticEnergy) {
  std::mt19937 rng(23);
  sd::Model<double> rigid = sd::build_model_from_urdf_file(sd_test::robot_path("ur5.urdf"));
  sd::Model<double> model = rigid;
  randomize_actuators(model, rng);
  sd::Data<double> data(model), rigid_data(rigid);
  const VectorXd q = sd_test::random_configuration(model, rng), qd = sd_test::random_vector(model.nv, rng);
  const Eigen::MatrixXd M = sd::crba(model, data, q);
  Eigen::MatrixXd expected = sd::crba(rigid, rigid_data, q);
  for (int k = 0; k < model.nv; ++k) expected(k, k) += model.armature[k];
  EXPECT_LE((M - expected).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_NEAR(sd::kinetic_energy(model, data, q, qd), 0.5 * qd.dot(expected * qd), 1e-13);
}

TEST(ActuatorDynamics, BatchAndRefinementIncludeTheArmature) {
  std::mt19937 rng(25);
  for (const char* file : {"ur5.urdf", "talos.urdf"}) {
    sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path(file));
    randomize_actuators(model, rng);
    sd::Data<double> data(model);
    sd::BatchData<double> batch(model);
    sd::RefinementWorkspace<double> refinement(model);
    const int n = 7;  // a partial last block of lanes
    Eigen::MatrixXd Q(model.nq, n), QD(model.nv, n), QDD(model.nv, n), T(model.nv, n);
    for (int c = 0; c < n; ++c) {
      Q.col(c) = sd_test::random_configuration(model, rng);
      QD.col(c) = sd_test::random_vector(model.nv, rng);
      QDD.col(c) = sd_test::random_vector(model.nv, rng);
    }
    sd::rnea_batch(model, batch, Q, QD, QDD, T);
    for (int c = 0; c < n; ++c) {
      const VectorXd tau = sd::rnea(model, data, Q.col(c), QD.col(c), QDD.col(c));
      EXPECT_LE(sd_test::relative_error(T.col(c), tau), 1e-14) << file << " state " << c;
      const VectorXd qdd = sd::aba_refined(model, data, refinement, Q.col(c), QD.col(c), tau);
      EXPECT_LE(sd_test::relative_error(qdd, QDD.col(c)), 1e-13) << file << " state " << c;
    }
  }
}

TEST(ActuatorDynamics, ZeroTermsChangeNothing) {
  std::mt19937 rng(24);
  const sd::Model<double> plain = sd::build_model_from_urdf_file(sd_test::robot_path("panda.urdf"));
  sd::Model<double> zeroed = plain;
  randomize_actuators(zeroed, rng);
  zeroed.armature.assign(zeroed.nv, 0.0);
  zeroed.damping.assign(zeroed.nv, 0.0);
  zeroed.friction.assign(zeroed.nv, 0.0);
  zeroed.finalize();
  EXPECT_FALSE(zeroed.has_armature);
  sd::Data<double> a(plain), b(zeroed);
  for (int s = 0; s < 5; ++s) {
    const VectorXd q = sd_test::random_configuration(plain, rng);
    const VectorXd qd = sd_test::random_vector(plain.nv, rng), qdd = sd_test::random_vector(plain.nv, rng);
    const VectorXd tau = sd::rnea(plain, a, q, qd, qdd);
    EXPECT_TRUE(tau == sd::rnea(zeroed, b, q, qd, qdd));
    EXPECT_TRUE(tau == sd::inverse_dynamics_actuated(zeroed, b, q, qd, qdd));
    const VectorXd qdd_back = sd::aba(plain, a, q, qd, tau);
    EXPECT_TRUE(qdd_back == sd::aba(zeroed, b, q, qd, tau));
    EXPECT_TRUE(qdd_back == sd::forward_dynamics_actuated(zeroed, b, q, qd, tau));
    EXPECT_TRUE(sd::crba(plain, a, q) == sd::crba(zeroed, b, q));
  }
}

TEST(ActuatorDynamics, UrdfDynamicsAndCouplingCarryTheTerms) {
  // A mimic joint with <dynamics> of its own: coupled, it has its master's coordinate and terms.
  const std::string urdf =
      "<robot name='r'><link name='a'/>"
      "<link name='b'><inertial><mass value='1'/><inertia ixx='1' iyy='1' izz='1' ixy='0' ixz='0' iyz='0'/></inertial></link>"
      "<link name='c'><inertial><mass value='1'/><inertia ixx='1' iyy='1' izz='1' ixy='0' ixz='0' iyz='0'/></inertial></link>"
      "<joint name='master' type='revolute'><parent link='a'/><child link='b'/><axis xyz='0 0 1'/>"
      "<limit lower='-1' upper='1' effort='10' velocity='1'/><dynamics damping='0.25' friction='0.5'/></joint>"
      "<joint name='follower' type='prismatic'><parent link='b'/><child link='c'/><axis xyz='1 0 0'/>"
      "<limit lower='-1' upper='1' effort='10' velocity='1'/><mimic joint='master' multiplier='2'/>"
      "<dynamics damping='3'/></joint></robot>";
  const sd::Model<double> independent = sd::build_model_from_urdf_string(urdf);
  ASSERT_EQ(independent.nv, 2);
  EXPECT_EQ(independent.damping, std::vector<double>({0.25, 3.0}));
  EXPECT_EQ(independent.friction, std::vector<double>({0.5, 0.0}));
  const sd::Model<double> coupled = sd::couple_mimic_joints(independent);
  ASSERT_EQ(coupled.nv, 1);
  EXPECT_EQ(coupled.damping[0], 0.25);
  EXPECT_EQ(coupled.friction[0], 0.5);
}

TEST(ActuatorDynamics, BadTermsAreRefusedNamingTheCulprit) {
  std::string with_negative = kOneJoint;
  with_negative.replace(with_negative.find("damping='0.7'"), 13, "damping='-1'");
  try {
    sd::build_model_from_urdf_string(with_negative);
    ADD_FAILURE() << "a negative damping was accepted";
  } catch (const sd::ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("damping"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("joint 'j'"), std::string::npos) << e.what();
  }
  sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path("ur5.urdf"));
  const std::string name = model.velocityNames()[2];
  for (const auto& [term, value] : {std::pair<std::string, double>{"armature", -0.1}, {"friction", std::nan("")},
                                    {"friction_velocity", 0.0}, {"damping", INFINITY}}) {
    sd::Model<double> bad = model;
    std::vector<double>& values = term == "armature" ? bad.armature
                       : term == "friction" ? bad.friction
                       : term == "damping"  ? bad.damping
                                            : bad.friction_velocity;
    values[2] = value;
    try {
      bad.finalize();
      ADD_FAILURE() << term << " = " << value << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("'" + name + "'"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(term), std::string::npos) << e.what();
    }
  }
}

}  // namespace
