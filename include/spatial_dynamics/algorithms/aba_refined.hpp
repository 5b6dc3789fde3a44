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
// and gravity terms; the later ones are mass-matrix products (one outward and one inward pass),
// which can even be done in S once δ_k is small enough (see subtract_mass_matrix_product_narrow).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

#include "spatial_dynamics/algorithms/aba.hpp"
#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/joint_kernels.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/simd_backend.hpp"
#include "spatial_dynamics/spatial/double_double.hpp"

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
  // Wide residual: per-body transforms, velocities, accelerations, forces; joint-space vectors.
  std::vector<PluckerTransform<W>> X_up_wide;
  std::vector<MotionVector<W>> v_wide;
  std::vector<MotionVector<W>> a_wide;
  std::vector<ForceVector<W>> f_wide;
  std::vector<W> sin_wide, cos_wide;  // each joint angle's sine and cosine in W (0 and 1 for other bodies)
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
        X_up_wide(model.nbodies()),
        v_wide(model.nbodies(), MotionVector<W>::Zero()),
        a_wide(model.nbodies(), MotionVector<W>::Zero()),
        f_wide(model.nbodies(), ForceVector<W>::Zero()),
        sin_wide(model.nbodies(), W(0)),
        cos_wide(model.nbodies(), W(1)),
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

// The wide passes are written coefficient by coefficient, into their destinations: Eigen's
// generic kernels for a scalar it cannot vectorise (long double, double-double) are several
// times slower, and with x87 arithmetic every temporary vector costs 80-bit stores and loads,
// dearer than the arithmetic itself. A parameter of scalar P (the model's own double) enters
// the products as it is: long double arithmetic loads it exactly and more cheaply than a stored
// long double, and double-double's mixed products skip the cross terms of its zero low part.

template <class P, class W>
inline Vector3<W> cross3(const Vector3<P>& a, const Vector3<W>& b) {
  return Vector3<W>(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
}
/// out = X m = (E ω ; E (v − r×ω))   (eq. 11); out must not be m.
template <class W>
inline void apply_wide_into(const PluckerTransform<W>& X, const MotionVector<W>& m, MotionVector<W>& out) {
  const Matrix3<W>& E = X.E;
  const Vector3<W>& r = X.r;
  const W t0 = m.linear[0] - (r[1] * m.angular[2] - r[2] * m.angular[1]);
  const W t1 = m.linear[1] - (r[2] * m.angular[0] - r[0] * m.angular[2]);
  const W t2 = m.linear[2] - (r[0] * m.angular[1] - r[1] * m.angular[0]);
  for (int row = 0; row < 3; ++row) {
    out.angular[row] = E(row, 0) * m.angular[0] + E(row, 1) * m.angular[1] + E(row, 2) * m.angular[2];
    out.linear[row] = E(row, 0) * t0 + E(row, 1) * t1 + E(row, 2) * t2;
  }
}
/// out += Xᵀ f = (Eᵀ n + r × Eᵀ f ; Eᵀ f); out must not be f.
template <class W>
inline void add_apply_transpose_wide(const PluckerTransform<W>& X, const ForceVector<W>& f, ForceVector<W>& out) {
  const Matrix3<W>& E = X.E;
  const Vector3<W>& r = X.r;
  const W l0 = E(0, 0) * f.linear[0] + E(1, 0) * f.linear[1] + E(2, 0) * f.linear[2];
  const W l1 = E(0, 1) * f.linear[0] + E(1, 1) * f.linear[1] + E(2, 1) * f.linear[2];
  const W l2 = E(0, 2) * f.linear[0] + E(1, 2) * f.linear[1] + E(2, 2) * f.linear[2];
  out.linear[0] += l0;
  out.linear[1] += l1;
  out.linear[2] += l2;
  out.angular[0] += E(0, 0) * f.angular[0] + E(1, 0) * f.angular[1] + E(2, 0) * f.angular[2] + (r[1] * l2 - r[2] * l1);
  out.angular[1] += E(0, 1) * f.angular[0] + E(1, 1) * f.angular[1] + E(2, 1) * f.angular[2] + (r[2] * l0 - r[0] * l2);
  out.angular[2] += E(0, 2) * f.angular[0] + E(1, 2) * f.angular[1] + E(2, 2) * f.angular[2] + (r[0] * l1 - r[1] * l0);
}
/// f += I a, I a = (Ī_O ω + h×v ; m v − h×ω)   (eq. 25)
template <class P, class W>
inline void add_inertia_times_wide(const RigidInertia<P>& I, const MotionVector<W>& a, ForceVector<W>& f) {
  const Matrix3<P>& J = I.rotational_inertia;
  const Vector3<P>& h = I.first_moment;
  const Vector3<W>& w = a.angular;
  const Vector3<W>& v = a.linear;
  for (int row = 0; row < 3; ++row) {
    const int r1 = row == 2 ? 0 : row + 1, r2 = row == 0 ? 2 : row - 1;  // (row, r1, r2) cyclic
    f.angular[row] += J(row, 0) * w[0] + J(row, 1) * w[1] + J(row, 2) * w[2] + (h[r1] * v[r2] - h[r2] * v[r1]);
    f.linear[row] += I.mass * v[row] - (h[r1] * w[r2] - h[r2] * w[r1]);
  }
}
/// f = v ×* I v = (ω×n + v×p ; ω×p) with (n ; p) = I v   (eqs. 18, 25)
template <class P, class W>
inline void bias_force_wide(const RigidInertia<P>& I, const MotionVector<W>& velocity, ForceVector<W>& f) {
  const Matrix3<P>& J = I.rotational_inertia;
  const Vector3<P>& h = I.first_moment;
  const Vector3<W>& w = velocity.angular;
  const Vector3<W>& v = velocity.linear;
  const W p0 = I.mass * v[0] - (h[1] * w[2] - h[2] * w[1]);
  const W p1 = I.mass * v[1] - (h[2] * w[0] - h[0] * w[2]);
  const W p2 = I.mass * v[2] - (h[0] * w[1] - h[1] * w[0]);
  f.linear[0] = w[1] * p2 - w[2] * p1;
  f.linear[1] = w[2] * p0 - w[0] * p2;
  f.linear[2] = w[0] * p1 - w[1] * p0;
  const W n0 = J(0, 0) * w[0] + J(0, 1) * w[1] + J(0, 2) * w[2] + (h[1] * v[2] - h[2] * v[1]);
  const W n1 = J(1, 0) * w[0] + J(1, 1) * w[1] + J(1, 2) * w[2] + (h[2] * v[0] - h[0] * v[2]);
  const W n2 = J(2, 0) * w[0] + J(2, 1) * w[1] + J(2, 2) * w[2] + (h[0] * v[1] - h[1] * v[0]);
  f.angular[0] = (w[1] * n2 - w[2] * n1) + (v[1] * p2 - v[2] * p1);
  f.angular[1] = (w[2] * n0 - w[0] * n2) + (v[2] * p0 - v[0] * p2);
  f.angular[2] = (w[0] * n1 - w[1] * n0) + (v[0] * p1 - v[1] * p0);
}

/// sin x and cos x in W. For long double: Cody–Waite reduction x = k π/2 + y (π/2 split into
/// three pieces of ≤ 33 bits, so k·piece is exact for |k| < 2^31) and Taylor series of ten terms
/// on |y| ≤ π/4, whose truncations (|y|²¹/21! < 2e-22 for sin, |y|²⁰/20! < 4e-21 for cos) are
/// below long double's ε. k is rounded in double (exact to within 1e-11 of x 2/π for |x| ≤ 1e5,
/// so |y| stays within π/4 + 2e-11), which avoids the x87 rounding-mode switch; glibc's sinl and
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
  static constexpr std::array<long double, 10> sin_coefficients = alternating_inverse_factorials<10>(1);
  static constexpr std::array<long double, 10> cos_coefficients = alternating_inverse_factorials<10>(0);
  constexpr double round_shift = 6755399441055744.0;  // 1.5·2⁵²: adding and subtracting it rounds to an integer
  const double k_double = (static_cast<double>(x) * static_cast<double>(two_over_pi) + round_shift) - round_shift;
  const long long quadrant = static_cast<long long>(k_double);  // round(x 2/π)
  const long double k = k_double;
  const long double y = (((x - k * pio2_1) - k * pio2_2) - k * pio2_3) - k * pio2_3t;
  const long double z = y * y;
  long double ps = sin_coefficients[9], pc = cos_coefficients[9];
  for (int j = 8; j >= 0; --j) {
    ps = sin_coefficients[j] + z * ps;  // sin y = y Σ (−z)^j/(2j+1)!
    pc = cos_coefficients[j] + z * pc;  // cos y = Σ (−z)^j/(2j)!
  }
  const long double sy = y * ps;
  sin_cos_of_quadrant(quadrant, sy, pc, s, c);  // x = k π/2 + y
}

inline void sin_cos_wide(const DoubleDouble& x, DoubleDouble& s, DoubleDouble& c) { sin_cos(x, s, c); }

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

/// ^iX_λ(i) in W, as joint_up_transform computes it, with the products written out; X_tree and
/// the axis are read from `params` (see times()). The joint angle's sine and cosine go to s, c.
template <class W, class P>
inline void wide_up_transform(const Model<W>& model, const Model<P>& params, int i, const W* q, W& s, W& c,
                              PluckerTransform<W>& X) {
  const Joint<W>& j = model.joints[i];
  const int angle = angle_coordinate(j);
  if (angle >= 0) sin_cos_wide(q[angle], s, c);
  if (j.type != JointType::Revolute) {
    joint_up_transform(model, i, q, s, c, X);
    return;
  }
  const Matrix3<P>& Et = params.X_tree[i].E;
  X.r = params.X_tree[i].r.template cast<W>();
  if (j.axis_kind != AxisKind::General) {
    // Rows (m, n) rotated as rotate_rows does, row l (the axis) copied.
    const int l = static_cast<int>(j.axis_kind), m = l == 2 ? 0 : l + 1, n = l == 0 ? 2 : l - 1;
    for (int k = 0; k < 3; ++k) {
      const P em = Et(m, k), en = Et(n, k);
      X.E(m, k) = c * em + s * en;
      X.E(n, k) = c * en - s * em;
      X.E(l, k) = W(Et(l, k));
    }
    return;
  }
  // E_J = c 1 − s a× + (1 − c) a aᵀ (RBDA eq. 2.24, transposed); E = E_J E_tree.
  const Vector3<W> a = params.joints[i].axis.template cast<W>();
  const W t = W(1) - c;
  Matrix3<W> EJ;
  EJ(0, 0) = c + t * a[0] * a[0];        EJ(0, 1) = s * a[2] + t * a[0] * a[1]; EJ(0, 2) = -s * a[1] + t * a[0] * a[2];
  EJ(1, 0) = -s * a[2] + t * a[1] * a[0]; EJ(1, 1) = c + t * a[1] * a[1];       EJ(1, 2) = s * a[0] + t * a[1] * a[2];
  EJ(2, 0) = s * a[1] + t * a[2] * a[0];  EJ(2, 1) = -s * a[0] + t * a[2] * a[1]; EJ(2, 2) = c + t * a[2] * a[2];
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col)
      X.E(row, col) = EJ(row, 0) * Et(0, col) + EJ(row, 1) * Et(1, col) + EJ(row, 2) * Et(2, col);
}

/// Where the wide passes read the model's parameters: from the model itself when W is a hardware
/// type (the conversion is exact and free), else from the workspace's converted copy.
template <class S, class W>
const auto& wide_parameters(const Model<S>& model, const RefinementWorkspace<S, W>& ws) {
  if constexpr (std::is_floating_point<W>::value || std::is_same<W, DoubleDouble>::value) return model;
  else return ws.model_wide;
}

/// a += v × e_k q̇ for a coordinate axis k, the velocity-product acceleration of a revolute
/// joint (ω × e_k q̇ ; v_O × e_k q̇) or, for a prismatic one (S = (0 ; e_k)), (0 ; ω × e_k q̇):
/// w × e_k has the two entries w_{k+2}, −w_{k+1} at k+1, k+2.
template <class W>
inline void add_coordinate_axis_product(const MotionVector<W>& v, int k, const W& qd, bool revolute, MotionVector<W>& a) {
  const int k1 = k == 2 ? 0 : k + 1, k2 = k == 0 ? 2 : k - 1;  // (k, k1, k2) cyclic
  if (revolute) {
    a.angular[k1] += v.angular[k2] * qd;
    a.angular[k2] -= v.angular[k1] * qd;
  }
  const Vector3<W>& moving = revolute ? v.linear : v.angular;
  a.linear[k1] += moving[k2] * qd;
  a.linear[k2] -= moving[k1] * qd;
}

/// r = τ − ID(q, q̇, x) in W (RBDA Table 5.1) in one outward pass: ^iX_λ, v_i = X v_λ + S q̇,
/// a_i = X a_λ + S x + v_i × S q̇ (a_0 = −a_g), f_i = I a_i + v_i ×* I v_i (eq. 29); then inward
/// r = τ − Sᵀ f_i with f_λ += Xᵀ f_i. Long double values live in memory as 80-bit words, whose
/// stores and loads cost several times a double's, so every quantity is formed once, in its
/// destination, and nothing is stored that the inward pass does not read again. Keeps the wide
/// transforms for the later products (subtract_mass_matrix_product).
template <class S, class W>
void wide_residual(const Model<S>& model, RefinementWorkspace<S, W>& ws, const ConstVectorRef<S>& tau) {
  const Model<W>& m = ws.model_wide;
  const auto& params = wide_parameters(model, ws);
  for (int i = 1; i < m.nbodies(); ++i) {
    const Joint<W>& j = m.joints[i];
    const int lambda = m.parent[i];
    PluckerTransform<W>& X = ws.X_up_wide[i];
    MotionVector<W>& v = ws.v_wide[i];
    MotionVector<W>& a = ws.a_wide[i];
    wide_up_transform(m, params, i, ws.q_wide.data() + j.idx_q, ws.sin_wide[i], ws.cos_wide[i], X);
    if (lambda == 0) {  // v_0 = 0, X a_0 = (0 ; E(−a_g)): the base does not rotate
      v = MotionVector<W>::Zero();
      a.angular = Vector3<W>::Zero();
      for (int row = 0; row < 3; ++row)
        a.linear[row] = -(X.E(row, 0) * m.gravity[0] + X.E(row, 1) * m.gravity[1] + X.E(row, 2) * m.gravity[2]);
    } else {
      apply_wide_into(X, ws.v_wide[lambda], v);
      apply_wide_into(X, ws.a_wide[lambda], a);
    }
    if (j.nv == 1 && j.axis_kind != AxisKind::General) {  // S = (e_k ; 0) or (0 ; e_k)
      const int k = static_cast<int>(j.axis_kind);
      const W& qd = ws.qd_wide[j.idx_v];
      const bool revolute = one_dof_rotates(j);
      (revolute ? v.angular : v.linear)[k] += qd;                                        // v_i = X v_λ + S q̇
      add_coordinate_axis_product(v, k, qd, revolute, a);                                // + v_i × S q̇
      (revolute ? a.angular : a.linear)[k] += ws.x_wide[j.idx_v];                        // + S x
    } else {
      const W& s = ws.sin_wide[i];
      const W& c = ws.cos_wide[i];
      const MotionVector<W> vJ = joint_motion(j, s, c, ws.qd_wide.data() + j.idx_v);
      v += vJ;                                                                           // v_i = X v_λ + S q̇
      a += MotionVector<W>(cross3(v.angular, vJ.angular),
                           Vector3<W>(cross3(v.angular, vJ.linear) + cross3(v.linear, vJ.angular)));  // + v_i × S q̇
      a += joint_motion(j, s, c, ws.x_wide.data() + j.idx_v);                            // + S x
      a += joint_bias(j, s, c, ws.qd_wide.data() + j.idx_v);                             // + c_J
    }
    bias_force_wide(params.inertia[i], v, ws.f_wide[i]);                                 // v ×* I v
    add_inertia_times_wide(params.inertia[i], a, ws.f_wide[i]);                          // + I a
  }
  for (int i = m.nbodies() - 1; i >= 1; --i) {
    const Joint<W>& j = m.joints[i];
    joint_project(j, ws.sin_wide[i], ws.cos_wide[i], ws.f_wide[i], ws.residual_wide.data() + j.idx_v);  // Sᵀ f_i
    if (m.parent[i] > 0) add_apply_transpose_wide(ws.X_up_wide[i], ws.f_wide[i], ws.f_wide[m.parent[i]]);  // f_λ += Xᵀ f
  }
  for (int k = 0; k < m.nv; ++k) ws.residual_wide[k] = W(tau[k]) - ws.residual_wide[k];
}

/// r ← r − M δ in W: the RNEA without velocity and gravity (a_i = X a_λ + S δ, f_i = I a_i).
template <class S, class W>
void subtract_mass_matrix_product(const Model<S>& model, RefinementWorkspace<S, W>& ws) {
  const Model<W>& m = ws.model_wide;
  const auto& params = wide_parameters(model, ws);
  ws.a_wide[0] = MotionVector<W>::Zero();
  for (int i = 1; i < m.nbodies(); ++i) {
    const Joint<W>& j = m.joints[i];
    apply_wide_into(ws.X_up_wide[i], ws.a_wide[m.parent[i]], ws.a_wide[i]);
    ws.a_wide[i] += joint_motion(j, ws.sin_wide[i], ws.cos_wide[i], ws.delta_wide.data() + j.idx_v);  // a_i = X a_λ + S δ
    ws.f_wide[i] = ForceVector<W>::Zero();
    add_inertia_times_wide(params.inertia[i], ws.a_wide[i], ws.f_wide[i]);     // f_i = I a_i
  }
  W column[6];
  for (int i = m.nbodies() - 1; i >= 1; --i) {
    const Joint<W>& j = m.joints[i];
    joint_project(j, ws.sin_wide[i], ws.cos_wide[i], ws.f_wide[i], column);
    for (int k = 0; k < j.nv; ++k) ws.residual_wide[j.idx_v + k] -= column[k];
    if (m.parent[i] > 0) add_apply_transpose_wide(ws.X_up_wide[i], ws.f_wide[i], ws.f_wide[m.parent[i]]);
  }
}

/// r ← r − M δ with the product in S (the model's transforms in data.X_up), for a correction so
/// small that the product's rounding, ε_S ‖M‖ ‖δ‖, stays below the wide residual's ε_W ‖M‖ ‖x‖.
template <class S, class W>
void subtract_mass_matrix_product_narrow(const Model<S>& model, const Data<S>& data, RefinementWorkspace<S, W>& ws) {
  const int n = model.nbodies();
  ws.a[0] = MotionVector<S>::Zero();
  for (int i = 1; i < n; ++i) {
    ws.a[i] = data.X_up[i].apply(ws.a[model.parent[i]]) + body_joint_motion(model, data, i, ws.delta.data());  // a = X a_λ + S δ
    ws.p[i] = model.inertia[i] * ws.a[i];                                                            // f = I a
  }
  S column[6];
  for (int i = n - 1; i >= 1; --i) {
    const Joint<S>& j = model.joints[i];
    body_joint_project(model, data, i, ws.p[i], column);
    for (int k = 0; k < j.nv; ++k) ws.residual_wide[j.idx_v + k] -= W(column[k]);
    if (model.parent[i] > 0) ws.p[model.parent[i]] += data.X_up[i].applyInverse(ws.p[i]);         // f_λ += Xᵀ f
  }
}

/// δ = M⁻¹ r by the factorisation the last aba() call left in data (U = Iᴬ S, D⁻¹, X_up):
/// ABA's passes 2 and 3 with no velocity, no gravity and joint forces r (RBDA Table 7.1). The
/// 1-DoF bodies work on the 3-vector halves, without assembling 6-vectors.
template <class S, class W>
void solve_with_aba_factorisation(const Model<S>& model, const Data<S>& data, RefinementWorkspace<S, W>& ws) {
  const int n = model.nbodies();
  for (int i = 1; i < n; ++i) ws.p[i] = ForceVector<S>::Zero();
  for (int i = n - 1; i >= 1; --i) {
    const Joint<S>& j = model.joints[i];
    const int lambda = model.parent[i];
    ForceVector<S>& p = ws.p[i];  // pᴬ, turned into pᵃ in place
    if (j.nv == 1) {
      const S u = ws.residual[j.idx_v] - detail::along_axis(j, one_dof_rotates(j) ? p.angular : p.linear);  // u = r − Sᵀ pᴬ
      ws.u[i][0] = u;
      if (lambda > 0) {
        const S scaled = u * data.D_inv[i](0, 0);
        p.angular += data.U[i].col(0).template head<3>() * scaled;                    // pᵃ = pᴬ + U D⁻¹ u
        p.linear += data.U[i].col(0).template tail<3>() * scaled;
        ws.p[lambda] += data.X_up[i].applyInverse(p);                                 // pᴬ_λ += Xᵀ pᵃ
      }
    } else {
      S column[6];
      body_joint_project(model, data, i, p, column);
      for (int k = 0; k < j.nv; ++k) ws.u[i][k] = ws.residual[j.idx_v + k] - column[k];  // u = r − Sᵀ pᴬ
      if (lambda > 0) {
        p = ForceVector<S>(Vector6<S>(p.toVector() + data.U[i] * (data.D_inv[i] * ws.u[i])));  // pᵃ = pᴬ + U D⁻¹ u
        ws.p[lambda] += data.X_up[i].applyInverse(p);                                 // pᴬ_λ += Xᵀ pᵃ
      }
    }
  }
  ws.a[0] = MotionVector<S>::Zero();
  for (int i = 1; i < n; ++i) {
    const Joint<S>& j = model.joints[i];
    MotionVector<S>& a = ws.a[i];
    a = data.X_up[i].apply(ws.a[model.parent[i]]);                                     // a' = X a_λ
    if (j.nv == 1) {
      const auto U = data.U[i].col(0);
      const S d = data.D_inv[i](0, 0) *
                  (ws.u[i][0] - (U.template head<3>().dot(a.angular) + U.template tail<3>().dot(a.linear)));  // δ = D⁻¹(u − Uᵀ a')
      ws.delta[j.idx_v] = d;
      add_one_dof_motion(j, d, a);                                                     // a = a' + S δ
    } else {
      const Vector6<S> d = data.D_inv[i] * (ws.u[i] - data.U[i].transpose() * a.toVector());  // zero past nv
      ws.delta.segment(j.idx_v, j.nv) = d.head(j.nv);
      a = a + joint_motion(j, data.joint_sin[i], data.joint_cos[i], d.data());          // a = a' + S δ
    }
  }
}

/// Corrections x ← x + M⁻¹ r with residuals in W, from the iterate in ws.x_wide and its
/// residual in ws.residual_wide. `rate` is one solve's relative error ρ ≈ κ(M) ε_S: when zero on
/// entry, the first correction measures it. Leaves the iterate in ws.x_wide and the number of
/// corrections in ws.iterations.
template <class S, class W>
void refine(const Model<S>& model, const Data<S>& data, RefinementWorkspace<S, W>& ws, int max_iterations, S& rate) {
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
    if (size <= eps_ratio * x_size) subtract_mass_matrix_product_narrow(model, data, ws);
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
  wide_residual(model, ws, tau);
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
  detail::refine(model, data, ws, max_iterations, ws.rate);
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
    detail::wide_residual(model, fine, tau);
    detail::refine(model, data, fine, max_iterations, rate);
    for (int k = 0; k < model.nv; ++k) data.qdd[k] = S(fine.x_wide[k]);
  }
  return data.qdd;
}

#ifdef SD_COMPILED_DOUBLE
// The double instances: compiled into the library, portable and AVX2 + FMA (simd_backend.hpp).
const VectorX<double>& aba_refined(const Model<double>& model, Data<double>& data,
                                   RefinementWorkspace<double, DoubleDouble>& ws, const ConstVectorRef<double>& q,
                                   const ConstVectorRef<double>& qd, const ConstVectorRef<double>& tau,
                                   int max_iterations = 8);
const VectorX<double>& aba_refined(const Model<double>& model, Data<double>& data,
                                   RefinementWorkspace<double, long double>& ws, const ConstVectorRef<double>& q,
                                   const ConstVectorRef<double>& qd, const ConstVectorRef<double>& tau,
                                   int max_iterations = 8);
#endif

}  // namespace spatial_dynamics
