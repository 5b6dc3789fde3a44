// The generalized-momentum observer (De Luca and Mattone 2005; Haddadin, De Luca and
// Albu-Schäffer, IEEE T-RO 2017): an estimate r̂ of the joint forces τ_ext that the environment
// applies in
//   M q̈ + C q̇ + g = τ_m − τ_a(q̇) + τ_ext,
// with τ_m the measured effort, taken as the actuators' output, and τ_a the actuator model's
// damping and friction (actuator_dynamics.hpp; the armature is part of M and of p = M q̇). Since
// ṗ = Ṁ q̇ + M q̈ and Ṁ = C + Cᵀ, ṗ = u + τ_ext with u = τ_m − τ_a + Cᵀ q̇ − g, and
//   r̂(t) = K (p(t) − p(t_0) − ∫_{t_0}^{t} (u + r̂) dt)
// follows ṙ̂ = K (τ_ext − r̂): each joint's estimate is τ_ext through a first-order lag of bandwidth
// K (1/s, diagonal). It needs q, q̇ and τ_m, not q̈.
//
// Discretisation (doc/external_torques.md): the integral by the trapezoid rule over each sample
// interval, with r̂_k, which it contains, solved for in closed form:
//   r̂_k = K (p_k − p_0 − I_{k−1} − Δt (u_{k−1} + u_k + r̂_{k−1}) / 2) / (1 + K Δt / 2),
//   I_k = I_{k−1} + Δt (u_{k−1} + u_k + r̂_{k−1} + r̂_k) / 2.
// That is the bilinear (Tustin) map of the lag: stable for any K Δt, second order in Δt.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>

#include "spatial_dynamics/algorithms/actuator_dynamics.hpp"
#include "spatial_dynamics/algorithms/coriolis.hpp"
#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"

namespace spatial_dynamics {

template <class S>
class MomentumObserver {
 public:
  /// An observer of `model` (which must outlive it) with gain K = diag(gain), one entry (1/s) per
  /// velocity coordinate; a gain that is not positive and finite throws std::invalid_argument
  /// naming its coordinate.
  MomentumObserver(const Model<S>& model, const VectorX<S>& gain)
      : model_(model),
        data_(model),
        gain_(gain),
        p0_(VectorX<S>::Zero(model.nv)),
        integral_(VectorX<S>::Zero(model.nv)),
        input_(VectorX<S>::Zero(model.nv)),
        previous_input_(VectorX<S>::Zero(model.nv)),
        residual_(VectorX<S>::Zero(model.nv)),
        effort_offset_(VectorX<S>::Zero(model.nv)),
        next_residual_(VectorX<S>::Zero(model.nv)),
        next_integral_(VectorX<S>::Zero(model.nv)) {
    detail::check_length("observer gain", gain.size(), model.nv);
    for (int k = 0; k < model.nv; ++k)
      if (!(gain[k] > S(0)) || !(gain[k] - gain[k] == S(0)))
        throw std::invalid_argument("momentum observer: the gain for '" + model.velocityNames()[k] +
                                    "' must be positive and finite (1/s)");
  }

  /// Forget the past: the next update starts afresh (r̂ = 0 there, p_0 its momentum). The tare stays.
  void reset() { started_ = false; }

  /// The current r̂ becomes the zero: it is taken from now on as a constant model error b, added to
  /// the measured effort (u + b), and r̂ continues from zero (p_0 and u_{k−1} shifted to match), so
  /// that r̂ then estimates τ_ext − b. Taring again adds the new r̂ to b.
  void tare() {
    if (!started_) return;
    for (int k = 0; k < model_.nv; ++k) {
      const S r = residual_[k];
      effort_offset_[k] += r;
      previous_input_[k] += r;
      p0_[k] += r / gain_[k];  // K (p − p_0 − I) = 0 now
      residual_[k] = S(0);
    }
  }
  /// Drops the tare: b = 0 (r̂ goes back to the untared estimate over the lag).
  void clear_tare() { effort_offset_.setZero(); }
  /// Sets b (one entry per velocity coordinate), e.g. a tare carried over to a rebuilt model.
  void set_effort_offset(const VectorX<S>& b) {
    detail::check_length("effort offset", b.size(), model_.nv);
    effort_offset_ = b;
  }
  /// b, the sum of the tares.
  const VectorX<S>& effort_offset() const { return effort_offset_; }
  bool started() const { return started_; }

  /// r̂ at the sample (q, q̇, τ_m), dt seconds after the previous one (dt is ignored on the first
  /// update after construction or reset()). A non-finite input, or dt not positive and finite,
  /// throws std::invalid_argument naming it; a result that overflows, std::domain_error naming its
  /// coordinate; either way the observer is left as it was.
  const VectorX<S>& update(const ConstVectorRef<S>& q, const ConstVectorRef<S>& qd,
                           const ConstVectorRef<S>& tau_measured, const S& dt) {
    detail::check_length("q", q.size(), model_.nq);
    detail::check_length("velocity", qd.size(), model_.nv);
    detail::check_length("measured effort", tau_measured.size(), model_.nv);
    if (!(q.allFinite() && qd.allFinite() && tau_measured.allFinite())) {
      check_finite("position", q, false);
      check_finite("velocity", qd, true);
      check_finite("measured effort", tau_measured, true);
    }
    if (started_ && !(dt > S(0) && dt - dt == S(0)))
      throw std::invalid_argument("momentum observer: the time step must be positive and finite");
    momentum_observer_terms(model_, data_, q, qd);  // p, Cᵀ q̇ and g(q) in one pass
    for (int k = 0; k < model_.nv; ++k)  // u = τ_m − τ_a + Cᵀ q̇ − g (+ b)
      input_[k] = tau_measured[k] - detail::actuator_force(model_, k, qd[k]) + data_.coriolis_transpose_velocity[k] -
                  data_.tau[k] + effort_offset_[k];
    check_finite("momentum rate", input_, true, "overflows: an input is too large");
    const VectorX<S>& p = data_.momentum;
    if (!started_) {
      p0_ = p;
      integral_.setZero();
      residual_.setZero();
      previous_input_ = input_;
      started_ = true;
      return residual_;
    }
    const S half_dt = dt / S(2);
    for (int k = 0; k < model_.nv; ++k) {  // into next_*: the state changes only if all is finite
      const S step = half_dt * (previous_input_[k] + input_[k] + residual_[k]);
      next_residual_[k] = gain_[k] * (p[k] - p0_[k] - integral_[k] - step) / (S(1) + gain_[k] * half_dt);
      next_integral_[k] = integral_[k] + step + half_dt * next_residual_[k];
    }
    if ((next_residual_ - next_residual_ + next_integral_ - next_integral_).sum() != S(0)) {  // some entry not finite
      check_finite("estimate", next_residual_, true, "overflows: an input is too large");
      check_finite("integral", next_integral_, true, "overflows: an input is too large");
    }
    residual_.swap(next_residual_);
    integral_.swap(next_integral_);
    previous_input_ = input_;
    return residual_;
  }

  /// The last estimate r̂ (zero before the second update).
  const VectorX<S>& residual() const { return residual_; }
  /// At the last sample: p = M q̇, and u = τ_m − τ_a + Cᵀ q̇ − g (+ b), the momentum rate the model
  /// explains (ṗ = u + τ_ext).
  const VectorX<S>& momentum() const { return data_.momentum; }
  const VectorX<S>& explained_momentum_rate() const { return input_; }
  const Model<S>& model() const { return model_; }

 private:
  /// A non-finite entry of x: std::invalid_argument (an input) or, with `why`, std::domain_error.
  template <class Vector>
  void check_finite(const char* what, const Vector& x, bool velocity_coordinates, const char* why = nullptr) const {
    if (x.allFinite()) return;
    Eigen::Index k = 0;
    while (std::isfinite(static_cast<double>(x[k]))) ++k;
    const std::string name = velocity_coordinates ? model_.velocityNames()[k] : model_.positionNames()[k];
    const std::string message = std::string("momentum observer: the ") + what + " of '" + name + "' is not finite";
    if (why) throw std::domain_error(message + ": it " + why);
    throw std::invalid_argument(message);
  }

  const Model<S>& model_;
  Data<S> data_;
  VectorX<S> gain_, p0_, integral_, input_, previous_input_, residual_, effort_offset_;
  VectorX<S> next_residual_, next_integral_;  // an update's results before they are committed
  bool started_ = false;
};

}  // namespace spatial_dynamics
