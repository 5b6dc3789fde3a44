// 3-vectors in WiderScalar<S> (double-double for double, double for float) and the few operations
// the ABA's gravity split needs (algorithms/gravity_split.hpp): E x and Eᵀ x for a rotation E in S,
// cross products with a 3-vector in S, scaling by an S and sums. Chosen here, in one place: for
// double where SD_PACKED3 is defined, double-double lanes in two registers
// (packed3_double_double.hpp); otherwise three WiderScalar<S>.
#pragma once

#include <type_traits>

#include "spatial_dynamics/spatial/number/double_double.hpp"
#include "spatial_dynamics/spatial/eigen_types.hpp"
#include "spatial_dynamics/spatial/mat3.hpp"
#include "spatial_dynamics/spatial/number/packed3_double_double.hpp"

namespace spatial_dynamics {

/// Memory for one wide 3-vector, of one layout in every build: for double the high and the low
/// parts as two packed 3-vectors' storage.
template <class S>
struct WideVector3Storage {
  WiderScalar<S> lane[3];
};
template <>
struct WideVector3Storage<double> {
  Packed3Storage hi, lo;
};

namespace wide3 {

/// The scalar form: three WiderScalar<S>.
template <class S>
struct ScalarWideVector3 {
  WiderScalar<S> x[3];
};

/// E x (transposed: Eᵀ x) in WiderScalar<S>, each product of an S and a wide value.
template <class S>
struct ScalarWideRotation {
  Mat3<S> E;
};
template <class S>
SD_INLINE ScalarWideVector3<S> operator*(const ScalarWideRotation<S>& R, const ScalarWideVector3<S>& v) {
  ScalarWideVector3<S> out;
  for (int r = 0; r < 3; ++r) out.x[r] = R.E(r, 0) * v.x[0] + R.E(r, 1) * v.x[1] + R.E(r, 2) * v.x[2];
  return out;
}
template <class S>
SD_INLINE ScalarWideVector3<S> operator+(const ScalarWideVector3<S>& a, const ScalarWideVector3<S>& b) {
  return {{a.x[0] + b.x[0], a.x[1] + b.x[1], a.x[2] + b.x[2]}};
}
template <class S>
SD_INLINE ScalarWideVector3<S> scale(const S& a, const ScalarWideVector3<S>& v) {
  return {{a * v.x[0], a * v.x[1], a * v.x[2]}};
}
template <class S>
SD_INLINE ScalarWideVector3<S> cross(const ScalarWideVector3<S>& a, const Vec3<S>& b) {
  return {{a.x[1] * b[2] - a.x[2] * b[1], a.x[2] * b[0] - a.x[0] * b[2], a.x[0] * b[1] - a.x[1] * b[0]}};
}
template <class S>
SD_INLINE ScalarWideVector3<S> cross(const Vec3<S>& a, const ScalarWideVector3<S>& b) {
  return {{a[1] * b.x[2] - a[2] * b.x[1], a[2] * b.x[0] - a[0] * b.x[2], a[0] * b.x[1] - a[1] * b.x[0]}};
}

#ifdef SD_PACKED3
}  // namespace wide3
namespace packed3 {
/// The packed form's rotation (its columns) times a double-double 3-vector.
SD_INLINE PackedDoubleDouble operator*(const Columns& R, const PackedDoubleDouble& v) {
  return mat_vec(R.c0, R.c1, R.c2, v);
}
}  // namespace packed3
namespace wide3 {
SD_INLINE packed3::PackedDoubleDouble scale(const double& a, const packed3::PackedDoubleDouble& v) {
  return packed3::scale(packed3::splat(a), v);
}
SD_INLINE packed3::PackedDoubleDouble cross(const packed3::PackedDoubleDouble& a, const Vec3<double>& b) {
  return packed3::cross(a, packed3::load(b));
}
SD_INLINE packed3::PackedDoubleDouble cross(const Vec3<double>& a, const packed3::PackedDoubleDouble& b) {
  return packed3::cross(packed3::load(a), b);
}
#endif

/// The choice, for S: its Vector and Rotation types and their loads and stores.
template <class S>
struct Form {
  using Vector = ScalarWideVector3<S>;
  using Rotation = ScalarWideRotation<S>;
  /// E, and Eᵀ, as a rotation of wide 3-vectors.
  static SD_INLINE Rotation rotation(const Mat3<S>& E) { return {E}; }
  static SD_INLINE Rotation transposed_rotation(const Mat3<S>& E) { return {E.transpose()}; }
  static SD_INLINE Vector from(const Vector3<S>& v) { return {{WiderScalar<S>(v[0]), WiderScalar<S>(v[1]), WiderScalar<S>(v[2])}}; }
  static SD_INLINE Vector load(const WideVector3Storage<S>& s) {
    Vector v;
    for (int k = 0; k < 3; ++k) {
      if constexpr (std::is_same<S, double>::value) v.x[k] = DoubleDouble(s.hi.lane[k], s.lo.lane[k]);
      else v.x[k] = s.lane[k];
    }
    return v;
  }
  static SD_INLINE void store(const Vector& v, WideVector3Storage<S>& s) {
    for (int k = 0; k < 3; ++k) {
      if constexpr (std::is_same<S, double>::value) {
        s.hi.lane[k] = v.x[k].hi;
        s.lo.lane[k] = v.x[k].lo;
      } else {
        s.lane[k] = v.x[k];
      }
    }
  }
  /// The three lanes as WiderScalar<S>.
  static SD_INLINE void lanes(const Vector& v, WiderScalar<S>* out) {
    for (int k = 0; k < 3; ++k) out[k] = v.x[k];
  }
};

#ifdef SD_PACKED3
template <>
struct Form<double> {
  using Vector = packed3::PackedDoubleDouble;
  using Rotation = packed3::Columns;
  /// E, and Eᵀ, by their columns.
  static SD_INLINE Rotation rotation(const Mat3<double>& E) {
    return {packed3::load(E.column[0]), packed3::load(E.column[1]), packed3::load(E.column[2])};
  }
  static SD_INLINE Rotation transposed_rotation(const Mat3<double>& E) { return rotation(E.transpose()); }
  static SD_INLINE Vector from(const Vector3<double>& v) { return {packed3::load3(v), packed3::Packed3{}}; }
  static SD_INLINE Vector load(const WideVector3Storage<double>& s) { return {packed3::load(s.hi), packed3::load(s.lo)}; }
  static SD_INLINE void store(const Vector& v, WideVector3Storage<double>& s) {
    packed3::store(v.hi, s.hi);
    packed3::store(v.lo, s.lo);
  }
  static SD_INLINE void lanes(const Vector& v, DoubleDouble* out) {
    for (int k = 0; k < 3; ++k) out[k] = DoubleDouble(v.hi[k], v.lo[k]);
  }
};
#endif

}  // namespace wide3
}  // namespace spatial_dynamics
