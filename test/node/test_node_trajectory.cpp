// Integration test of ~inverse_dynamics_trajectory: efforts at every point against the library's
// rnea, peak efforts and first effort-limit violations, finite differences against an analytic
// trajectory, joints left out held at their joint_states positions, and bad requests naming the
// culprit while the node keeps serving.
#include <sensor_msgs/JointState.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "node_test_utils.hpp"
#include "spatial_dynamics/InverseDynamicsTrajectory.h"

using namespace sd_node_test;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using spatial_dynamics::InverseDynamicsTrajectory;

namespace {

constexpr double kTolerance = 1e-12;

class NodeTrajectory : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ASSERT_TRUE(wait_for_services()) << "the node's services did not appear";
    ASSERT_TRUE(ros::service::waitForService(service("inverse_dynamics_trajectory"), ros::Duration(30)));
  }

  void SetUp() override {
    model = model_from_parameter();
    for (int i = 1; i < model.nbodies(); ++i) names.push_back(model.joint_names[i]);
  }

  /// The URDF's effort limit as the service documents it: +inf when none or not positive.
  double limit(const std::string& joint) const {
    const double e = model.joints[model.jointBody(joint)].limits.effort;
    return e > 0 ? e : std::numeric_limits<double>::infinity();
  }

  /// A trajectory naming every joint in `order`, with the given states (model order) as columns.
  InverseDynamicsTrajectory request(const std::vector<std::string>& order, const MatrixXd& q, const MatrixXd* qd,
                                    const MatrixXd* qdd, const std::vector<double>& times) const {
    InverseDynamicsTrajectory srv;
    srv.request.trajectory.joint_names = order;
    for (Eigen::Index k = 0; k < q.cols(); ++k) {
      trajectory_msgs::JointTrajectoryPoint p;
      for (const std::string& name : order) {
        const int i = model.joints[model.jointBody(name)].idx_v;
        p.positions.push_back(q(i, k));
        if (qd) p.velocities.push_back((*qd)(i, k));
        if (qdd) p.accelerations.push_back((*qdd)(i, k));
      }
      p.time_from_start = ros::Duration(times[k]);
      srv.request.trajectory.points.push_back(p);
    }
    return srv;
  }

  /// Column k of the response's field (model order: the response names the model's joints).
  static VectorXd column(const InverseDynamicsTrajectory& srv, std::size_t k,
                         std::vector<double> trajectory_msgs::JointTrajectoryPoint::*field) {
    return to_eigen(srv.response.points[k].*field);
  }

  sd::Model<double> model;
  std::vector<std::string> names;
  std::mt19937 rng{17};
};

std::vector<double> even_times(int n, double h, double t0 = 0.5) {
  std::vector<double> t(n);
  for (int k = 0; k < n; ++k) t[k] = t0 + k * h;
  return t;
}

}  // namespace

TEST_F(NodeTrajectory, EffortsPeaksAndLimitsMatchTheLibraryAtEveryPoint) {
  const int n = 13;  // not a multiple of the batch's lanes
  MatrixXd q(model.nq, n), qd(model.nv, n), qdd(model.nv, n);
  for (int k = 0; k < n; ++k) {
    q.col(k) = sd_test::random_configuration(model, rng);
    qd.col(k) = sd_test::random_vector(model.nv, rng, 2.0);
    qdd.col(k) = sd_test::random_vector(model.nv, rng, 5.0);
  }
  std::vector<std::string> shuffled = names;
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  InverseDynamicsTrajectory srv = call("inverse_dynamics_trajectory", request(shuffled, q, &qd, &qdd, even_times(n, 0.1)));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  EXPECT_FALSE(contains(srv.response.message, "differences")) << srv.response.message;
  EXPECT_EQ(srv.response.name, names);
  ASSERT_EQ(srv.response.points.size(), static_cast<std::size_t>(n));
  ASSERT_EQ(srv.response.peak_effort.size(), names.size());
  ASSERT_EQ(srv.response.effort_limit.size(), names.size());
  ASSERT_EQ(srv.response.first_violation.size(), names.size());

  sd::Data<double> data(model);
  VectorXd peak = VectorXd::Zero(model.nv);
  std::vector<int> first(model.nv, -1);
  for (int k = 0; k < n; ++k) {
    EXPECT_EQ(srv.response.points[k].time_from_start, srv.request.trajectory.points[k].time_from_start);
    EXPECT_EQ(column(srv, k, &trajectory_msgs::JointTrajectoryPoint::positions), q.col(k));
    const VectorXd tau = sd::rnea(model, data, q.col(k), qd.col(k), qdd.col(k));
    EXPECT_LE(sd_test::relative_error(column(srv, k, &trajectory_msgs::JointTrajectoryPoint::effort), tau), kTolerance)
        << "point " << k;
    for (int i = 0; i < model.nv; ++i) {
      peak[i] = std::max(peak[i], std::abs(tau[i]));
      if (std::abs(tau[i]) > limit(names[i]) && first[i] < 0) first[i] = k;
    }
  }
  EXPECT_LE(sd_test::relative_error(to_eigen(srv.response.peak_effort), peak), kTolerance);
  for (int i = 0; i < model.nv; ++i) {
    EXPECT_EQ(srv.response.effort_limit[i], limit(names[i])) << names[i];
    EXPECT_EQ(srv.response.first_violation[i], first[i]) << names[i];
  }
}

TEST_F(NodeTrajectory, FirstViolationIsThePointWhereTheLimitIsFirstExceeded) {
  // At rest for five points (gravity torques, checked below the limits), then accelerations big
  // enough to exceed some joints' limits from point 5 on.
  const int n = 9, onset = 5;
  const VectorXd q0 = sd_test::random_configuration(model, rng);
  MatrixXd q = q0.replicate(1, n), qd = MatrixXd::Zero(model.nv, n), qdd = MatrixXd::Zero(model.nv, n);
  for (int k = onset; k < n; ++k) qdd.col(k) = VectorXd::Constant(model.nv, 400.0 * (k - onset + 1));
  sd::Data<double> data(model);
  const VectorXd gravity = sd::rnea(model, data, q0, qd.col(0), qdd.col(0));
  std::vector<int> expected(model.nv, -1);
  int violating = 0;
  for (int i = 0; i < model.nv; ++i) {
    if (std::abs(gravity[i]) > limit(names[i])) {  // a joint too weak to hold itself: skip it
      expected[i] = 0;
      continue;
    }
    for (int k = onset; k < n && expected[i] < 0; ++k)
      if (std::abs(sd::rnea(model, data, q.col(k), qd.col(k), qdd.col(k))[i]) > limit(names[i])) expected[i] = k;
    violating += expected[i] >= onset;
  }
  ASSERT_GT(violating, 0) << "the accelerations exceed no limit";
  const InverseDynamicsTrajectory srv =
      call("inverse_dynamics_trajectory", request(names, q, &qd, &qdd, even_times(n, 0.05)));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  for (int i = 0; i < model.nv; ++i) EXPECT_EQ(srv.response.first_violation[i], expected[i]) << names[i];
  // The peak is the largest |τ| of the points, which is at the last (largest accelerations) or at rest.
  const VectorXd last = sd::rnea(model, data, q.col(n - 1), qd.col(n - 1), qdd.col(n - 1));
  EXPECT_LE(sd_test::relative_error(to_eigen(srv.response.peak_effort), last.cwiseAbs().cwiseMax(gravity.cwiseAbs())),
            kTolerance);
}

TEST_F(NodeTrajectory, CentralDifferencesMatchAnAnalyticTrajectory) {
  // q_i(t) = c_i + a sin(ω t + φ_i) at evenly spaced times, without velocities or accelerations.
  // Taylor remainders bound the differences' errors with |q'''| ≤ a ω³ and |q''''| ≤ a ω⁴:
  //   inside, central:          |Δq̇| ≤ h² a ω³ / 6,   |Δq̈| ≤ h² a ω⁴ / 12;
  //   first and last point:     |Δq̇| ≤ h² a ω³ / 3 (one-sided, three points),
  //                             |Δq̈| ≤ h a ω³ + h² a ω⁴ / 12 (the neighbour's second difference).
  // τ is affine in q̈ (M) and quadratic in q̇, so |Δτ| ≤ |M| |Δq̈| + |∂τ/∂q̇| |Δq̇| + O(|Δq̇|²).
  const int n = 41;
  const double h = 0.01, a = 0.4, w = 1.5;
  const std::vector<double> t = even_times(n, h, 1.0);
  const VectorXd center = sd_test::random_configuration(model, rng) * 0.5;
  const VectorXd phase = sd_test::random_vector(model.nv, rng, M_PI);
  MatrixXd q(model.nq, n), qd(model.nv, n), qdd(model.nv, n);
  for (int k = 0; k < n; ++k) {
    const VectorXd angle = (w * t[k] + phase.array()).matrix();
    q.col(k) = center + a * angle.array().sin().matrix();
    qd.col(k) = a * w * angle.array().cos().matrix();
    qdd.col(k) = -a * w * w * angle.array().sin().matrix();
  }
  const InverseDynamicsTrajectory srv =
      call("inverse_dynamics_trajectory", request(names, q, nullptr, nullptr, t));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  EXPECT_TRUE(contains(srv.response.message, "velocities of 41 of 41 points and accelerations of 41 of 41 points"))
      << srv.response.message;
  EXPECT_TRUE(contains(srv.response.message, "central")) << srv.response.message;
  EXPECT_TRUE(contains(srv.response.message, "one-sided")) << srv.response.message;
  ASSERT_EQ(srv.response.points.size(), static_cast<std::size_t>(n));

  sd::Data<double> data(model);
  for (int k = 0; k < n; ++k) {
    const bool end = k == 0 || k == n - 1;
    const double dv = (end ? h * h * a * w * w * w / 3 : h * h * a * w * w * w / 6) * 1.001;
    const double da = (end ? h * a * w * w * w + h * h * a * w * w * w * w / 12 : h * h * a * w * w * w * w / 12) * 1.001;
    const VectorXd v = column(srv, k, &trajectory_msgs::JointTrajectoryPoint::velocities);
    const VectorXd acc = column(srv, k, &trajectory_msgs::JointTrajectoryPoint::accelerations);
    EXPECT_LE((v - qd.col(k)).lpNorm<Eigen::Infinity>(), dv) << "point " << k;
    EXPECT_LE((acc - qdd.col(k)).lpNorm<Eigen::Infinity>(), da) << "point " << k;
    // The effort is the library's at the returned derivatives …
    const VectorXd tau = column(srv, k, &trajectory_msgs::JointTrajectoryPoint::effort);
    EXPECT_LE(sd_test::relative_error(tau, VectorXd(sd::rnea(model, data, q.col(k), v, acc))), kTolerance);
    // … and within the bound above of the analytic trajectory's.
    const VectorXd exact = sd::rnea(model, data, q.col(k), qd.col(k), qdd.col(k));
    const MatrixXd M = sd::crba(model, data, q.col(k));
    MatrixXd D(model.nv, model.nv);  // ∂τ/∂q̇ by central differences: exact for a quadratic
    for (int j = 0; j < model.nv; ++j) {
      VectorXd plus = qd.col(k), minus = qd.col(k);
      plus[j] += 1e-3;
      minus[j] -= 1e-3;
      const VectorXd tp = sd::rnea(model, data, q.col(k), plus, qdd.col(k));
      D.col(j) = (tp - sd::rnea(model, data, q.col(k), minus, qdd.col(k))) / 2e-3;
    }
    // The quadratic part c(δ) = τ(q, δ, 0) − τ(q, 0, 0) = Σ_jk H_jk δ_j δ_k, H by polarisation.
    const VectorXd zero = VectorXd::Zero(model.nv);
    const VectorXd g = sd::rnea(model, data, q.col(k), zero, zero);
    auto c = [&](const VectorXd& velocity) { return VectorXd(sd::rnea(model, data, q.col(k), velocity, zero) - g); };
    std::vector<VectorXd> c_unit(model.nv);
    for (int j = 0; j < model.nv; ++j) c_unit[j] = c(VectorXd::Unit(model.nv, j));
    VectorXd quadratic = VectorXd::Zero(model.nv);
    for (int j = 0; j < model.nv; ++j) {
      quadratic += c_unit[j].cwiseAbs() * dv * dv;
      for (int m = j + 1; m < model.nv; ++m)
        quadratic += (c(VectorXd::Unit(model.nv, j) + VectorXd::Unit(model.nv, m)) - c_unit[j] - c_unit[m]).cwiseAbs() * dv * dv;
    }
    const VectorXd bound = M.cwiseAbs() * VectorXd::Constant(model.nv, da) +
                           D.cwiseAbs() * VectorXd::Constant(model.nv, dv) + quadratic;
    for (int i = 0; i < model.nv; ++i)
      EXPECT_LE(std::abs(tau[i] - exact[i]), 1.01 * bound[i] + 1e-12 * (1 + std::abs(exact[i])))
          << "point " << k << ", joint " << names[i];
  }

  // Uneven times: the differences are exact for a quadratic q(t) = b + c t + d t².
  std::vector<double> uneven = {0.0, 0.05, 0.07, 0.16, 0.2, 0.31};
  const VectorXd b = sd_test::random_vector(model.nv, rng), c = sd_test::random_vector(model.nv, rng),
                 d = sd_test::random_vector(model.nv, rng);
  MatrixXd qq(model.nq, 6);
  for (int k = 0; k < 6; ++k) qq.col(k) = b + c * uneven[k] + d * uneven[k] * uneven[k];
  const InverseDynamicsTrajectory quadratic =
      call("inverse_dynamics_trajectory", request(names, qq, nullptr, nullptr, uneven));
  ASSERT_TRUE(quadratic.response.success) << quadratic.response.message;
  for (int k = 0; k < 6; ++k) {
    const VectorXd v = column(quadratic, k, &trajectory_msgs::JointTrajectoryPoint::velocities);
    const VectorXd acc = column(quadratic, k, &trajectory_msgs::JointTrajectoryPoint::accelerations);
    EXPECT_LE((v - (c + 2 * d * uneven[k])).lpNorm<Eigen::Infinity>(), 1e-9) << "point " << k;
    EXPECT_LE((acc - 2 * d).lpNorm<Eigen::Infinity>(), 1e-7) << "point " << k;
  }
}

TEST_F(NodeTrajectory, JointsLeftOutAreHeldAtTheirJointStatesPositions) {
  ros::NodeHandle nh;
  ros::Publisher joint_states = nh.advertise<sensor_msgs::JointState>("/joint_states", 10);
  for (int k = 0; k < 100 && joint_states.getNumSubscribers() == 0; ++k) ros::Duration(0.05).sleep();
  const VectorXd q_state = sd_test::random_configuration(model, rng);
  sensor_msgs::JointState msg;
  msg.name = names;
  msg.position = to_std(q_state);
  msg.velocity = to_std(sd_test::random_vector(model.nv, rng));  // not used: left-out joints are held still

  // The trajectory names every other joint.
  std::vector<std::string> named;
  for (std::size_t i = 0; i < names.size(); i += 2) named.push_back(names[i]);
  const int n = 5;
  MatrixXd q(model.nq, n), qd(model.nv, n), qdd(model.nv, n);
  for (int k = 0; k < n; ++k) {
    q.col(k) = sd_test::random_configuration(model, rng);
    qd.col(k) = sd_test::random_vector(model.nv, rng);
    qdd.col(k) = sd_test::random_vector(model.nv, rng);
  }
  InverseDynamicsTrajectory srv;
  for (int attempt = 0; attempt < 50; ++attempt) {  // until the node has the joint states
    msg.header.stamp = ros::Time::now();
    joint_states.publish(msg);
    ros::Duration(0.1).sleep();
    srv = call("inverse_dynamics_trajectory", request(named, q, &qd, &qdd, even_times(n, 0.1)));
    if (srv.response.success && column(srv, 0, &trajectory_msgs::JointTrajectoryPoint::positions)[1] == q_state[1]) break;
  }
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  EXPECT_TRUE(contains(srv.response.message, "'" + names[1] + "'")) << srv.response.message;
  EXPECT_TRUE(contains(srv.response.message, "held at their latest joint_states position")) << srv.response.message;
  sd::Data<double> data(model);
  for (int k = 0; k < n; ++k) {
    VectorXd qk = q_state, qdk = VectorXd::Zero(model.nv), qddk = VectorXd::Zero(model.nv);
    for (const std::string& name : named) {
      const int i = model.joints[model.jointBody(name)].idx_v;
      qk[i] = q(i, k);
      qdk[i] = qd(i, k);
      qddk[i] = qdd(i, k);
    }
    EXPECT_EQ(column(srv, k, &trajectory_msgs::JointTrajectoryPoint::positions), qk) << "point " << k;
    EXPECT_EQ(column(srv, k, &trajectory_msgs::JointTrajectoryPoint::velocities), qdk) << "point " << k;
    EXPECT_EQ(column(srv, k, &trajectory_msgs::JointTrajectoryPoint::accelerations), qddk) << "point " << k;
    EXPECT_LE(sd_test::relative_error(column(srv, k, &trajectory_msgs::JointTrajectoryPoint::effort),
                                      VectorXd(sd::rnea(model, data, qk, qdk, qddk))),
              kTolerance)
        << "point " << k;
  }
}

TEST_F(NodeTrajectory, BadRequestsNameTheCulpritAndTheNodeKeepsServing) {
  const int n = 6;
  MatrixXd q(model.nq, n), qd(model.nv, n), qdd(model.nv, n);
  for (int k = 0; k < n; ++k) {
    q.col(k) = sd_test::random_configuration(model, rng);
    qd.col(k) = sd_test::random_vector(model.nv, rng);
    qdd.col(k) = sd_test::random_vector(model.nv, rng);
  }
  const std::vector<double> times = even_times(n, 0.1);
  const InverseDynamicsTrajectory good = request(names, q, &qd, &qdd, times);
  const InverseDynamicsTrajectory no_derivatives = request(names, q, nullptr, nullptr, times);

  auto expect_rejected = [&](InverseDynamicsTrajectory srv, const std::vector<std::string>& parts, const char* what) {
    srv = call("inverse_dynamics_trajectory", srv);
    EXPECT_FALSE(srv.response.success) << what << ": accepted";
    for (const std::string& part : parts)
      EXPECT_TRUE(contains(srv.response.message, part)) << what << ": message '" << srv.response.message << "' lacks '"
                                                        << part << "'";
    const InverseDynamicsTrajectory again = call("inverse_dynamics_trajectory", good);  // still serving, correctly
    ASSERT_TRUE(again.response.success) << again.response.message;
    sd::Data<double> data(model);
    EXPECT_LE(sd_test::relative_error(column(again, n - 1, &trajectory_msgs::JointTrajectoryPoint::effort),
                                      VectorXd(sd::rnea(model, data, q.col(n - 1), qd.col(n - 1), qdd.col(n - 1)))),
              kTolerance);
  };

  InverseDynamicsTrajectory bad = good;
  bad.request.trajectory.joint_names[1] = "no_such_joint";
  expect_rejected(bad, {"unknown joint 'no_such_joint'"}, "unknown joint");

  bad = good;
  bad.request.trajectory.joint_names[2] = names[0];
  expect_rejected(bad, {"joint '" + names[0] + "' is named twice"}, "repeated joint");

  bad = good;
  bad.request.trajectory.points[2].positions.pop_back();
  expect_rejected(bad, {"point 2: positions has " + std::to_string(names.size() - 1) + " entries",
                        "joint_names has " + std::to_string(names.size())},
                  "short positions");

  bad = good;
  bad.request.trajectory.points[4].accelerations.push_back(0.0);
  expect_rejected(bad, {"point 4: accelerations has " + std::to_string(names.size() + 1) + " entries"},
                  "long accelerations");

  bad = good;
  bad.request.trajectory.points[3].velocities[1] = std::numeric_limits<double>::quiet_NaN();
  expect_rejected(bad, {"point 3: velocities of joint '" + names[1] + "' is not finite"}, "NaN velocity");

  bad = good;
  bad.request.trajectory.points[1].positions[0] = std::numeric_limits<double>::infinity();
  expect_rejected(bad, {"point 1: positions of joint '" + names[0] + "' is not finite"}, "infinite position");

  bad = no_derivatives;
  bad.request.trajectory.points[3].time_from_start = bad.request.trajectory.points[2].time_from_start;
  expect_rejected(bad, {"point 3: time_from_start", "increase strictly"}, "repeated time");

  bad = no_derivatives;
  bad.request.trajectory.points.resize(1);
  expect_rejected(bad, {"the trajectory has 1 point(s)", "at least 2 points"}, "one point, no velocities");

  bad = no_derivatives;
  bad.request.trajectory.points.resize(2);
  expect_rejected(bad, {"the trajectory has 2 point(s)", "accelerations", "at least 3 points"},
                  "two points, no accelerations");

  // With every derivative given, times need not increase (nothing is differentiated).
  InverseDynamicsTrajectory still = good;
  still.request.trajectory.points[3].time_from_start = still.request.trajectory.points[2].time_from_start;
  still = call("inverse_dynamics_trajectory", still);
  EXPECT_TRUE(still.response.success) << still.response.message;
}
