// Forward dynamics with mixed-precision iterative refinement (Wilkinson; Higham, "Accuracy and
// Stability of Numerical Algorithms", §12.1), for ill-conditioned mass matrices:
//   x₀ = ABA(q, q̇, τ)                                  in S (the model's scalar)
//   r_k = τ − ID(q, q̇, x_k) = τ − h − M x_k             in W, a wider type (double-double
//                                                       or long double: DefaultResidualScalar)
//   δ_k = M⁻¹ r_k                                       in S, reusing ABA's factorisation
//   x_{k+1} = x_k + δ_k                                  in W
// Each solve in S has a relative error of about ρ = κ(M)·ε_S, which the first correction
// measures (‖δ₀‖/‖x‖ is x₀'s error). The loop stops when the correction no longer changes the
// result (‖δ‖ ≤ ε_S ‖x‖), when the next one, about ρ‖δ‖, would not (Higham eq. 12.7), when
// the corrections stop shrinking, or after max_iterations. The limit is the residual's
// accuracy, about ρ·ε_W/ε_S relative instead of ABA's ρ. Where that exceeds ε_S (κ(M) beyond
// about ε_S/ε_W: 2000 in double with long double residuals, 1e6 with double-double ones), the
// overload with a second workspace goes on with a residual in a finer type F (float128) from
// the wide iterate: dearer per step, and taken only by those calls.
// Since ID is linear in q̈, r_{k+1} = r_k − M δ_k: only the first residual needs the velocity
// and gravity terms; the later ones are mass-matrix products M δ = ID(q, 0, δ) without gravity,
// which can even be done in S once δ_k is small enough (see subtract_mass_matrix_product_narrow).
// Both are the RNEA (rnea.hpp), instantiated in W or in S.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

#include "spatial_dynamics/algorithms/aba.hpp"
#include "spatial_dynamics/algorithms/rnea.hpp"
#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/model/joints/body_joint.hpp"
#include "spatial_dynamics/compiled/compiled_functions.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/simd_backend.hpp"
#include "spatial_dynamics/spatial/number/double_double.hpp"

namespace spatial_dynamics {

/// The residual's wide type by default: double-double, whose arithmetic runs several times faster
/// than long double's x87 code where the CPU has a fused multiply-add, which the compiled
/// library's AVX2 build uses (simd_backend.hpp). Without FMA its exact products take Dekker's
/// splitting and cost more than x87's: RefinementWorkspace<S, long double> is the cheaper choice
/// for the portable build on such a CPU.
using DefaultResidualScalar = DoubleDouble;

/// Buffers for aba_refined, allocated once per model (like Data, one per thread). Holds the
/// model in the wider type W; converting double to long double or double-double is exact.
template <class S, class W = DefaultResidualScalar>
struct RefinementWorkspace {
  Model<W> model_wide;
  Data<W> data_wide;    // the RNEA's buffers in W: residuals and products M δ
  Data<S> data_narrow;  // the RNEA's buffers in S: products M δ of small corrections
  VectorX<W> q_wide, qd_wide;
  VectorX<W> x_wide;         // the refined accelerations x_k
  VectorX<W> residual_wide;  // r_k
  VectorX<W> delta_wide;     // δ_k converted to W (exactly)
  // Narrow correction solve M δ = r by the articulated-body factorisation.
  std::vector<ForceVector<S>> p;
  std::vector<MotionVector<S>> a;
  std::vector<Vector6<S>> u;
  VectorX<S> residual, delta;
  int iterations = 0;  // corrections applied by the last call
  S first_correction = S(0);  // ‖δ₀‖/‖x‖ of the last call: the unrefined result's relative error
  S effort_norm = S(0);       // ‖τ‖ of the last call
  S rate = S(0);              // ρ, one solve's relative error, as the last call estimated it

  explicit RefinementWorkspace(const Model<S>& model)
      : model_wide(model.template cast<W>()),
        data_wide(model_wide),
        data_narrow(model),
        q_wide(VectorX<W>::Zero(model.nq)),
        qd_wide(VectorX<W>::Zero(model.nv)),
        x_wide(VectorX<W>::Zero(model.nv)),
        residual_wide(VectorX<W>::Zero(model.nv)),
        delta_wide(VectorX<W>::Zero(model.nv)),
        p(model.nbodies(), ForceVector<S>::Zero()),
        a(model.nbodies(), MotionVector<S>::Zero()),
        u(model.nbodies(), Vector6<S>::Zero()),
        residual(VectorX<S>::Zero(model.nv)),
        delta(VectorX<S>::Zero(model.nv)) {}
};

namespace detail {

/// The relative accuracy ε_W of a residual computed in W: W's rounding, except for double-double,
/// whose arithmetic (2^-104) is finer than its sines and cosines (1.3e-22 absolute at worst,
/// test_double_double): 2^-72 = 2.1e-22.
template <class W>
W residual_epsilon() {
  if constexpr (std::is_same<W, DoubleDouble>::value) return W(0x1p-72);
  else return Eigen::NumTraits<W>::epsilon();
}

/// x in a wider type F, exactly (double-double: the sum of its parts, rounded once in F).
template <class F, class W>
F widen(const W& x) {
  if constexpr (std::is_same<W, DoubleDouble>::value) return F(x.hi) + F(x.lo);
  else return F(x);
}

/// ID(q, q̇, q̈) in W (RBDA Table 5.1) at the workspace's q, under gravity or none: the RNEA on
/// the wide model.
template <class S, class W>
const VectorX<W>& wide_inverse_dynamics(const Model<S>& model, RefinementWorkspace<S, W>& ws, const VectorX<W>& qd,
                                        const VectorX<W>& qdd, bool with_gravity) {
  static_cast<void>(model);
  const Vector3<W> gravity = with_gravity ? ws.model_wide.gravity : Vector3<W>(Vector3<W>::Zero());
  return rnea_impl(ws.model_wide, ws.data_wide, ws.q_wide, qd, qdd, static_cast<const ForceVector<W>*>(nullptr), gravity);
}

/// r₀ = τ − ID(q, q̇, x₀) in W.
template <class S, class W>
void wide_residual(const Model<S>& model, const ConstVectorRef<S>& tau, RefinementWorkspace<S, W>& ws) {
  const VectorX<W>& id = wide_inverse_dynamics(model, ws, ws.qd_wide, ws.x_wide, true);
  for (int k = 0; k < ws.model_wide.nv; ++k) ws.residual_wide[k] = W(tau[k]) - id[k];
}

/// r ← r − M δ in W: M δ = ID(q, 0, δ) without gravity (RBDA eq. 5.1).
template <class S, class W>
void subtract_mass_matrix_product(const Model<S>& model, RefinementWorkspace<S, W>& ws) {
  const VectorX<W>& product = wide_inverse_dynamics(model, ws, ws.data_wide.zero_v, ws.delta_wide, false);
  for (int k = 0; k < ws.model_wide.nv; ++k) ws.residual_wide[k] -= product[k];
}

/// r ← r − M δ with the product in S, for a correction so small that the product's rounding,
/// ε_S ‖M‖ ‖δ‖, stays below the wide residual's ε_W ‖M‖ ‖x‖.
template <class S, class W>
void subtract_mass_matrix_product_narrow(const Model<S>& model, const ConstVectorRef<S>& q,
                                         RefinementWorkspace<S, W>& ws) {
  const VectorX<S>& product = mass_matrix_times(model, ws.data_narrow, q, ws.delta);
  for (int k = 0; k < model.nv; ++k) ws.residual_wide[k] -= W(product[k]);
}

/// δ = M⁻¹ r by the factorisation the last aba() call left in data (U = Iᴬ S, D⁻¹, X_up):
/// ABA's passes 2 and 3 (aba.hpp) with no velocity, no gravity and joint forces r (RBDA Table 7.1).
template <class S, class W>
void solve_with_aba_factorisation(const Model<S>& model, const Data<S>& data, RefinementWorkspace<S, W>& ws) {
  for (int i = 1; i < model.nbodies(); ++i) ws.p[i] = ForceVector<S>::Zero();
  for (int i = model.nbodies() - 1; i >= 1; --i)
    articulated_force_step(model, data, i, ws.residual.data(), ws.p.data(), ws.u.data(), static_cast<const ForceVector<S>*>(nullptr));
  ws.a[0] = MotionVector<S>::Zero();
  articulated_acceleration_pass(model, data, static_cast<const MotionVector<S>*>(nullptr), ws.u.data(), ws.a.data(), ws.delta.data());
}

/// Corrections x ← x + M⁻¹ r with residuals in W, from the iterate in ws.x_wide and its
/// residual in ws.residual_wide. `rate` is one solve's relative error ρ ≈ κ(M) ε_S: when zero on
/// entry, the first correction measures it. Leaves the iterate in ws.x_wide and the number of
/// corrections in ws.iterations.
template <class S, class W>
void refine(const Model<S>& model, const Data<S>& data, RefinementWorkspace<S, W>& ws, const ConstVectorRef<S>& q,
            int max_iterations, S& rate) {
  using std::sqrt;
  const S eps = Eigen::NumTraits<S>::epsilon();
  const S eps_ratio = S(residual_epsilon<W>() / W(eps));  // ε_W / ε_S
  S previous = std::numeric_limits<S>::infinity();
  ws.iterations = 0;
  ws.first_correction = S(0);
  for (int it = 0; it < max_iterations; ++it) {
    for (int k = 0; k < model.nv; ++k) ws.residual[k] = S(ws.residual_wide[k]);
    const S residual_size = ws.residual.norm();
    solve_with_aba_factorisation(model, data, ws);
    const S size = ws.delta.norm();
    if (!(size < previous)) break;  // no longer improving (or not finite): keep x_k
    for (int k = 0; k < model.nv; ++k) {
      ws.delta_wide[k] = W(ws.delta[k]);
      ws.x_wide[k] += ws.delta_wide[k];
    }
    ++ws.iterations;
    S x_size(0);
    for (int k = 0; k < model.nv; ++k) x_size += S(ws.x_wide[k]) * S(ws.x_wide[k]);
    x_size = sqrt(x_size);
    if (it == 0) ws.first_correction = size / x_size;
    // ρ from x₀'s relative error ‖δ₀‖/‖x‖, and at least ε ‖M⁻¹‖ ‖τ‖/‖x‖ (‖M⁻¹‖ ≈ ‖δ₀‖/‖r₀‖), the
    // rounding of τ's own size that the residuals carry: the ABA splits gravity off (gravity_split.hpp),
    // so x₀ can be far more accurate than a solve of a residual whose forces cancel (τ ≈ h).
    if (rate == S(0)) rate = std::max(size / x_size, eps * (size / residual_size) * ws.effort_norm / x_size);
    if (size <= eps * x_size) break;         // the correction is below the result's resolution
    // The next correction, about ρ‖δ‖, would be below the resolution (with a margin of 32 for
    // ρ measured on one right-hand side), or this one is already at the residual's noise level
    // (ρ·ε_W/ε_S ‖x‖), so the next could not improve on it.
    if (rate * size <= eps / S(32) * x_size || size <= rate * eps_ratio * x_size) break;
    previous = size;
    // r_{k+1} = r_k − M δ_k: in W, or in S once ‖δ‖ ≤ (ε_W/ε_S) ‖x‖ makes that as accurate.
    if (size <= eps_ratio * x_size) subtract_mass_matrix_product_narrow(model, q, ws);
    else subtract_mass_matrix_product(model, ws);
  }
}

/// x₀ = ABA(q, q̇, τ), then r₀ = τ − ID(q, q̇, x₀) in W.
template <class S, class W>
void aba_with_wide_residual(const Model<S>& model, Data<S>& data, RefinementWorkspace<S, W>& ws,
                            const ConstVectorRef<S>& q, const ConstVectorRef<S>& qd, const ConstVectorRef<S>& tau) {
  aba<S>(model, data, q, qd, tau);
  ws.effort_norm = tau.norm();
  for (int k = 0; k < model.nq; ++k) ws.q_wide[k] = W(q[k]);
  for (int k = 0; k < model.nv; ++k) {
    ws.qd_wide[k] = W(qd[k]);
    ws.x_wide[k] = W(data.qdd[k]);
  }
  wide_residual(model, tau, ws);
}

}  // namespace detail

/// q̈ = FD(q, q̇, τ) refined as above with residuals in W. Result in data.qdd (rounded once from
/// the wide iterate); ws.iterations tells how many corrections were applied. Throws as aba() does.
template <class S, class W>
const VectorX<S>& aba_refined(const Model<S>& model, Data<S>& data, RefinementWorkspace<S, W>& ws,
                              const ConstVectorRef<S>& q, const ConstVectorRef<S>& qd,
                              const ConstVectorRef<S>& tau, int max_iterations = 8) {
  detail::aba_with_wide_residual(model, data, ws, q, qd, tau);
  ws.rate = S(0);
  detail::refine(model, data, ws, q, max_iterations, ws.rate);
  for (int k = 0; k < model.nv; ++k) data.qdd[k] = S(ws.x_wide[k]);
  return data.qdd;
}

/// As above, and where the W residual cannot resolve the result to S's rounding (ρ·ε_W/ε_S >
/// ε_S), the refinement goes on from the W iterate with residuals in F (e.g. Quad from
/// reference/high_precision.hpp, whose ε_F makes the limit ρ·ε_F/ε_S negligible).
/// fine.iterations is 0 when the W residual sufficed.
template <class S, class W, class F>
const VectorX<S>& aba_refined(const Model<S>& model, Data<S>& data, RefinementWorkspace<S, W>& ws,
                              RefinementWorkspace<S, F>& fine, const ConstVectorRef<S>& q,
                              const ConstVectorRef<S>& qd, const ConstVectorRef<S>& tau, int max_iterations = 8) {
  aba_refined(model, data, ws, q, qd, tau, max_iterations);  // the library's build for double
  fine.iterations = 0;
  S rate = ws.rate;
  const S eps = Eigen::NumTraits<S>::epsilon();
  if (rate * S(detail::residual_epsilon<W>() / W(eps)) > eps) {
    for (int k = 0; k < model.nq; ++k) fine.q_wide[k] = F(q[k]);
    for (int k = 0; k < model.nv; ++k) {
      fine.qd_wide[k] = F(qd[k]);
      fine.x_wide[k] = detail::widen<F>(ws.x_wide[k]);  // exact when F is wider than W
    }
    detail::wide_residual(model, tau, fine);
    detail::refine(model, data, fine, q, max_iterations, rate);
    for (int k = 0; k < model.nv; ++k) data.qdd[k] = S(fine.x_wide[k]);
  }
  return data.qdd;
}

}  // namespace spatial_dynamics
