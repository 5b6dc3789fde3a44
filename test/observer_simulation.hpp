// A simulated robot for the momentum observer's tests (test_momentum_observer.cpp, and the node's
// test_node_external_torques.cpp, which publishes it as joint_states): the library's own forward
// dynamics (forward_dynamics_actuated, RK4 at 1 kHz) under a PD controller with gravity
// compensation that tracks random sums of sines, whose torque is the measured effort; a wrench at
// a tool frame and a torque step at one joint as the disturbances; the library's observer run on
// every sample; and the ideal response ṙ = K (τ_ext − r), integrated exactly for a τ_ext linear
// between samples.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "spatial_dynamics/algorithms/actuator_dynamics.hpp"
#include "spatial_dynamics/algorithms/crba.hpp"
#include "spatial_dynamics/algorithms/jacobian.hpp"
#include "spatial_dynamics/estimation/momentum_observer.hpp"
#include "test_utils.hpp"

namespace sd_test {

namespace sd = spatial_dynamics;
using Eigen::VectorXd;

constexpr double kDt = 1e-3;    // 1 kHz
constexpr double kGain = 50.0;  // K (1/s)

struct Robot {
  std::string name;
  sd::Model<double> model;
  std::string tool;  // the frame the wrench acts at
};

inline Robot robot(const std::string& file, const std::string& tool, bool actuator_model) {
  Robot r{file, sd::build_model_from_urdf_file(sd_test::robot_path(file)), tool};
  r.model.reset_actuator_terms();  // rigid, as the node's ~actuator_model rigid_body (the URDF's <dynamics> go)
  r.model.finalize();
  if (actuator_model) {
    r.name += " with damping and friction";
    for (int i = 1; i < r.model.nbodies(); ++i) {  // the arm's revolute joints, not the fingers
      if (r.model.joints[i].type != sd::JointType::Revolute) continue;
      const int k = r.model.joints[i].idx_v;
      r.model.damping[k] = 0.5 + 0.1 * k;    // N m s/rad
      r.model.friction[k] = 0.8 - 0.05 * k;  // N m
      r.model.friction_velocity[k] = 0.05;   // rad/s
    }
    r.model.finalize();
  }
  return r;
}

inline std::vector<Robot> robots() {
  return {robot("ur5.urdf", "ee_link", false), robot("panda.urdf", "panda_hand", false),
          robot("panda.urdf", "panda_hand", true)};
}

/// What acts on the robot besides its controller: a wrench at the tool frame (in its axes) from
/// `wrench_from`, and an external torque at one joint from `step_from`.
struct Disturbance {
  sd::ForceVector<double> wrench = sd::ForceVector<double>::Zero();
  double wrench_from = 1e9, wrench_until = 1e9;
  int step_joint = -1;
  double step = 0, step_from = 1e9;
};

struct Trajectory {
  std::vector<double> t;
  std::vector<VectorXd> q, qd, effort, estimate, ideal;  // per sample; effort: the measured one
};

/// Simulates `duration` seconds and runs the observer on every sample.
/// With `tare_at`, the observer is tared at that sample, and the ideal response recorded from then
/// on is less the estimate tared away.
inline Trajectory simulate(const Robot& robot, const Disturbance& d, double duration, double noise, unsigned seed,
                    double tare_at = 1e9) {
  const sd::Model<double>& model = robot.model;
  const int n = model.nv, tool = model.frameIndex(robot.tool), body = model.frames[tool].body;
  sd::Data<double> data(model);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  // q_d(t) = q0 + Σ_m a_m sin(ω_m t + φ_m) about 35 % into each joint's range (away from the
  // stretched-out singular pose; arms: one coordinate per joint, q and q̇ alike), a_m up to a tenth
  // of the range (0.3 at most).
  VectorXd q0 = VectorXd::Zero(n), reach = VectorXd::Zero(n);
  for (int i = 1; i < model.nbodies(); ++i) {
    const auto& j = model.joints[i];
    const double lo = std::isfinite(j.limits.position_lower) ? j.limits.position_lower : -1.0;
    const double hi = std::isfinite(j.limits.position_upper) ? j.limits.position_upper : 1.0;
    q0[j.idx_q] = lo + 0.35 * (hi - lo);
    reach[j.idx_v] = std::min(0.3, 0.1 * (hi - lo));
  }
  std::vector<VectorXd> amplitude(3, VectorXd(n)), omega(3, VectorXd(n)), phase(3, VectorXd(n));
  for (int m = 0; m < 3; ++m)
    for (int k = 0; k < n; ++k) {
      amplitude[m][k] = reach[k] * u(rng);
      omega[m][k] = 1.5 + u(rng);
      phase[m][k] = M_PI * u(rng);
    }
  // PD gains of a 10 rad/s critically damped loop on each coordinate's own inertia M_kk(q0).
  const VectorXd inertia = sd::crba(model, data, q0).diagonal();
  const VectorXd kp = 100.0 * inertia, kd = 20.0 * inertia;
  auto controller = [&](double t, const VectorXd& q, const VectorXd& qd) {
    VectorXd q_desired = q0;
    for (int m = 0; m < 3; ++m)
      q_desired += amplitude[m].cwiseProduct((omega[m] * t + phase[m]).array().sin().matrix());
    VectorXd tau = sd::gravity_torques(model, data, q);
    return VectorXd(tau + kp.cwiseProduct(q_desired - q) - kd.cwiseProduct(qd));
  };
  auto joint_disturbance = [&](double t) {
    VectorXd tau = VectorXd::Zero(n);
    if (d.step_joint >= 0 && t >= d.step_from - 0.5 * kDt) tau[d.step_joint] = d.step;
    return tau;
  };
  auto tool_torques = [&](const VectorXd& q) {  // Jᵀ F
    return VectorXd(sd::frame_jacobian(model, data, q, tool, sd::ReferenceFrame::Local).transpose() * d.wrench.toVector());
  };
  // The wrench in the body's coordinates: f_B = ^FX_Bᵀ F.
  std::vector<sd::ForceVector<double>> f_ext(model.nbodies(), sd::ForceVector<double>::Zero());
  const sd::ForceVector<double> wrench_on_body = model.frames[tool].X_frame_body.applyInverse(d.wrench);
  // One RK4 step of (q, q̇) from t, the disturbances as at the step's start.
  auto step = [&](double t, VectorXd& q, VectorXd& qd) {
    const bool wrench_on = t >= d.wrench_from - 0.5 * kDt && t < d.wrench_until - 0.5 * kDt;
    f_ext[body] = wrench_on ? wrench_on_body : sd::ForceVector<double>::Zero();
    const VectorXd tau_joint = joint_disturbance(t);
    auto accel = [&](double s, const VectorXd& x, const VectorXd& v) {
      return VectorXd(sd::forward_dynamics_actuated(model, data, x, v, controller(s, x, v) + tau_joint, f_ext));
    };
    const VectorXd a1 = accel(t, q, qd);
    const VectorXd v2 = qd + 0.5 * kDt * a1, q2 = q + 0.5 * kDt * qd;
    const VectorXd a2 = accel(t + 0.5 * kDt, q2, v2);
    const VectorXd v3 = qd + 0.5 * kDt * a2, q3 = q + 0.5 * kDt * v2;
    const VectorXd a3 = accel(t + 0.5 * kDt, q3, v3);
    const VectorXd v4 = qd + kDt * a3, q4 = q + kDt * v3;
    const VectorXd a4 = accel(t + kDt, q4, v4);
    q += kDt / 6 * (qd + 2 * v2 + 2 * v3 + v4);
    qd += kDt / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
    return wrench_on;
  };
  sd::MomentumObserver<double> observer(model, VectorXd::Constant(n, kGain));
  std::normal_distribution<double> effort_noise(0.0, noise > 0 ? noise : 1.0);  // drawn from only when noise > 0
  VectorXd q = q0, qd = VectorXd::Zero(n), ideal = VectorXd::Zero(n), previous_input = VectorXd::Zero(n);
  VectorXd tared = VectorXd::Zero(n);  // the estimate tared away
  bool wrench_on = false;  // during the step that ended at this sample
  Trajectory run;
  const int samples = static_cast<int>(std::lround(duration / kDt));
  const double decay = std::exp(-kGain * kDt);
  for (int k = 0; k <= samples; ++k) {
    const double t = k * kDt;
    VectorXd measured = controller(t, q, qd);
    if (noise > 0)
      for (int j = 0; j < n; ++j) measured[j] += effort_noise(rng);
    VectorXd estimate = observer.update(q, qd, measured, kDt);
    if (std::abs(t - tare_at) < 0.5 * kDt) {
      tared = estimate;
      observer.tare();
      estimate = observer.residual();
    }
    // The ideal response over the step that ended here, τ_ext linear from its start to here:
    // r(Δ) = x₁ − s/K + (r₀ − x₀ + s/K) e^{−KΔ}, s = (x₁ − x₀)/Δ.
    const VectorXd input_start = previous_input;
    const VectorXd input_end = (wrench_on ? tool_torques(q) : VectorXd::Zero(n)) + joint_disturbance(t - kDt);
    if (k > 0) {
      const VectorXd slope_over_gain = (input_end - input_start) / (kDt * kGain);
      ideal = input_end - slope_over_gain + (ideal - input_start + slope_over_gain) * decay;
    }
    run.t.push_back(t);
    run.q.push_back(q);
    run.qd.push_back(qd);
    run.effort.push_back(measured);
    run.estimate.push_back(estimate);
    run.ideal.push_back(ideal - tared);
    if (k == samples) break;
    // The next step's τ_ext at its start, the disturbances as they will act over it.
    const bool on = t >= d.wrench_from - 0.5 * kDt && t < d.wrench_until - 0.5 * kDt;
    previous_input = (on ? tool_torques(q) : VectorXd::Zero(n)) + joint_disturbance(t);
    wrench_on = step(t, q, qd);
  }
  return run;
}

inline double max_abs(const std::vector<VectorXd>& xs) {
  double m = 0;
  for (const VectorXd& x : xs) m = std::max(m, x.cwiseAbs().maxCoeff());
  return m;
}

inline double max_difference(const Trajectory& run) {
  double m = 0;
  for (std::size_t k = 0; k < run.t.size(); ++k) m = std::max(m, (run.estimate[k] - run.ideal[k]).cwiseAbs().maxCoeff());
  return m;
}

inline Disturbance tool_wrench() {
  Disturbance d;
  d.wrench = sd::ForceVector<double>(sd::Vec3<double>(0.5, -0.3, 0.2), sd::Vec3<double>(5.0, -3.0, 8.0));
  d.wrench_from = 5.0;
  return d;
}

}  // namespace sd_test
