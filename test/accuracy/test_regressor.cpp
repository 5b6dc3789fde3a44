// The inertial-parameter regressors (algorithms/regressor.hpp) against the reference's inverse
// dynamics in float128 (reference/: RNEA on 6×6 matrices):
//  - Y π + armature ⊙ q̈ = ID(q, q̇, q̈) (≤ 1e-13 relative) on every bundled robot (fixed; talos and
//    solo12 also floating), the panda with coupled fingers and the mobile manipulator coupled, with
//    armature;
//  - a payload's columns Y_P π_P = ID with the payload attached − ID without (≤ 1e-13 relative to
//    that difference), on frames fixed to bodies at the root, in the middle and at the tips;
//  - the actuator columns times (armature, damping, friction) = actuator_effort;
//  - inertial_parameters() and set_inertial_parameters() round trip, and the setter refuses bodies
//    that are not physical, naming the link.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "spatial_dynamics/algorithms/actuator_dynamics.hpp"
#include "spatial_dynamics/algorithms/regressor.hpp"
#include "spatial_dynamics/reduction/couple_mimic_joints.hpp"
#include "spatial_dynamics/reduction/payload.hpp"
#include "spatial_dynamics/reference/high_precision.hpp"
#include "spatial_dynamics/reference/inverse_dynamics.hpp"
#include "exact_rotations.hpp"
#include "synthetic_robots.hpp"
#include "test_utils.hpp"

namespace sd = spatial_dynamics;
namespace ref = spatial_dynamics::reference;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using sd::Quad;
using VectorQ = sd::VectorX<Quad>;

namespace {

struct Case {
  std::string name;
  sd::Model<double> model;
};

sd::Model<double> robot(const std::string& file, bool floating) {
  sd::ModelBuildOptions options;
  options.floating_base = floating;
  return sd::build_model_from_urdf_file(sd_test::robot_path(file), options);
}

std::vector<Case> cases() {
  std::vector<Case> out;
  for (const std::string& file : sd_test::robot_files()) out.push_back({file + " fixed", robot(file, false)});
  for (const char* file : {"talos.urdf", "solo12.urdf"}) out.push_back({std::string(file) + " floating", robot(file, true)});
  out.push_back({"panda.urdf coupled fingers", sd::couple_mimic_joints(robot("panda.urdf", false))});
  sd::Model<double> manipulator = sd::couple_mimic_joints(sd::build_model_from_urdf_string(sd_test::mobile_manipulator_urdf(7)));
  for (int k = 0; k < manipulator.nv; ++k) manipulator.armature[k] = 0.05 * (k + 1);
  manipulator.finalize();
  out.push_back({"mobile manipulator coupled, armature", manipulator});
  return out;
}

struct State {
  VectorXd q, qd, qdd;
  VectorQ Q, Qd, Qdd;  // the same state in float128 (a free joint's quaternion of unit length there)
};

State random_state(const sd::Model<double>& model, const sd::Model<Quad>& model_q, std::mt19937& rng) {
  State s;
  s.q = sd_test::random_configuration(model, rng);
  s.Q = sd::to_quad(s.q);
  for (int i = 1; i < model_q.nbodies(); ++i)
    if (model_q.joints[i].type == sd::JointType::Free) s.Q.segment<4>(model_q.joints[i].idx_q + 3).normalize();
  s.q = s.Q.cast<double>();
  s.qd = sd_test::random_vector(model.nv, rng);
  s.qdd = sd_test::random_vector(model.nv, rng);
  s.Qd = sd::to_quad(s.qd);
  s.Qdd = sd::to_quad(s.qdd);
  return s;
}

/// A physical payload: mass 0.5–3 kg, centre of mass within 0.15 m, principal moments that meet the
/// triangle inequality, turned by a random rotation.
sd::Payload random_payload(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0), offset(-0.15, 0.15);
  sd::Payload p;
  p.mass = 0.5 + 2.5 * unit(rng);
  p.center_of_mass = Eigen::Vector3d(offset(rng), offset(rng), offset(rng));
  const Eigen::Vector3d moments(0.02 + 0.02 * unit(rng), 0.02 + 0.02 * unit(rng), 0.0);  // within a factor 2
  const Eigen::Vector3d principal(moments[0], moments[1], 0.5 * (moments[0] + moments[1]));
  const Eigen::Matrix3d R = Eigen::Quaterniond::UnitRandom().toRotationMatrix();
  p.inertia = R * principal.asDiagonal() * R.transpose();
  return p;
}

/// Frames on the first, a middle and the last body.
std::vector<std::string> payload_frames(const sd::Model<double>& model) {
  std::vector<std::string> names;
  for (int body : {1, model.nbodies() / 2, model.nbodies() - 1})
    for (const sd::Frame<double>& f : model.frames)
      if (f.body == body) {
        names.push_back(f.name);
        break;
      }
  return names;
}

}  // namespace

TEST(JointTorqueRegressor, TimesParametersIsTheReferenceInverseDynamics) {
  unsigned seed = 1;
  for (const Case& c : cases()) {
    const sd::Model<Quad> oracle = sd_test::with_exact_rotations(c.model);
    sd::Data<double> data(c.model);
    std::mt19937 rng(seed++);
    const VectorXd pi = c.model.inertial_parameters();
    VectorXd armature(c.model.nv);
    for (int k = 0; k < c.model.nv; ++k) armature[k] = c.model.armature[k];
    double worst = 0;
    for (int s = 0; s < 10; ++s) {
      const State x = random_state(c.model, oracle, rng);
      const MatrixXd& Y = sd::joint_torque_regressor(c.model, data, x.q, x.qd, x.qdd);
      ASSERT_EQ(Y.rows(), c.model.nv);
      ASSERT_EQ(Y.cols(), 10 * (c.model.nbodies() - 1));
      const VectorXd tau = Y * pi + armature.cwiseProduct(x.qdd);
      worst = std::max(worst, sd::relative_error_to(tau, ref::inverse_dynamics(oracle, x.Q, x.Qd, x.Qdd)));
    }
    std::printf("[regressor] %-40s Y π vs float128 ID %8.2g\n", c.name.c_str(), worst);
    EXPECT_LE(worst, 1e-13) << c.name;
  }
}

TEST(PayloadRegressor, ColumnsTimesParametersAreTheLoadedLessTheUnloadedDynamics) {
  unsigned seed = 11;
  for (const Case& c : cases()) {
    const sd::Model<Quad> oracle = sd_test::with_exact_rotations(c.model);
    sd::Data<double> data(c.model);
    std::mt19937 rng(seed++);
    for (const std::string& frame : payload_frames(c.model)) {
      const sd::Payload payload = random_payload(rng);
      const sd::Model<Quad> loaded = sd_test::with_exact_rotations(sd::with_payloads(c.model, {{frame, payload}}));
      VectorXd pi(10);
      sd::payload_inertia(frame, payload).toParameters(pi.data());
      double worst = 0;
      for (int s = 0; s < 5; ++s) {
        const State x = random_state(c.model, oracle, rng);
        const VectorXd tau_payload = sd::payload_regressor(c.model, data, x.q, x.qd, x.qdd, frame) * pi;
        const VectorQ expected = ref::inverse_dynamics(loaded, x.Q, x.Qd, x.Qdd) - ref::inverse_dynamics(oracle, x.Q, x.Qd, x.Qdd);
        worst = std::max(worst, sd::relative_error_to(tau_payload, expected));
      }
      std::printf("[regressor] %-40s payload on %-24s %8.2g\n", c.name.c_str(), frame.c_str(), worst);
      EXPECT_LE(worst, 1e-13) << c.name << ", frame " << frame;
    }
  }
}

TEST(PayloadRegressor, ActuatorColumnsGiveTheActuatorEffort) {
  sd::Model<double> model = robot("panda.urdf", false);
  for (int k = 0; k < model.nv; ++k) {
    model.armature[k] = 0.1 + 0.01 * k;
    model.damping[k] = 0.5 + 0.1 * k;
    model.friction[k] = 1.0 + 0.2 * k;
    model.friction_velocity[k] = 0.05;
  }
  model.finalize();
  sd::Data<double> data(model);
  std::mt19937 rng(5);
  for (int s = 0; s < 10; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng), qdd = sd_test::random_vector(model.nv, rng);
    VectorXd qd = sd_test::random_vector(model.nv, rng);
    qd[0] = 0.02;  // inside the friction ramp
    qd[1] = -0.01;
    sd::payload_regressor(model, data, q, qd, qdd, "panda_link8");
    const VectorXd expected = sd::actuator_effort(model, data, qd, qdd);
    for (int k = 0; k < model.nv; ++k) {
      const double effort = data.Y_actuator(k, 0) * model.armature[k] + data.Y_actuator(k, 1) * model.damping[k] +
                            data.Y_actuator(k, 2) * model.friction[k];
      EXPECT_NEAR(effort, expected[k], 1e-14 * (1 + std::abs(expected[k]))) << k;
    }
  }
  EXPECT_THROW(sd::payload_regressor(model, data, VectorXd::Zero(model.nq), VectorXd::Zero(model.nv),
                                     VectorXd::Zero(model.nv), "no_such_link"),
               std::out_of_range);
}

TEST(InertialParameters, RoundTripAndRefuseBodiesThatAreNotPhysical) {
  sd::Model<double> model = robot("ur5.urdf", false);
  const VectorXd pi = model.inertial_parameters();
  ASSERT_EQ(pi.size(), 10 * (model.nbodies() - 1));
  // body 1's parameters by hand from its inertia (eq. 25)
  const sd::RigidInertia<double>& I1 = model.inertia[1];
  EXPECT_EQ(pi[0], I1.mass);
  EXPECT_EQ(pi[3], I1.first_moment[2]);
  EXPECT_EQ(pi[5], I1.rotational_inertia(0, 1));
  EXPECT_EQ(pi[7], I1.rotational_inertia(0, 2));
  EXPECT_EQ(pi[9], I1.rotational_inertia(2, 2));
  model.set_inertial_parameters(pi);
  EXPECT_EQ(model.inertial_parameters(), pi);

  auto refused = [&](VectorXd bad, const std::string& needle) {
    const VectorXd before = model.inertial_parameters();
    try {
      model.set_inertial_parameters(bad);
      ADD_FAILURE() << "accepted: " << needle;
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find(needle), std::string::npos) << error.what();
    }
    EXPECT_EQ(model.inertial_parameters(), before);  // left as it was
  };
  VectorXd bad = pi;
  bad[10] = -1.0;  // body 2's mass
  refused(bad, "link '" + model.body_names[2] + "'");
  bad = pi;
  bad[10 * 2 + 4] = 100.0;  // body 3's I_xx far above I_yy + I_zz
  refused(bad, "triangle inequality");
  bad = pi;
  bad[10 * 3 + 1] = std::numeric_limits<double>::quiet_NaN();
  refused(bad, "not finite");
  refused(VectorXd::Zero(pi.size() - 1), "10 each");
}

TEST(JointTorqueRegressor, NonFiniteInputIsReportedNotReturned) {
  const sd::Model<double> model = robot("panda.urdf", false);
  sd::Data<double> data(model);
  VectorXd qd = VectorXd::Zero(model.nv);
  qd[2] = std::numeric_limits<double>::infinity();
  try {
    sd::joint_torque_regressor(model, data, VectorXd::Zero(model.nq), qd, VectorXd::Zero(model.nv));
    ADD_FAILURE() << "an infinite velocity gave a result";
  } catch (const std::domain_error& error) {
    EXPECT_NE(std::string(error.what()).find("joint torque regressor"), std::string::npos) << error.what();
  }
  EXPECT_THROW(sd::joint_torque_regressor(model, data, VectorXd::Zero(model.nq + 1), qd, qd), std::invalid_argument);
}
