// An articulated inertia Iᴬ = [A B; Bᵀ C] (a symmetric 6×6 matrix, RBDA §7.2) held as the
// columns of its blocks A, B and C in packed 3-vectors (packed3.hpp): the ABA's inward step at
// double where SD_PACKED3 is defined. A 3×3 rotation Eᵀ M E is six products of a matrix by its
// columns' lanes, where Eigen's 3×3 blocks of a 6×6 matrix are strided scalar code.
#pragma once

#include "spatial_dynamics/spatial/eigen_types.hpp"
#include "spatial_dynamics/spatial/number/packed3.hpp"

namespace spatial_dynamics {
#ifdef SD_PACKED3
namespace packed3 {

/// The columns of A, B and C; Bᵀ is B's transpose, never stored.
struct InertiaBlocks {
  Packed3 A[3], B[3], C[3];
};

// A 6×6 matrix's column is stored in two parts, as it is read back: the first three columns as
// rows 0–3 and rows 4–5 (A's columns are 4-lane loads of rows 0–3), the last three as rows 0–1
// and rows 2–5 (B's columns are rows 0–2, C's rows 3–5 read as rows 2–5). A load that spans two
// earlier stores waits for both to reach the cache; the inward pass reads a parent's inertia
// right after its child's step wrote it.

/// The blocks of a symmetric 6×6 matrix (column-major): A's columns are the top halves of its
/// first three columns, B's and C's the top and bottom halves of its last three.
SD_INLINE InertiaBlocks load_blocks(const Matrix6<double>& M) {
  const double* m = M.data();
  InertiaBlocks I;
  for (int k = 0; k < 3; ++k) {
    I.A[k] = load(m + 6 * k);
    I.B[k] = load3(m + 18 + 6 * k);
    I.C[k] = load_after(m + 20 + 6 * k);
  }
  return I;
}

/// Σ_k E(k, c) x_k: the matrix with columns x_0..x_2 times column c of E, whose coefficients are
/// broadcast from memory (no lane shuffles).
SD_INLINE Packed3 times_column(const Packed3 (&x)[3], const double* E_column) {
  return x[0] * splat(E_column[0]) + x[1] * splat(E_column[1]) + x[2] * splat(E_column[2]);
}

/// [A B; Bᵀ C] (w ; v) = (A w + B v ; Bᵀ w + C v) for w and v given by their coefficients, which
/// are broadcast from memory.
SD_INLINE void times_motion(const InertiaBlocks& I, const double* w, const double* v, Packed3& top, Packed3& bottom) {
  Packed3 Bt[3];  // Bᵀ by its columns
  transpose(I.B[0], I.B[1], I.B[2], Bt[0], Bt[1], Bt[2]);
  top = times_column(I.A, w) + times_column(I.B, v);
  bottom = times_column(Bt, w) + times_column(I.C, v);
}

/// (Eᵀ M E)ᵀ = Eᵀ Mᵀ E by its columns, for M by its columns and E column-major: P = M E, then
/// Pᵀ E from P's rows.
SD_INLINE void rotate_transposed(const double* E, Packed3 (&M)[3]) {
  const Packed3 P0 = times_column(M, E), P1 = times_column(M, E + 3), P2 = times_column(M, E + 6);
  Packed3 rows[3];  // of P
  transpose(P0, P1, P2, rows[0], rows[1], rows[2]);
  M[0] = times_column(rows, E);
  M[1] = times_column(rows, E + 3);
  M[2] = times_column(rows, E + 6);
}

/// Eᵀ M E by its columns for E a rotation about a coordinate axis (packed3.hpp's AxisRotation):
/// M E mixes M's columns m and n, Eᵀ two lanes of each column.
template <int axis>
SD_INLINE void rotate_about_axis(const AxisRotation<axis>& E, double s, double c, Packed3 (&M)[3]) {
  constexpr int m = AxisRotation<axis>::m, n = AxisRotation<axis>::n;
  const Packed3 Mm = M[m], Mn = M[n];
  M[m] = splat(c) * Mm - splat(s) * Mn;  // M E: column m is M (c e_m − s e_n), column n M (s e_m + c e_n)
  M[n] = splat(s) * Mm + splat(c) * Mn;
  for (Packed3& column : M) column = E.transposed_times(column);
}

/// One of the first three columns of a 6×6 matrix += (top ; bottom), or = with `add` false:
/// rows 0–3, then rows 4–5.
SD_INLINE void add_to_left_column(double* column, Packed3 top, Packed3 bottom, bool add = true) {
  Packed3 rows03 = __builtin_shuffle(top, bottom, LaneIndex{0, 1, 2, 4});
  __m128d rows45 = _mm256_castpd256_pd128((__m256d)__builtin_shuffle(bottom, LaneIndex{1, 2, 1, 2}));
  if (add) {
    rows03 += load(column);
    rows45 += _mm_loadu_pd(column + 4);
  }
  std::memcpy(column, &rows03, sizeof rows03);
  _mm_storeu_pd(column + 4, rows45);
}

/// One of the last three columns of a 6×6 matrix += (top ; bottom), or = with `add` false:
/// rows 0–1, then rows 2–5.
SD_INLINE void add_to_right_column(double* column, Packed3 top, Packed3 bottom, bool add = true) {
  __m128d rows01 = _mm256_castpd256_pd128((__m256d)top);
  Packed3 rows25 = __builtin_shuffle(top, bottom, LaneIndex{2, 4, 5, 6});
  if (add) {
    rows01 += _mm_loadu_pd(column);
    rows25 += load(column + 2);
  }
  _mm_storeu_pd(column, rows01);
  std::memcpy(column + 2, &rows25, sizeof rows25);
}

/// The rigid inertia [Ī_O h×; −h× m1] (eq. 25) of mass m and first moment h by its six columns'
/// halves (top ; bottom), as store_columns_6x6 takes them.
struct RigidColumns {
  Packed3 top[6], bottom[6];
};
SD_INLINE RigidColumns rigid_columns(double mass, const Vector3<double>& first_moment,
                                     const Matrix3<double>& rotational_inertia) {
  RigidColumns R;
  load_columns(rotational_inertia, R.top[0], R.top[1], R.top[2]);
  const Packed3 h = load3(first_moment);
  // h× by its columns (0, h₂, −h₁), (−h₂, 0, h₀), (h₁, −h₀, 0): h's lanes permuted, then signed
  // (the zero lanes and the pad by 0); −h× by the opposite signs. m1 by its columns m e_k.
  const Packed3 h021 = __builtin_shuffle(h, LaneIndex{0, 2, 1, 3}), h210 = __builtin_shuffle(h, LaneIndex{2, 1, 0, 3}),
                h102 = __builtin_shuffle(h, LaneIndex{1, 0, 2, 3});
  R.top[3] = h021 * Packed3{0.0, 1.0, -1.0, 0.0};
  R.top[4] = h210 * Packed3{-1.0, 0.0, 1.0, 0.0};
  R.top[5] = h102 * Packed3{1.0, -1.0, 0.0, 0.0};
  for (int k = 0; k < 3; ++k) R.bottom[k] = -R.top[3 + k];
  const Packed3 m = splat(mass);
  R.bottom[3] = m * Packed3{1.0, 0.0, 0.0, 0.0};
  R.bottom[4] = m * Packed3{0.0, 1.0, 0.0, 0.0};
  R.bottom[5] = m * Packed3{0.0, 0.0, 1.0, 0.0};
  return R;
}

/// The six columns (top ; bottom) into a 6×6 matrix, or added to it with `add`.
SD_INLINE void store_columns_6x6(const Packed3 (&top)[6], const Packed3 (&bottom)[6], Matrix6<double>& out, bool add) {
  double* o = out.data();
  for (int k = 0; k < 3; ++k) add_to_left_column(o + 6 * k, top[k], bottom[k], add);
  for (int k = 3; k < 6; ++k) add_to_right_column(o + 6 * k, top[k], bottom[k], add);
}

/// The rigid inertia of mass m and first moment h as a 6×6 matrix, stored as the inward step
/// reads and adds to it.
SD_INLINE void store_rigid(double mass, const Vector3<double>& first_moment, const Matrix3<double>& rotational_inertia,
                           Matrix6<double>& out) {
  const RigidColumns R = rigid_columns(mass, first_moment, rotational_inertia);
  store_columns_6x6(R.top, R.bottom, out, false);
}

/// A rank-one term W Vᵀ of a 6×6 matrix, W = (w_top ; w_bottom) and V = (v_top ; v_bottom).
struct RankOne {
  Packed3 w_top, w_bottom, v_top, v_bottom;
};

/// out += Xᵀ [A B; Bᵀ C] X (− W Vᵀ where `downdate` is given) for X = (E, r) (plucker_transform.hpp),
/// or out = base + … where `base` is given (a rigid inertia, so that out need not hold it first):
/// with A' = Eᵀ A E, B' = Eᵀ B E, C' = Eᵀ C E and G = B' + r×C', the blocks [A' − G r× + r×B'ᵀ, G ;
/// Gᵀ, C'] — column k of G r× is G (r × e_k), column k of r×B'ᵀ is r × (row k of B'), and Gᵀ is
/// formed as B'ᵀ − C' r× (sums of columns, where r×C' by columns would be three cross products). With `axis`
/// 0–2, E is the rotation about that coordinate axis by the angle of sine s and cosine c, and its
/// three products take the lanes it mixes (rotate_about_axis) instead of E's nine coefficients.
SD_INLINE void add_transformed(const Matrix3<double>& E, const Vector3<double>& r, InertiaBlocks I,
                               Matrix6<double>& out, int axis = -1, double s = 0, double c = 1,
                               const RankOne* downdate = nullptr, const RigidColumns* base = nullptr) {
  if (axis < 0) {
    rotate_transposed(E.data(), I.A);  // A' (symmetric)
    rotate_transposed(E.data(), I.C);  // C'
    rotate_transposed(E.data(), I.B);  // B'ᵀ
  } else {
    with_axis(axis, [&](auto k) SD_INLINE_LAMBDA {
      const AxisRotation<decltype(k)::value> rotation(s, c);
      rotate_about_axis(rotation, s, c, I.A);  // A'
      rotate_about_axis(rotation, s, c, I.C);  // C'
      rotate_about_axis(rotation, s, c, I.B);  // B'
    });
    transpose(I.B[0], I.B[1], I.B[2], I.B[0], I.B[1], I.B[2]);  // B'ᵀ
  }
  // Gᵀ = B'ᵀ + (r×C')ᵀ = B'ᵀ − C' r× (C' symmetric): column k of C' r× is C' (r × e_k), a sum of
  // C''s columns; G r× likewise of G's.
  const Packed3 r0 = splat(r.x()), r1 = splat(r.y()), r2 = splat(r.z());
  Packed3 Gt0 = I.B[0] - (I.C[1] * r2 - I.C[2] * r1);  // C' (r × e₀) = r₂ C'₁ − r₁ C'₂
  Packed3 Gt1 = I.B[1] - (I.C[2] * r0 - I.C[0] * r2);  // C' (r × e₁) = r₀ C'₂ − r₂ C'₀
  Packed3 Gt2 = I.B[2] - (I.C[0] * r1 - I.C[1] * r0);  // C' (r × e₂) = r₁ C'₀ − r₀ C'₁
  Packed3 G0, G1, G2;
  transpose(Gt0, Gt1, Gt2, G0, G1, G2);
  const Packed3 rr = load3(r);
  Packed3 TL0 = I.A[0] - (G1 * r2 - G2 * r1) + cross(rr, I.B[0]);  // G (r × e₀) = r₂ G₁ − r₁ G₂
  Packed3 TL1 = I.A[1] - (G2 * r0 - G0 * r2) + cross(rr, I.B[1]);  // G (r × e₁) = r₀ G₂ − r₂ G₀
  Packed3 TL2 = I.A[2] - (G0 * r1 - G1 * r0) + cross(rr, I.B[2]);  // G (r × e₂) = r₁ G₀ − r₀ G₁
  if (downdate) {  // column k −= W V_k
    const RankOne& d = *downdate;
    const Packed3 v0 = broadcast<0>(d.v_top), v1 = broadcast<1>(d.v_top), v2 = broadcast<2>(d.v_top);
    const Packed3 v3 = broadcast<0>(d.v_bottom), v4 = broadcast<1>(d.v_bottom), v5 = broadcast<2>(d.v_bottom);
    TL0 -= d.w_top * v0;
    TL1 -= d.w_top * v1;
    TL2 -= d.w_top * v2;
    Gt0 -= d.w_bottom * v0;
    Gt1 -= d.w_bottom * v1;
    Gt2 -= d.w_bottom * v2;
    G0 -= d.w_top * v3;
    G1 -= d.w_top * v4;
    G2 -= d.w_top * v5;
    I.C[0] -= d.w_bottom * v3;
    I.C[1] -= d.w_bottom * v4;
    I.C[2] -= d.w_bottom * v5;
  }
  Packed3 top[6] = {TL0, TL1, TL2, G0, G1, G2}, bottom[6] = {Gt0, Gt1, Gt2, I.C[0], I.C[1], I.C[2]};
  if (base) {
    for (int k = 0; k < 6; ++k) {
      top[k] += base->top[k];
      bottom[k] += base->bottom[k];
    }
  }
  store_columns_6x6(top, bottom, out, !base);
}

}  // namespace packed3
#endif
}  // namespace spatial_dynamics
