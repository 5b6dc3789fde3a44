// Forward dynamics with mixed-precision iterative refinement (Wilkinson; Higham, "Accuracy and
// Stability of Numerical Algorithms", §12.1), for ill-conditioned mass matrices:
//   x₀ = ABA(q, q̇, τ)                                  in S (the model's scalar)
//   r_k = τ − ID(q, q̇, x_k) = τ − h − M x_k             in W, a wider type (long double)
//   δ_k = M⁻¹ r_k                                       in S, reusing ABA's factorisation
//   x_{k+1} = x_k + δ_k                                  in W
// repeated until the correction no longer changes the result (‖δ‖ ≤ ε_S ‖x‖) or stops shrinking,
// or max_iterations corrections were made. Each step gains a factor of about κ(M)·ε_S; the
// limit is the accuracy of the residual, about κ(M)·ε_W relative instead of ABA's κ(M)·ε_S.
// Since ID is linear in q̈, r_{k+1} = r_k − M δ_k: only the first residual needs the velocity
// and gravity terms; the later ones are mass-matrix products (one outward and one inward pass),
// which can even be done in S once δ_k is small enough (see subtract_mass_matrix_product_narrow).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "spatial_dynamics/algorithms/aba.hpp"
#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/joint_kernels.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"

namespace spatial_dynamics {

/// Buffers for aba_refined, allocated once per model (like Data, one per thread). Holds the
/// model in the wider type W; converting double to long double is exact.
template <class S, class W = long double>
struct RefinementWorkspace {
  Model<W> model_wide;
  // Wide residual: per-body transforms, velocities, accelerations, forces; joint-space vectors.
  std::vector<PluckerTransform<W>> X_up_wide;
  std::vector<MotionVector<W>> v_wide;
  std::vector<MotionVector<W>> a_wide;
  std::vector<ForceVector<W>> f_wide;
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

  explicit RefinementWorkspace(const Model<S>& model)
      : model_wide(model.template cast<W>()),
        X_up_wide(model.nbodies()),
        v_wide(model.nbodies(), MotionVector<W>::Zero()),
        a_wide(model.nbodies(), MotionVector<W>::Zero()),
        f_wide(model.nbodies(), ForceVector<W>::Zero()),
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

// The wide passes are written coefficient by coefficient: Eigen's generic kernels for a scalar
// it cannot vectorise (long double) are several times slower than these few lines.

template <class W>
inline Vector3<W> times(const Matrix3<W>& E, const Vector3<W>& x) {  // E x
  return Vector3<W>(E(0, 0) * x[0] + E(0, 1) * x[1] + E(0, 2) * x[2], E(1, 0) * x[0] + E(1, 1) * x[1] + E(1, 2) * x[2],
                    E(2, 0) * x[0] + E(2, 1) * x[1] + E(2, 2) * x[2]);
}
template <class W>
inline Vector3<W> transpose_times(const Matrix3<W>& E, const Vector3<W>& x) {  // Eᵀ x
  return Vector3<W>(E(0, 0) * x[0] + E(1, 0) * x[1] + E(2, 0) * x[2], E(0, 1) * x[0] + E(1, 1) * x[1] + E(2, 1) * x[2],
                    E(0, 2) * x[0] + E(1, 2) * x[1] + E(2, 2) * x[2]);
}
template <class W>
inline Vector3<W> cross3(const Vector3<W>& a, const Vector3<W>& b) {
  return Vector3<W>(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
}
/// X m = (E ω ; E (v − r×ω))   (eq. 11)
template <class W>
inline MotionVector<W> apply_wide(const PluckerTransform<W>& X, const MotionVector<W>& m) {
  return {times(X.E, m.angular), times(X.E, Vector3<W>(m.linear - cross3(X.r, m.angular)))};
}
/// Xᵀ f = (Eᵀ n + r × Eᵀ f ; Eᵀ f)
template <class W>
inline ForceVector<W> apply_transpose_wide(const PluckerTransform<W>& X, const ForceVector<W>& f) {
  const Vector3<W> lin = transpose_times(X.E, f.linear);
  return {Vector3<W>(transpose_times(X.E, f.angular) + cross3(X.r, lin)), lin};
}
/// I v = (Ī_O ω + h×v ; m v − h×ω)   (eq. 25)
template <class W>
inline ForceVector<W> inertia_times_wide(const RigidInertia<W>& I, const MotionVector<W>& v) {
  return {Vector3<W>(times(I.rotational_inertia, v.angular) + cross3(I.first_moment, v.linear)),
          Vector3<W>(I.mass * v.linear - cross3(I.first_moment, v.angular))};
}
/// v ×* f = (ω×n + v×f ; ω×f)   (eq. 18)
template <class W>
inline ForceVector<W> force_cross_wide(const MotionVector<W>& v, const ForceVector<W>& f) {
  return {Vector3<W>(cross3(v.angular, f.angular) + cross3(v.linear, f.linear)), cross3(v.angular, f.linear)};
}

/// sin x and cos x in W. For long double: Cody–Waite reduction x = k π/2 + y (π/2 split into
/// three pieces of ≤ 33 bits, so k·piece is exact for |k| < 2^31) and Taylor series on
/// |y| ≤ π/4, whose truncation (|y|²³/23! < 2e-25) is below long double's ε; glibc's sinl and
/// cosl take several times longer. Other types use their own sin and cos.
template <class W>
inline void sin_cos_wide(const W& x, W& s, W& c) {
  using std::cos;
  using std::sin;
  s = sin(x);
  c = cos(x);
}
/// (−1)^j / (2j + offset)! for j = 0 … count−1: Taylor coefficients of sin (offset 1) and cos (0).
template <int count>
constexpr std::array<long double, count> alternating_inverse_factorials(int offset) {
  std::array<long double, count> c{};
  long double factorial = 1.0L;
  int n = 1;
  for (int j = 0; j < count; ++j) {
    for (; n <= 2 * j + offset; ++n) factorial *= n;  // exact: the odd part of 22! has 52 bits
    c[j] = (j % 2 ? -1.0L : 1.0L) / factorial;
  }
  return c;
}

inline void sin_cos_wide(const long double& x, long double& s, long double& c) {
  if (!(x <= 1e5L && x >= -1e5L)) {
    s = std::sin(x);
    c = std::cos(x);
    return;
  }
  constexpr long double pio2_1 = 1.57079632673412561417e+00L;   // 0x3FF921FB 54400000 (fdlibm)
  constexpr long double pio2_2 = 6.07710050630396597660e-11L;   // 0x3DD0B461 1A600000
  constexpr long double pio2_3 = 2.02226624871116645580e-21L;   // 0x3BA3198A 2E000000
  constexpr long double pio2_3t = 8.47842766036889956997e-32L;  // π/2 − pio2_1 − pio2_2 − pio2_3
  constexpr long double two_over_pi = 0.636619772367581343075535053490057448L;
  static constexpr std::array<long double, 11> sin_coefficients = alternating_inverse_factorials<11>(1);
  static constexpr std::array<long double, 12> cos_coefficients = alternating_inverse_factorials<12>(0);
  const long long quadrant = static_cast<long long>(x * two_over_pi + (x < 0 ? -0.5L : 0.5L));  // round(x 2/π)
  const long double k = static_cast<long double>(quadrant);
  const long double y = (((x - k * pio2_1) - k * pio2_2) - k * pio2_3) - k * pio2_3t;
  const long double z = y * y;
  long double ps = sin_coefficients[10], pc = cos_coefficients[11];
  for (int j = 9; j >= 0; --j) ps = sin_coefficients[j] + z * ps;   // sin y = y Σ (−z)^j/(2j+1)!
  for (int j = 10; j >= 0; --j) pc = cos_coefficients[j] + z * pc;  // cos y = Σ (−z)^j/(2j)!
  const long double sy = y * ps;
  switch (quadrant & 3) {  // x = k π/2 + y
    case 0: s = sy; c = pc; return;
    case 1: s = pc; c = -sy; return;
    case 2: s = -sy; c = -pc; return;
    default: s = -pc; c = sy; return;
  }
}

/// ^iX_λ(i) in W, as joint_up_transform computes it, with the products written out.
template <class W>
inline void wide_up_transform(const Model<W>& model, int i, const W* q, PluckerTransform<W>& X) {
  const Joint<W>& j = model.joints[i];
  if (j.type != JointType::Revolute) {
    joint_up_transform(model, i, q, X);
    return;
  }
  W c, s;
  sin_cos_wide(q[0], s, c);
  const PluckerTransform<W>& Xt = model.X_tree[i];
  X.r = Xt.r;
  switch (j.axis_kind) {
    case AxisKind::X: X.E = Xt.E; rotate_rows(X.E, 1, 2, c, s); return;
    case AxisKind::Y: X.E = Xt.E; rotate_rows(X.E, 2, 0, c, s); return;
    case AxisKind::Z: X.E = Xt.E; rotate_rows(X.E, 0, 1, c, s); return;
    default: {
      // E_J = c 1 − s a× + (1 − c) a aᵀ (RBDA eq. 2.24, transposed); E = E_J E_tree.
      const Vector3<W>& a = j.axis;
      const W t = W(1) - c;
      Matrix3<W> EJ;
      EJ(0, 0) = c + t * a[0] * a[0];        EJ(0, 1) = s * a[2] + t * a[0] * a[1]; EJ(0, 2) = -s * a[1] + t * a[0] * a[2];
      EJ(1, 0) = -s * a[2] + t * a[1] * a[0]; EJ(1, 1) = c + t * a[1] * a[1];       EJ(1, 2) = s * a[0] + t * a[1] * a[2];
      EJ(2, 0) = s * a[1] + t * a[2] * a[0];  EJ(2, 1) = -s * a[0] + t * a[2] * a[1]; EJ(2, 2) = c + t * a[2] * a[2];
      for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col)
          X.E(row, col) = EJ(row, 0) * Xt.E(0, col) + EJ(row, 1) * Xt.E(1, col) + EJ(row, 2) * Xt.E(2, col);
      return;
    }
  }
}

/// r = τ − ID(q, q̇, x) in W (RBDA Table 5.1), keeping the wide transforms for later products.
template <class S, class W>
void wide_residual(RefinementWorkspace<S, W>& ws, const ConstVectorRef<S>& tau) {
  const Model<W>& m = ws.model_wide;
  ws.v_wide[0] = MotionVector<W>::Zero();
  ws.a_wide[0] = MotionVector<W>(Vector3<W>::Zero(), -m.gravity);                 // a_0 = −a_g
  for (int i = 1; i < m.nbodies(); ++i) {
    const Joint<W>& j = m.joints[i];
    const int lambda = m.parent[i];
    wide_up_transform(m, i, ws.q_wide.data() + j.idx_q, ws.X_up_wide[i]);
    const MotionVector<W> vJ = joint_motion(j, ws.qd_wide.data() + j.idx_v);
    const MotionVector<W>& v = ws.v_wide[i] = apply_wide(ws.X_up_wide[i], ws.v_wide[lambda]) + vJ;  // v_i = X v_λ + S q̇
    ws.a_wide[i] = apply_wide(ws.X_up_wide[i], ws.a_wide[lambda]) + joint_motion(j, ws.x_wide.data() + j.idx_v) +
                   MotionVector<W>(cross3(v.angular, vJ.angular),
                                   Vector3<W>(cross3(v.angular, vJ.linear) + cross3(v.linear, vJ.angular)));  // + v × S q̇
    ws.f_wide[i] = inertia_times_wide(m.inertia[i], ws.a_wide[i]) +
                   force_cross_wide(v, inertia_times_wide(m.inertia[i], v));        // f = I a + v ×* I v (eq. 29)
  }
  for (int i = m.nbodies() - 1; i >= 1; --i) {
    const Joint<W>& j = m.joints[i];
    joint_project(j, ws.f_wide[i], ws.residual_wide.data() + j.idx_v);              // Sᵀ f_i
    if (m.parent[i] > 0) ws.f_wide[m.parent[i]] += apply_transpose_wide(ws.X_up_wide[i], ws.f_wide[i]);  // f_λ += Xᵀ f
  }
  for (int k = 0; k < m.nv; ++k) ws.residual_wide[k] = W(tau[k]) - ws.residual_wide[k];
}

/// r ← r − M δ in W: the RNEA without velocity and gravity (a_i = X a_λ + S δ, f_i = I a_i).
template <class S, class W>
void subtract_mass_matrix_product(RefinementWorkspace<S, W>& ws) {
  const Model<W>& m = ws.model_wide;
  ws.a_wide[0] = MotionVector<W>::Zero();
  for (int i = 1; i < m.nbodies(); ++i) {
    const Joint<W>& j = m.joints[i];
    ws.a_wide[i] = apply_wide(ws.X_up_wide[i], ws.a_wide[m.parent[i]]) + joint_motion(j, ws.delta_wide.data() + j.idx_v);
    ws.f_wide[i] = inertia_times_wide(m.inertia[i], ws.a_wide[i]);
  }
  W column[6];
  for (int i = m.nbodies() - 1; i >= 1; --i) {
    const Joint<W>& j = m.joints[i];
    joint_project(j, ws.f_wide[i], column);
    for (int k = 0; k < j.nv; ++k) ws.residual_wide[j.idx_v + k] -= column[k];
    if (m.parent[i] > 0) ws.f_wide[m.parent[i]] += apply_transpose_wide(ws.X_up_wide[i], ws.f_wide[i]);
  }
}

/// r ← r − M δ with the product in S (the model's transforms in data.X_up), for a correction so
/// small that the product's rounding, ε_S ‖M‖ ‖δ‖, stays below the wide residual's ε_W ‖M‖ ‖x‖.
template <class S, class W>
void subtract_mass_matrix_product_narrow(const Model<S>& model, const Data<S>& data, RefinementWorkspace<S, W>& ws) {
  const int n = model.nbodies();
  ws.a[0] = MotionVector<S>::Zero();
  for (int i = 1; i < n; ++i) {
    const Joint<S>& j = model.joints[i];
    ws.a[i] = data.X_up[i].apply(ws.a[model.parent[i]]) + joint_motion(j, ws.delta.data() + j.idx_v);  // a = X a_λ + S δ
    ws.p[i] = model.inertia[i] * ws.a[i];                                                            // f = I a
  }
  S column[6];
  for (int i = n - 1; i >= 1; --i) {
    const Joint<S>& j = model.joints[i];
    joint_project(j, ws.p[i], column);
    for (int k = 0; k < j.nv; ++k) ws.residual_wide[j.idx_v + k] -= W(column[k]);
    if (model.parent[i] > 0) ws.p[model.parent[i]] += data.X_up[i].applyInverse(ws.p[i]);         // f_λ += Xᵀ f
  }
}

/// δ = M⁻¹ r by the factorisation the last aba() call left in data (U = Iᴬ S, D⁻¹, X_up):
/// ABA's passes 2 and 3 with no velocity, no gravity and joint forces r (RBDA Table 7.1).
template <class S, class W>
void solve_with_aba_factorisation(const Model<S>& model, const Data<S>& data, RefinementWorkspace<S, W>& ws) {
  const int n = model.nbodies();
  for (int i = 1; i < n; ++i) ws.p[i] = ForceVector<S>::Zero();
  for (int i = n - 1; i >= 1; --i) {
    const Joint<S>& j = model.joints[i];
    const int lambda = model.parent[i];
    if (j.nv == 1) {
      const S u = ws.residual[j.idx_v] - joint_project(j, ws.p[i].toVector());          // u = r − Sᵀ pᴬ
      ws.u[i][0] = u;
      if (lambda > 0) {
        const Vector6<S> pa = ws.p[i].toVector() + data.U[i].col(0) * (u * data.D_inv[i](0, 0));  // pᵃ = pᴬ + U D⁻¹ u
        ws.p[lambda] += data.X_up[i].applyInverse(ForceVector<S>(pa));                 // pᴬ_λ += Xᵀ pᵃ
      }
    } else {
      ws.u[i] = ws.residual.template segment<6>(j.idx_v) - ws.p[i].toVector();
    }
  }
  ws.a[0] = MotionVector<S>::Zero();
  for (int i = 1; i < n; ++i) {
    const Joint<S>& j = model.joints[i];
    const MotionVector<S> a_prime = data.X_up[i].apply(ws.a[model.parent[i]]);
    const Vector6<S> ap = a_prime.toVector();
    if (j.nv == 1) {
      const S d = data.D_inv[i](0, 0) * (ws.u[i][0] - data.U[i].col(0).dot(ap));        // δ = D⁻¹(u − Uᵀ a')
      ws.delta[j.idx_v] = d;
      ws.a[i] = a_prime + joint_motion(j, &d);
    } else {
      const Vector6<S> d = data.D_inv[i] * (ws.u[i] - data.U[i].transpose() * ap);
      ws.delta.template segment<6>(j.idx_v) = d;
      ws.a[i] = a_prime + MotionVector<S>(d);
    }
  }
}

}  // namespace detail

/// q̈ = FD(q, q̇, τ) refined as above. Result in data.qdd (rounded once from the wide iterate);
/// ws.iterations tells how many corrections were applied. Throws as aba() does.
template <class S, class W>
const VectorX<S>& aba_refined(const Model<S>& model, Data<S>& data, RefinementWorkspace<S, W>& ws,
                              const ConstVectorRef<S>& q, const ConstVectorRef<S>& qd,
                              const ConstVectorRef<S>& tau, int max_iterations = 8) {
  using std::sqrt;
  aba(model, data, q, qd, tau);
  for (int k = 0; k < model.nq; ++k) ws.q_wide[k] = W(q[k]);
  for (int k = 0; k < model.nv; ++k) {
    ws.qd_wide[k] = W(qd[k]);
    ws.x_wide[k] = W(data.qdd[k]);
  }
  detail::wide_residual(ws, tau);
  const S eps = Eigen::NumTraits<S>::epsilon();
  const S eps_ratio = S(Eigen::NumTraits<W>::epsilon() / W(eps));
  S previous = std::numeric_limits<S>::infinity();
  ws.iterations = 0;
  for (int it = 0; it < max_iterations; ++it) {
    for (int k = 0; k < model.nv; ++k) ws.residual[k] = S(ws.residual_wide[k]);
    detail::solve_with_aba_factorisation(model, data, ws);
    const S size = ws.delta.norm();
    if (!(size < previous)) break;  // no longer improving (or not finite): keep x_k
    for (int k = 0; k < model.nv; ++k) {
      ws.delta_wide[k] = W(ws.delta[k]);
      ws.x_wide[k] += ws.delta_wide[k];
    }
    ++ws.iterations;
    S x_size(0);
    for (int k = 0; k < model.nv; ++k) x_size += S(ws.x_wide[k]) * S(ws.x_wide[k]);
    if (size <= eps * sqrt(x_size)) break;  // the correction is below the result's resolution
    previous = size;
    // r_{k+1} = r_k − M δ_k: in W, or in S once ‖δ‖ ≤ (ε_W/ε_S) ‖x‖ makes that as accurate.
    if (size <= eps_ratio * sqrt(x_size)) detail::subtract_mass_matrix_product_narrow(model, data, ws);
    else detail::subtract_mass_matrix_product(ws);
  }
  for (int k = 0; k < model.nv; ++k) data.qdd[k] = S(ws.x_wide[k]);
  return data.qdd;
}

}  // namespace spatial_dynamics
