// 3-vectors in WiderScalar<S> (double-double for double, double for float) and the few operations
// the ABA's gravity split needs (algorithms/gravity_split.hpp): E x and Eᵀ x for a rotation E in S,
// cross products with a 3-vector in S, scaling by an S and sums. Chosen here, in one place: for
// double where SD_PACKED3 is defined, double-double lanes in two registers
// (packed3_double_double.hpp); otherwise three WiderScalar<S>.
#pragma once

#include <type_traits>

#include "spatial_dynamics/spatial/number/double_double.hpp"
#include "spatial_dynamics/spatial/eigen_types.hpp"
#include "spatial_dynamics/spatial/number/packed3_double_double.hpp"
#include "spatial_dynamics/spatial/rotation_about_axis.hpp"

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
  Matrix3<S> E;
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
SD_INLINE ScalarWideVector3<S> cross(const ScalarWideVector3<S>& a, const Vector3<S>& b) {
  return {{a.x[1] * b[2] - a.x[2] * b[1], a.x[2] * b[0] - a.x[0] * b[2], a.x[0] * b[1] - a.x[1] * b[0]}};
}
template <class S>
SD_INLINE ScalarWideVector3<S> cross(const Vector3<S>& a, const ScalarWideVector3<S>& b) {
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
SD_INLINE packed3::PackedDoubleDouble cross(const packed3::PackedDoubleDouble& a, const Vector3<double>& b) {
  return packed3::cross(a, packed3::load3(b));
}
SD_INLINE packed3::PackedDoubleDouble cross(const Vector3<double>& a, const packed3::PackedDoubleDouble& b) {
  return packed3::cross(packed3::load3(a), b);
}
#endif

/// The choice, for S: its Vector and Rotation types and their loads and stores.
template <class S>
struct Form {
  using Vector = ScalarWideVector3<S>;
  using Rotation = ScalarWideRotation<S>;
  /// The rotation a pass on vec3::Form<S> holds (its member E), in this form.
  template <class FormRotation>
  static SD_INLINE Rotation rotation_of(const FormRotation& R) { return {R.E}; }
  /// R y; where `about` tells that R rotates about a coordinate axis (R's coefficients then need
  /// not be given), by the two coordinates it mixes, m = k + 1 and n = k + 2 (mod 3): (c y_m + s y_n,
  /// c y_n − s y_m) (RBDA Table 2.2).
  static SD_INLINE Vector rotate(const RotationAboutAxis<S>& about, const Rotation& R, const Vector& y) {
    if (about.axis < 0) return R * y;
    const int m = (about.axis + 1) % 3, n = (about.axis + 2) % 3;
    Vector out = y;
    out.x[m] = y.x[m] * about.c + y.x[n] * about.s;
    out.x[n] = y.x[n] * about.c - y.x[m] * about.s;
    return out;
  }
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
  /// The three lanes as WiderScalar<S>, or lane k.
  static SD_INLINE void lanes(const Vector& v, WiderScalar<S>* out) {
    for (int k = 0; k < 3; ++k) out[k] = v.x[k];
  }
  static SD_INLINE WiderScalar<S> lane(const Vector& v, int k) { return v.x[k]; }
  /// a · v for a in S.
  static SD_INLINE WiderScalar<S> dot(const Vector3<S>& a, const Vector& v) {
    return (v.x[0] * a[0] + v.x[1] * a[1]) + v.x[2] * a[2];
  }
};

#ifdef SD_PACKED3
template <>
struct Form<double> {
  using Vector = packed3::PackedDoubleDouble;
  using Rotation = packed3::Columns;
  /// The rotation a pass on vec3::Form<double> holds: the same columns.
  static SD_INLINE const Rotation& rotation_of(const Rotation& R) { return R; }
  /// R y; by the lanes it mixes where `about` tells that R rotates about a coordinate axis (R's
  /// coefficients then need not be given).
  static SD_INLINE Vector rotate(const RotationAboutAxis<double>& about, const Rotation& R, const Vector& y) {
    if (about.axis < 0) return R * y;
    Vector out;
    packed3::with_axis(about.axis, [&](auto k) SD_INLINE_LAMBDA {
      out = packed3::times(packed3::AxisRotation<decltype(k)::value>(about.s, about.c), y, false);
    });
    return out;
  }
  static SD_INLINE Vector from(const Vector3<double>& v) { return {packed3::load3(v), packed3::Packed3{}}; }
  static SD_INLINE Vector load(const WideVector3Storage<double>& s) { return {packed3::load(s.hi), packed3::load(s.lo)}; }
  static SD_INLINE void store(const Vector& v, WideVector3Storage<double>& s) {
    packed3::store(v.hi, s.hi);
    packed3::store(v.lo, s.lo);
  }
  static SD_INLINE void lanes(const Vector& v, DoubleDouble* out) {
    for (int k = 0; k < 3; ++k) out[k] = DoubleDouble(v.hi[k], v.lo[k]);
  }
  static SD_INLINE DoubleDouble lane(const Vector& v, int k) {
    switch (k) {  // lanes by constant indices
      case 0: return {v.hi[0], v.lo[0]};
      case 1: return {v.hi[1], v.lo[1]};
      default: return {v.hi[2], v.lo[2]};
    }
  }
  static SD_INLINE DoubleDouble dot(const Vector3<double>& a, const Vector& v) {
    return packed3::dot(packed3::load3(a), v);
  }
};
#endif

}  // namespace wide3
}  // namespace spatial_dynamics
