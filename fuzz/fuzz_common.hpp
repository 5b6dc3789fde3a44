// Shared by the libFuzzer targets: the oracle (every call either returns finite numbers or throws a
// std::exception with a message), model invariants, and a byte reader for structured inputs.
// A finding prints what was wrong and aborts, which libFuzzer records as a crash with its input.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "spatial_dynamics/algorithms.hpp"
#include "test_paths.hpp"

namespace sd_fuzz {

namespace sd = spatial_dynamics;

[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "\nFINDING: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

template <class Derived>
void require_finite(const Eigen::DenseBase<Derived>& x, const std::string& what) {
  if (!x.derived().allFinite()) finding(what + " is not finite and no error was reported");
}

inline void require_finite(double x, const std::string& what) {
  if (!std::isfinite(x)) finding(what + " is not finite and no error was reported");
}

/// Runs `call`. An error must be a std::exception with a message; anything else escapes and
/// crashes the target. Returns whether the call completed.
template <class F>
bool result_or_error(const std::string& what, F&& call) {
  try {
    call();
    return true;
  } catch (const std::exception& e) {
    if (e.what() == nullptr || e.what()[0] == '\0') finding(what + " threw an exception without a message");
    return false;
  }
}

/// Runs `call`, which must throw a std::exception with a message (e.g. a wrong-length argument).
template <class F>
void expect_error(const std::string& what, F&& call) {
  if (result_or_error(what, call)) finding(what + " was accepted");
}

/// What every Model must satisfy, whatever it was built from: consistent sizes, a topological
/// order, coordinates inside q and q̇, frames on existing bodies, and only finite numbers.
inline void check_model(const sd::Model<double>& m, const std::string& what) {
  const std::size_t n = m.parent.size();
  if (n == 0) finding(what + ": a model without bodies");
  if (m.joints.size() != n || m.X_tree.size() != n || m.inertia.size() != n || m.body_names.size() != n ||
      m.joint_names.size() != n)
    finding(what + ": per-body arrays of different lengths");
  if (m.parent[0] != -1) finding(what + ": body 0 has a parent");
  int nq = 0, nv = 0;
  for (std::size_t i = 1; i < n; ++i) {
    const sd::Joint<double>& j = m.joints[i];
    if (m.parent[i] < 0 || m.parent[i] >= static_cast<int>(i)) finding(what + ": parent[i] is not < i");
    if (j.idx_q < 0 || j.idx_v < 0 || j.idx_q + j.nq > m.nq || j.idx_v + j.nv > m.nv)
      finding(what + ": joint '" + m.joint_names[i] + "' has coordinates outside q or q̇");
    if (j.mimic.active() && (j.mimic.master_body <= 0 || j.mimic.master_body >= static_cast<int>(n)))
      finding(what + ": joint '" + m.joint_names[i] + "' mimics a body that does not exist");
    if (!j.axis.allFinite() || !std::isfinite(j.mimic.multiplier) || !std::isfinite(j.mimic.offset))
      finding(what + ": joint '" + m.joint_names[i] + "' has a non-finite axis or mimic relation");
    if (!j.coupled) {
      nq += j.nq;
      nv += j.nv;
    }
    if (!m.hasJoint(m.joint_names[i]) || m.jointBody(m.joint_names[i]) != static_cast<int>(i))
      finding(what + ": the name of joint '" + m.joint_names[i] + "' finds another body (names not unique)");
  }
  if (nq != m.nq || nv != m.nv) finding(what + ": nq/nv differ from the joints' coordinates");
  for (std::size_t i = 0; i < n; ++i) {
    const std::string body = what + ": body '" + m.body_names[i] + "'";
    if (!m.X_tree[i].E.allFinite() || !m.X_tree[i].r.allFinite()) finding(body + " has a non-finite tree transform");
    const sd::RigidInertia<double>& I = m.inertia[i];
    if (!std::isfinite(I.mass) || !I.first_moment.allFinite() || !I.rotational_inertia.allFinite())
      finding(body + " has a non-finite inertia");
  }
  for (std::size_t k = 0; k < m.frames.size(); ++k) {
    const sd::Frame<double>& f = m.frames[k];
    if (f.body < 0 || f.body >= static_cast<int>(n)) finding(what + ": frame '" + f.name + "' on no body");
    if (!m.hasFrame(f.name) || m.frameIndex(f.name) != static_cast<int>(k))
      finding(what + ": the name of frame '" + f.name + "' finds another frame (names not unique)");
    if (!f.X_frame_body.E.allFinite() || !f.X_frame_body.r.allFinite())
      finding(what + ": frame '" + f.name + "' has a non-finite transform");
  }
  if (!m.gravity.allFinite()) finding(what + ": non-finite gravity");
}

/// A state of moderate size: joints within their limits (or within ±π), a unit quaternion for a
/// free root, velocities within ±10, accelerations, torques and external forces within ±100.
struct State {
  Eigen::VectorXd q, qd, qdd, tau;
  std::vector<sd::ForceVector<double>> f_ext;
};

inline State random_state(const sd::Model<double>& model, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  State s;
  s.q.resize(model.nq);
  for (int i = 1; i < model.nbodies(); ++i) {
    const sd::Joint<double>& j = model.joints[i];
    if (j.coupled) continue;
    if (j.type == sd::JointType::Free) {
      for (int k = 0; k < 3; ++k) s.q[j.idx_q + k] = u(rng);
      Eigen::Vector4d quat(u(rng), u(rng), u(rng), u(rng));
      if (quat.norm() < 1e-3) quat = Eigen::Vector4d(0, 0, 0, 1);
      s.q.segment<4>(j.idx_q + 3) = quat.normalized();
    } else if (std::isfinite(j.limits.position_lower) && std::isfinite(j.limits.position_upper) &&
               j.limits.position_upper > j.limits.position_lower &&
               j.limits.position_upper - j.limits.position_lower < 1e3) {
      const double mid = 0.5 * (j.limits.position_lower + j.limits.position_upper);
      s.q[j.idx_q] = mid + 0.5 * (j.limits.position_upper - j.limits.position_lower) * u(rng);
    } else {
      s.q[j.idx_q] = M_PI * u(rng);
    }
  }
  s.qd = 10.0 * Eigen::VectorXd::NullaryExpr(model.nv, [&] { return u(rng); });
  s.qdd = 100.0 * Eigen::VectorXd::NullaryExpr(model.nv, [&] { return u(rng); });
  s.tau = 100.0 * Eigen::VectorXd::NullaryExpr(model.nv, [&] { return u(rng); });
  for (int i = 0; i < model.nbodies(); ++i) {
    sd::Vector6<double> f;
    for (int k = 0; k < 6; ++k) f[k] = 100.0 * u(rng);
    s.f_ext.emplace_back(f);
  }
  return s;
}

/// Every algorithm at one state: each returns finite numbers or throws with a message.
inline void run_algorithms(const sd::Model<double>& model, sd::Data<double>& data, const State& s,
                           std::mt19937_64& rng) {
  result_or_error("rnea", [&] { require_finite(sd::rnea(model, data, s.q, s.qd, s.qdd), "rnea"); });
  result_or_error("rnea with external forces",
                  [&] { require_finite(sd::rnea(model, data, s.q, s.qd, s.qdd, s.f_ext), "rnea with external forces"); });
  result_or_error("gravity_torques", [&] { require_finite(sd::gravity_torques(model, data, s.q), "gravity_torques"); });
  result_or_error("nonlinear_effects",
                  [&] { require_finite(sd::nonlinear_effects(model, data, s.q, s.qd), "nonlinear_effects"); });
  result_or_error("forward_dynamics",
                  [&] { require_finite(sd::forward_dynamics(model, data, s.q, s.qd, s.tau), "forward_dynamics"); });
  result_or_error("forward_dynamics with external forces", [&] {
    require_finite(sd::forward_dynamics(model, data, s.q, s.qd, s.tau, s.f_ext), "forward_dynamics with external forces");
  });
  if (!model.has_coupled_joints) {
    result_or_error("aba", [&] { require_finite(sd::aba(model, data, s.q, s.qd, s.tau), "aba"); });
  } else {
    expect_error("aba of a model with coupled joints", [&] { sd::aba(model, data, s.q, s.qd, s.tau); });
  }
  result_or_error("crba", [&] {
    const Eigen::MatrixXd& M = sd::crba(model, data, s.q);
    require_finite(M, "crba");
    if (M != M.transpose()) finding("crba: the mass matrix is not symmetric");
  });
  result_or_error("forward_kinematics", [&] {
    sd::forward_kinematics(model, data, s.q, s.qd);
    for (int i = 0; i < model.nbodies(); ++i) {
      require_finite(data.X_base[i].E.eigen(), "forward_kinematics: a body rotation");
      require_finite(data.X_base[i].r.eigen(), "forward_kinematics: a body position");
      require_finite(data.v[i].toVector(), "forward_kinematics: a body velocity");
    }
    for (std::size_t k = 0; k < model.frames.size(); ++k)
      require_finite(data.X_frame_base[k].r.eigen(), "forward_kinematics: a frame position");
  });
  if (!model.frames.empty()) {
    const int frame = static_cast<int>(rng() % model.frames.size());
    for (sd::ReferenceFrame reference : {sd::ReferenceFrame::Local, sd::ReferenceFrame::RootAligned})
      result_or_error("frame_jacobian",
                      [&] { require_finite(sd::frame_jacobian(model, data, s.q, frame, reference), "frame_jacobian"); });
  }
  result_or_error("kinetic_energy", [&] { require_finite(sd::kinetic_energy(model, data, s.q, s.qd), "kinetic_energy"); });
  result_or_error("total_momentum",
                  [&] { require_finite(sd::total_momentum(model, data, s.q, s.qd).toVector(), "total_momentum"); });
  // Wrong lengths are errors, never out-of-bounds reads.
  const Eigen::VectorXd longer = Eigen::VectorXd::Zero(model.nv + 1);
  expect_error("rnea with a velocity one too long", [&] { sd::rnea(model, data, s.q, longer, s.qdd); });
  expect_error("crba with a q one too long", [&] { sd::crba(model, data, Eigen::VectorXd::Zero(model.nq + 1)); });
  std::vector<sd::ForceVector<double>> too_few(s.f_ext.begin(), s.f_ext.end() - 1);
  expect_error("rnea with one external force too few", [&] { sd::rnea(model, data, s.q, s.qd, s.qdd, too_few); });
}

/// Reads a structured input from the front of the fuzz data; past the end every read is 0.
class Reader {
 public:
  Reader(const std::uint8_t* data, std::size_t size) : p_(data), end_(data + size) {}

  bool empty() const { return p_ == end_; }
  std::uint8_t byte() { return p_ == end_ ? 0 : *p_++; }
  std::uint16_t u16() {
    const std::uint16_t low = byte();
    return static_cast<std::uint16_t>(low | byte() << 8);
  }
  bool flag() { return byte() & 1; }

  /// A double: mostly ordinary values, often the awkward ones (NaN, ±Inf, huge, tiny, negative).
  double number() {
    const std::uint8_t kind = byte();
    static const double special[] = {0.0,
                                     1.0,
                                     -1.0,
                                     0.5,
                                     1e-300,
                                     1e300,
                                     -1e300,
                                     std::numeric_limits<double>::quiet_NaN(),
                                     std::numeric_limits<double>::infinity(),
                                     -std::numeric_limits<double>::infinity(),
                                     std::numeric_limits<double>::max(),
                                     std::numeric_limits<double>::denorm_min(),
                                     1e6,
                                     -1e6,
                                     M_PI,
                                     1e-9};
    constexpr int n_special = sizeof(special) / sizeof(special[0]);
    if (kind < n_special) return special[kind];
    if (kind < 128) return static_cast<std::int16_t>(u16()) / 1000.0;  // ±32.767 in steps of 0.001
    if (kind < 160) {  // raw bits: every double there is
      std::uint64_t bits = 0;
      for (int k = 0; k < 8; ++k) bits |= std::uint64_t(byte()) << (8 * k);
      double x;
      std::memcpy(&x, &bits, sizeof x);
      return x;
    }
    return static_cast<std::int8_t>(byte()) / 16.0;  // ±8 in steps of 1/16
  }

  /// One of `known` (most of the time) or a name nobody has.
  std::string name(const std::vector<std::string>& known) {
    const std::uint8_t kind = byte();
    if (kind < 224 && !known.empty()) return known[(kind | byte() << 8) % known.size()];
    std::string s;
    for (int k = byte() % 12; k > 0; --k) s += static_cast<char>(byte());
    return s;
  }

 private:
  const std::uint8_t* p_;
  const std::uint8_t* end_;
};

}  // namespace sd_fuzz
