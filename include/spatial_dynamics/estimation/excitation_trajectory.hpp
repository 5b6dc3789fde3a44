// An exciting trajectory for payload identification (doc/payload_identification.md): per joint a
// finite Fourier series (Swevers, Ganseman et al., IEEE T-RA 1997, eq. 9)
//   q(t) = q₀ + Σ_{l=1..L} a_l / (ω l) sin(ω l t) − b_l / (ω l) cos(ω l t),   ω = 2π / T,
// periodic in T, the duration split into whole periods of at most `max_period`. Σ a_l = 0 makes
// q̇(0) = q̇(T) = 0 and Σ l b_l = 0 makes q̈(0) = q̈(T) = 0: it starts and ends at rest. Among
// `candidates` random coefficient sets (a fixed seed: the same request gives the same trajectory),
// each scaled per joint to the largest motion within the limits, the one whose payload regressor,
// scaled as the identification scales it, has the smallest condition number over one period wins.
// Limits: a joint may use `speed_scale` of its URDF velocity limit and of its position range about
// the range's middle (a joint without position limits: ±π · speed_scale about its rest position),
// and |q̈| ≤ max_acceleration when that is above zero. They are checked on a grid 20 times finer
// than the highest harmonic's and the sample spacing's, with a margin of 1 %.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "spatial_dynamics/algorithms/regressor.hpp"
#include "spatial_dynamics/estimation/payload_identification.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"

namespace spatial_dynamics {

struct ExcitationOptions {
  double speed_scale = 0.5;       // (0, 1]
  double max_acceleration = 0;    // rad/s² or m/s²; 0: no limit
  int harmonics = 5;              // L
  double max_period = 10;         // s
  double sample_period = 0.01;    // s, the points' spacing
  int candidates = 24;
  unsigned seed = 1;
  std::string frame;              // the payload's frame (empty: the link moved by the deepest joint)
  Eigen::VectorXd rest_position;  // q of the joints not moved (empty: zero)
};

struct Excitation {
  std::vector<std::string> joints;
  Eigen::VectorXd time;                              // s, from 0 to the duration
  Eigen::MatrixXd position, velocity, acceleration;  // joints × points
  double condition_number = 0;                       // of the scaled payload regressor (payload_column_scales), one period
};

namespace detail {

/// One joint's series: value, first and second derivative at t of Σ a_l/(ωl) sin − b_l/(ωl) cos.
struct FourierSeries {
  Eigen::VectorXd a, b;
  double omega = 0;
  void evaluate(double t, double& q, double& qd, double& qdd) const {
    q = qd = qdd = 0;
    for (int l = 1; l <= a.size(); ++l) {
      const double w = omega * l, s = std::sin(w * t), c = std::cos(w * t);
      q += a[l - 1] / w * s - b[l - 1] / w * c;
      qd += a[l - 1] * c + b[l - 1] * s;
      qdd += w * (b[l - 1] * c - a[l - 1] * s);
    }
  }
};

struct ExcitedJoint {
  int body = 0;
  double middle = 0, half_range = 0, velocity = 0, acceleration = 0;  // what the motion may use
};

inline std::vector<ExcitedJoint> excited_joints(const Model<double>& model, const std::vector<std::string>& joints,
                                                const ExcitationOptions& o) {
  if (joints.empty()) throw std::invalid_argument("joints: none given");
  std::set<std::string> seen;
  std::vector<ExcitedJoint> out;
  for (const std::string& name : joints) {
    if (!model.hasJoint(name)) throw std::invalid_argument("joints: unknown joint '" + name + "'");
    if (!seen.insert(name).second) throw std::invalid_argument("joints: joint '" + name + "' is given twice");
    const int body = model.jointBody(name);
    const Joint<double>& j = model.joints[body];
    if (j.coupled) throw std::invalid_argument("joints: joint '" + name + "' follows another joint (mimic): move its master");
    if (j.nv != 1 || j.nq != 1) throw std::invalid_argument("joints: joint '" + name + "' has several coordinates: only revolute and prismatic joints are excited");
    ExcitedJoint e;
    e.body = body;
    const JointLimits<double>& limits = j.limits;
    if (!(limits.velocity > 0) || !std::isfinite(limits.velocity))
      throw std::invalid_argument("joint '" + name + "' has no velocity limit above zero in the URDF");
    e.velocity = o.speed_scale * limits.velocity;
    e.acceleration = o.max_acceleration > 0 ? o.max_acceleration : std::numeric_limits<double>::infinity();
    const double rest = o.rest_position.size() == model.nq ? o.rest_position[j.idx_q] : 0.0;
    if (std::isfinite(limits.position_lower) && std::isfinite(limits.position_upper)) {
      if (!(limits.position_upper > limits.position_lower))
        throw std::invalid_argument("joint '" + name + "' has an empty position range in the URDF");
      e.middle = 0.5 * (limits.position_lower + limits.position_upper);
      e.half_range = 0.5 * o.speed_scale * (limits.position_upper - limits.position_lower);
    } else {
      e.middle = rest;
      e.half_range = o.speed_scale * M_PI;
    }
    out.push_back(e);
  }
  return out;
}

inline void check_excitation_options(double duration, const ExcitationOptions& o) {
  if (!std::isfinite(duration) || duration <= 0 || duration > 3600)
    throw std::invalid_argument("duration: " + std::to_string(duration) + " s is not in (0, 3600]");
  if (!(o.speed_scale > 0 && o.speed_scale <= 1))
    throw std::invalid_argument("speed_scale: " + std::to_string(o.speed_scale) + " is not in (0, 1]");
  if (!std::isfinite(o.max_acceleration) || o.max_acceleration < 0)
    throw std::invalid_argument("max_acceleration: " + std::to_string(o.max_acceleration) + " must be finite and not negative");
  if (o.harmonics < 1 || !(o.max_period > 0) || !(o.sample_period > 0) || o.candidates < 1)
    throw std::invalid_argument("excitation options: harmonics, max_period, sample_period and candidates must be positive");
  if (duration < 2 * o.sample_period)
    throw std::invalid_argument("duration: " + std::to_string(duration) + " s is shorter than two samples");
}

/// The condition number of the payload regressor stacked over `q`'s columns, scaled as the
/// identification scales it (payload_column_scales).
inline double payload_condition(const Model<double>& model, Data<double>& data, const std::string& frame,
                                const Eigen::MatrixXd& q, const Eigen::MatrixXd& qd, const Eigen::MatrixXd& qdd,
                                double length_scale) {
  Eigen::MatrixXd A(q.cols() * model.nv, 10);
  for (Eigen::Index s = 0; s < q.cols(); ++s)
    A.middleRows(s * model.nv, model.nv) = payload_regressor(model, data, q.col(s), qd.col(s), qdd.col(s), frame);
  const Eigen::VectorXd scales = payload_column_scales(A, length_scale);
  const Eigen::VectorXd sigma = Eigen::JacobiSVD<Eigen::MatrixXd>(A * scales.cwiseInverse().asDiagonal()).singularValues();
  return sigma[9] > 0 ? sigma[0] / sigma[9] : std::numeric_limits<double>::infinity();
}

}  // namespace detail

/// The exciting trajectory of `joints` over `duration` seconds (points every sample_period, the last
/// at the duration). Throws std::invalid_argument naming the joint, the field or the option that
/// cannot be met; std::out_of_range for an unknown frame.
inline Excitation excitation_trajectory(const Model<double>& model, const std::vector<std::string>& joints,
                                                  double duration, const ExcitationOptions& options = {}) {
  detail::check_excitation_options(duration, options);
  const std::vector<detail::ExcitedJoint> excited = detail::excited_joints(model, joints, options);
  int deepest = 0;
  for (const auto& e : excited) deepest = std::max(deepest, e.body);
  const std::string frame = options.frame.empty() ? model.body_names[deepest] : options.frame;
  if (!model.hasFrame(frame)) throw std::out_of_range("unknown frame '" + frame + "'");
  const int L = options.harmonics, nj = static_cast<int>(excited.size());
  const double period = duration / std::ceil(duration / options.max_period), omega = 2 * M_PI / period;
  const double check_step = std::min(options.sample_period, period / L) / 20;
  const int checks = static_cast<int>(std::ceil(period / check_step));
  Eigen::VectorXd rest = options.rest_position.size() == model.nq ? options.rest_position : Eigen::VectorXd::Zero(model.nq);

  // per candidate: each joint's series scaled to its limits, q₀ centring it in its range
  struct Candidate {
    std::vector<detail::FourierSeries> series;
    Eigen::VectorXd offset;
  };
  auto scaled_candidate = [&](std::mt19937& rng) {
    std::normal_distribution<double> normal(0.0, 1.0);
    Candidate c;
    c.offset.resize(nj);
    for (int j = 0; j < nj; ++j) {
      detail::FourierSeries f;
      f.omega = omega;
      f.a = Eigen::VectorXd::NullaryExpr(L, [&] { return normal(rng); });
      f.b = Eigen::VectorXd::NullaryExpr(L, [&] { return normal(rng); });
      f.a.array() -= f.a.mean();  // Σ a_l = 0
      const Eigen::VectorXd l = Eigen::VectorXd::LinSpaced(L, 1, L);
      f.b -= (l.dot(f.b) / l.squaredNorm()) * l;  // Σ l b_l = 0
      double lo = INFINITY, hi = -INFINITY, vmax = 0, amax = 0, q, qd, qdd;
      for (int k = 0; k <= checks; ++k) {
        f.evaluate(k * check_step, q, qd, qdd);
        lo = std::min(lo, q), hi = std::max(hi, q), vmax = std::max(vmax, std::abs(qd)), amax = std::max(amax, std::abs(qdd));
      }
      const detail::ExcitedJoint& e = excited[j];
      const double scale = 0.99 * std::min({e.half_range / (0.5 * (hi - lo)), e.velocity / vmax, e.acceleration / amax});
      f.a *= scale;
      f.b *= scale;
      c.offset[j] = e.middle - scale * 0.5 * (hi + lo);
      c.series.push_back(f);
    }
    return c;
  };
  auto sample = [&](const Candidate& c, const Eigen::VectorXd& times, Eigen::MatrixXd& q, Eigen::MatrixXd& qd, Eigen::MatrixXd& qdd) {
    q = rest.replicate(1, times.size());
    qd = qdd = Eigen::MatrixXd::Zero(model.nv, times.size());
    for (Eigen::Index k = 0; k < times.size(); ++k)
      for (int j = 0; j < nj; ++j) {
        const Joint<double>& joint = model.joints[excited[j].body];
        double x, v, a;
        c.series[j].evaluate(times[k], x, v, a);
        q(joint.idx_q, k) = c.offset[j] + x;
        qd(joint.idx_v, k) = v;
        qdd(joint.idx_v, k) = a;
      }
  };

  Data<double> data(model);
  std::mt19937 rng(options.seed);
  const Eigen::VectorXd probe_times = Eigen::VectorXd::LinSpaced(200, 0, period * 199 / 200);
  Candidate best;
  double best_condition = INFINITY;
  for (int k = 0; k < options.candidates; ++k) {
    const Candidate c = scaled_candidate(rng);
    Eigen::MatrixXd q, qd, qdd;
    sample(c, probe_times, q, qd, qdd);
    const double condition = detail::payload_condition(model, data, frame, q, qd, qdd, PayloadIdentificationOptions().length_scale);
    if (k == 0 || condition < best_condition) best = c, best_condition = condition;
  }

  Excitation out;
  out.joints = joints;
  out.condition_number = best_condition;
  const int steps = static_cast<int>(std::floor(duration / options.sample_period + 1e-9));
  const bool whole = duration - steps * options.sample_period <= 1e-9 * duration;  // else a last point at the duration
  const int points = steps + (whole ? 1 : 2);
  out.time.resize(points);
  for (int k = 0; k <= steps; ++k) out.time[k] = k * options.sample_period;
  out.time[points - 1] = duration;
  Eigen::MatrixXd q, qd, qdd;
  sample(best, out.time, q, qd, qdd);
  out.position.resize(nj, points);
  out.velocity.resize(nj, points);
  out.acceleration.resize(nj, points);
  for (int j = 0; j < nj; ++j) {
    const Joint<double>& joint = model.joints[excited[j].body];
    out.position.row(j) = q.row(joint.idx_q);
    out.velocity.row(j) = qd.row(joint.idx_v);
    out.acceleration.row(j) = qdd.row(joint.idx_v);
  }
  return out;
}

}  // namespace spatial_dynamics
