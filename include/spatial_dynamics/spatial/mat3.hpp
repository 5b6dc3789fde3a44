// The 3×3 matrix the spatial types are made of (a transform's E, a body's Ī_O), stored by its
// columns, each a Vec3 (vec3.hpp: for double, four aligned lanes with a zero pad). A product with
// a vector is then x₀ c₀ + x₁ c₁ + x₂ c₂ on whole columns. Converts to and from Eigen's 3×3
// matrices (eigen(), and implicitly).
#pragma once

#include "spatial_dynamics/spatial/vec3.hpp"

namespace spatial_dynamics {

template <class S>
struct Mat3 {
  Vec3<S> column[3];

  Mat3() = default;
  SD_INLINE Mat3(const Vec3<S>& c0, const Vec3<S>& c1, const Vec3<S>& c2) : column{c0, c1, c2} {}
  template <class Derived,
            class = std::enable_if_t<Derived::RowsAtCompileTime == 3 && Derived::ColsAtCompileTime == 3>>
  Mat3(const Eigen::MatrixBase<Derived>& m)  // NOLINT: from Eigen
      : column{Vec3<S>(S(m(0, 0)), S(m(1, 0)), S(m(2, 0))), Vec3<S>(S(m(0, 1)), S(m(1, 1)), S(m(2, 1))),
               Vec3<S>(S(m(0, 2)), S(m(1, 2)), S(m(2, 2)))} {}

  static SD_INLINE Mat3 Zero() { return Mat3(); }
  static SD_INLINE Mat3 Identity() { return Mat3(Vec3<S>::UnitX(), Vec3<S>::UnitY(), Vec3<S>::UnitZ()); }
  /// diag(d)
  static SD_INLINE Mat3 Diagonal(const S& d0, const S& d1, const S& d2) {
    return Mat3(Vec3<S>(d0, S(0), S(0)), Vec3<S>(S(0), d1, S(0)), Vec3<S>(S(0), S(0), d2));
  }
  /// a bᵀ
  static SD_INLINE Mat3 Outer(const Vec3<S>& a, const Vec3<S>& b) { return Mat3(a * b[0], a * b[1], a * b[2]); }
  /// The cross-product matrix a× (a× b = a × b).
  static SD_INLINE Mat3 Skew(const Vec3<S>& a) {
    return Mat3(Vec3<S>(S(0), a[2], -a[1]), Vec3<S>(-a[2], S(0), a[0]), Vec3<S>(a[1], -a[0], S(0)));
  }

  SD_INLINE S operator()(int r, int c) const { return column[c][r]; }
  SD_INLINE typename detail::Vec3Lanes<S>::reference operator()(int r, int c) { return column[c][r]; }
  SD_INLINE const Vec3<S>& col(int c) const { return column[c]; }
  SD_INLINE Vec3<S>& col(int c) { return column[c]; }
  SD_INLINE Vec3<S> row(int r) const { return Vec3<S>(column[0][r], column[1][r], column[2][r]); }

  Matrix3<S> eigen() const {
    Matrix3<S> m;
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) m(r, c) = column[c][r];
    return m;
  }
  operator Matrix3<S>() const { return eigen(); }  // NOLINT: to Eigen

  template <class T>
  Mat3<T> cast() const {
    return Mat3<T>(column[0].template cast<T>(), column[1].template cast<T>(), column[2].template cast<T>());
  }

  /// M x = x₀ c₀ + x₁ c₁ + x₂ c₂
  SD_INLINE Vec3<S> operator*(const Vec3<S>& x) const {
#ifdef SD_PACKED3
    if constexpr (std::is_same<S, double>::value) {
      using namespace packed3;
      return vec3(mat_vec(load(column[0]), load(column[1]), load(column[2]), load(x)));
    }
#endif
    return column[0] * x[0] + column[1] * x[1] + column[2] * x[2];
  }
  /// Mᵀ x = (c₀ · x, c₁ · x, c₂ · x)
  SD_INLINE Vec3<S> transposeTimes(const Vec3<S>& x) const {
#ifdef SD_PACKED3
    if constexpr (std::is_same<S, double>::value) {
      using namespace packed3;
      Packed3 t0, t1, t2;
      packed3::transpose(load(column[0]), load(column[1]), load(column[2]), t0, t1, t2);
      return vec3(mat_vec(t0, t1, t2, load(x)));
    }
#endif
    return Vec3<S>(dot(column[0], x), dot(column[1], x), dot(column[2], x));
  }
  SD_INLINE Mat3 transpose() const {
#ifdef SD_PACKED3
    if constexpr (std::is_same<S, double>::value) {
      using namespace packed3;
      Packed3 t0, t1, t2;
      packed3::transpose(load(column[0]), load(column[1]), load(column[2]), t0, t1, t2);
      return Mat3(vec3(t0), vec3(t1), vec3(t2));
    }
#endif
    return Mat3(row(0), row(1), row(2));
  }
  /// M N, column by column
  SD_INLINE Mat3 operator*(const Mat3& N) const { return Mat3(*this * N.column[0], *this * N.column[1], *this * N.column[2]); }
  /// M Nᵀ: column c is Σ_k c_k N(c, k), N's entries broadcast (no transpose).
  SD_INLINE Mat3 timesTransposed(const Mat3& N) const {
    Mat3 out;
    for (int c = 0; c < 3; ++c) out.column[c] = column[0] * N(c, 0) + column[1] * N(c, 1) + column[2] * N(c, 2);
    return out;
  }
  /// Mᵀ N
  SD_INLINE Mat3 transposeTimes(const Mat3& N) const {
    return Mat3(transposeTimes(N.column[0]), transposeTimes(N.column[1]), transposeTimes(N.column[2]));
  }
  SD_INLINE Mat3 operator+(const Mat3& N) const { return Mat3(column[0] + N.column[0], column[1] + N.column[1], column[2] + N.column[2]); }
  SD_INLINE Mat3 operator-(const Mat3& N) const { return Mat3(column[0] - N.column[0], column[1] - N.column[1], column[2] - N.column[2]); }
  SD_INLINE Mat3 operator-() const { return Mat3(-column[0], -column[1], -column[2]); }
  SD_INLINE Mat3 operator*(const S& k) const { return Mat3(column[0] * k, column[1] * k, column[2] * k); }
  SD_INLINE Mat3& operator+=(const Mat3& N) { return *this = *this + N; }
  SD_INLINE Mat3& operator-=(const Mat3& N) { return *this = *this - N; }
  bool operator==(const Mat3& N) const { return column[0] == N.column[0] && column[1] == N.column[1] && column[2] == N.column[2]; }
  bool operator!=(const Mat3& N) const { return !(*this == N); }

  /// The Frobenius norm.
  S norm() const {
    using std::sqrt;
    return sqrt(column[0].squaredNorm() + column[1].squaredNorm() + column[2].squaredNorm());
  }
  bool allFinite() const { return column[0].allFinite() && column[1].allFinite() && column[2].allFinite(); }
  S trace() const { return column[0][0] + column[1][1] + column[2][2]; }
  /// Copies the lower triangle into the upper one: exactly symmetric. (Whole columns are built
  /// and stored, so that a packed load of them forwards from the store.)
  SD_INLINE void symmetrize_from_lower() {
#ifdef SD_PACKED3
    if constexpr (std::is_same<S, double>::value) {
      using namespace packed3;
      const Packed3 c0 = load(column[0]), c1 = load(column[1]), c2 = load(column[2]);
      column[1] = vec3(__builtin_shuffle(c0, c1, LaneIndex{1, 5, 6, 7}));
      column[2] = vec3(__builtin_shuffle(__builtin_shuffle(c0, c1, LaneIndex{2, 6, 2, 6}), c2, LaneIndex{0, 1, 6, 7}));
      return;
    }
#endif
    column[1] = Vec3<S>(column[0][1], column[1][1], column[1][2]);
    column[2] = Vec3<S>(column[0][2], column[1][2], column[2][2]);
  }
  /// M r×: column k is M (r × e_k), e.g. r₂ c₁ − r₁ c₂ for k = 0.
  SD_INLINE Mat3 timesSkew(const Vec3<S>& r) const {
    return Mat3(column[1] * r[2] - column[2] * r[1], column[2] * r[0] - column[0] * r[2],
                column[0] * r[1] - column[1] * r[0]);
  }
  /// r× M: column k is r × c_k.
  SD_INLINE Mat3 skewTimes(const Vec3<S>& r) const {
    return Mat3(cross(r, column[0]), cross(r, column[1]), cross(r, column[2]));
  }
  /// M + d 1
  SD_INLINE Mat3 plusDiagonal(const S& d) const {
    return Mat3(column[0] + Vec3<S>(d, S(0), S(0)), column[1] + Vec3<S>(S(0), d, S(0)), column[2] + Vec3<S>(S(0), S(0), d));
  }
};

template <class S>
SD_INLINE Mat3<S> operator*(const S& k, const Mat3<S>& M) {
  return M * k;
}

template <class S>
std::ostream& operator<<(std::ostream& out, const Mat3<S>& M) {
  return out << M.eigen();
}

/// The cross-product matrix a× (skew(a) b = a × b), of a Vec3.
template <class S>
Mat3<S> skew(const Vec3<S>& a) {
  return Mat3<S>::Skew(a);
}

}  // namespace spatial_dynamics
