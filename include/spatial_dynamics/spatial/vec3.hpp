// The 3-vector the spatial types are made of (the ω, v, n, f halves, r, h): three coordinates,
// stored for double in four lanes of 32 aligned bytes (the fourth, the pad, is 0; a vector value
// of GCC's extension, detail::Double4), one layout in every build so that Model and Data are the same objects whichever build runs. Where the build
// has AVX2 and FMA (SD_PACKED3, spatial/number/packed3.hpp) the double operations act on the four
// lanes at once; otherwise, and for every other scalar, on the three coordinates one by one.
// Converts to and from Eigen's 3-vectors (eigen(), and implicitly).
#pragma once

#include <cmath>
#include <cstring>
#include <ostream>
#include <type_traits>

#include "spatial_dynamics/spatial/eigen_types.hpp"
#include "spatial_dynamics/spatial/number/double_double.hpp"
#include "spatial_dynamics/spatial/number/packed3_double_double.hpp"

namespace spatial_dynamics {

namespace detail {
/// For double: the four lanes as one value (GCC's and Clang's vector extension), so that a copy is
/// one move of 32 bytes and a Vec3 stays in a register; a coordinate is written through a
/// reference that may alias it.
typedef double Double4 __attribute__((vector_size(32), aligned(32)));  // 32 in every build
typedef double AliasingDouble __attribute__((may_alias));
template <class S>
struct Vec3Lanes {
  using reference = S&;
  using pointer = S*;
  using const_pointer = const S*;
  S x[3];
  SD_INLINE void set(const S& a, const S& b, const S& c) {
    x[0] = a;
    x[1] = b;
    x[2] = c;
  }
  SD_INLINE S get(int k) const { return x[k]; }
  SD_INLINE S& ref(int k) { return x[k]; }
  SD_INLINE const S* ptr() const { return x; }
  SD_INLINE S* ptr() { return x; }
};
template <>
struct Vec3Lanes<double> {
  typedef AliasingDouble& reference;
  typedef AliasingDouble* pointer;
  typedef const AliasingDouble* const_pointer;
  Double4 x;
  SD_INLINE void set(double a, double b, double c) { x = Double4{a, b, c, 0.0}; }
  SD_INLINE double get(int k) const { return x[k]; }
  SD_INLINE AliasingDouble& ref(int k) { return reinterpret_cast<AliasingDouble*>(&x)[k]; }
  SD_INLINE const AliasingDouble* ptr() const { return reinterpret_cast<const AliasingDouble*>(&x); }
  SD_INLINE AliasingDouble* ptr() { return reinterpret_cast<AliasingDouble*>(&x); }
};
/// For double-double (the gravity split's and the refinement's wider type): the high and the
/// low parts, each as double's four lanes; a coordinate is written as its two parts.
template <>
struct Vec3Lanes<DoubleDouble> {
  struct reference {
    Vec3Lanes& v;
    int k;
    SD_INLINE operator DoubleDouble() const { return v.get(k); }  // NOLINT: reads like a DoubleDouble&
    SD_INLINE reference& operator=(const DoubleDouble& y) {
      v.hi[k] = y.hi;
      v.lo[k] = y.lo;
      return *this;
    }
  };
  typedef void* pointer;  // no contiguous coordinates: data() is not defined
  typedef const void* const_pointer;
  Double4 hi, lo;
  SD_INLINE void set(const DoubleDouble& a, const DoubleDouble& b, const DoubleDouble& c) {
    hi = Double4{a.hi, b.hi, c.hi, 0.0};
    lo = Double4{a.lo, b.lo, c.lo, 0.0};
  }
  SD_INLINE DoubleDouble get(int k) const { return DoubleDouble(hi[k], lo[k]); }
  SD_INLINE reference ref(int k) { return {*this, k}; }
};
}  // namespace detail

template <class S>
struct Vec3 {
  detail::Vec3Lanes<S> lanes;

  SD_INLINE Vec3(const S& x, const S& y, const S& z) { lanes.set(x, y, z); }
  SD_INLINE Vec3() : Vec3(S(0), S(0), S(0)) {}
  template <class Derived, class = std::enable_if_t<Derived::SizeAtCompileTime == 3>>
  SD_INLINE Vec3(const Eigen::MatrixBase<Derived>& v) : Vec3(S(v(0)), S(v(1)), S(v(2))) {}  // NOLINT: from Eigen

  static SD_INLINE Vec3 Zero() { return Vec3(); }
  static SD_INLINE Vec3 UnitX() { return Vec3(S(1), S(0), S(0)); }
  static SD_INLINE Vec3 UnitY() { return Vec3(S(0), S(1), S(0)); }
  static SD_INLINE Vec3 UnitZ() { return Vec3(S(0), S(0), S(1)); }
  static SD_INLINE Vec3 Unit(int k) { return Vec3(S(k == 0), S(k == 1), S(k == 2)); }

  SD_INLINE S operator[](int k) const { return lanes.get(k); }
  SD_INLINE typename detail::Vec3Lanes<S>::reference operator[](int k) { return lanes.ref(k); }
  SD_INLINE S operator()(int k) const { return lanes.get(k); }
  SD_INLINE typename detail::Vec3Lanes<S>::reference operator()(int k) { return lanes.ref(k); }
  SD_INLINE S x() const { return lanes.get(0); }
  SD_INLINE S y() const { return lanes.get(1); }
  SD_INLINE S z() const { return lanes.get(2); }
  SD_INLINE typename detail::Vec3Lanes<S>::const_pointer data() const { return lanes.ptr(); }
  SD_INLINE typename detail::Vec3Lanes<S>::pointer data() { return lanes.ptr(); }
  static constexpr int size() { return 3; }

  SD_INLINE Vector3<S> eigen() const { return Vector3<S>(x(), y(), z()); }
  SD_INLINE operator Vector3<S>() const { return eigen(); }  // NOLINT: to Eigen
  Eigen::Matrix<S, 1, 3> transpose() const { return eigen().transpose(); }

  template <class T>
  Vec3<T> cast() const {
    return Vec3<T>(T(x()), T(y()), T(z()));
  }

  SD_INLINE S dot(const Vec3& o) const;
  SD_INLINE Vec3 cross(const Vec3& o) const;
  SD_INLINE S squaredNorm() const { return dot(*this); }
  S norm() const {
    using std::sqrt;
    return sqrt(squaredNorm());
  }
  Vec3 normalized() const;
  /// Whether every coordinate is finite (x − x is 0 exactly for a finite x).
  bool allFinite() const { return x() - x() == S(0) && y() - y() == S(0) && z() - z() == S(0); }
  bool isZero() const { return x() == S(0) && y() == S(0) && z() == S(0); }

  SD_INLINE Vec3& operator+=(const Vec3& o);
  SD_INLINE Vec3& operator-=(const Vec3& o);
  SD_INLINE Vec3& operator*=(const S& k);

};

static_assert(sizeof(Vec3<double>) == 32 && alignof(Vec3<double>) == 32, "one layout in every build");
static_assert(sizeof(Vec3<DoubleDouble>) == 64, "one layout in every build");

#ifdef SD_PACKED3
namespace packed3 {
SD_INLINE Packed3 load(const Vec3<double>& v) { return v.lanes.x; }
SD_INLINE Vec3<double> vec3(Packed3 x) {
  Vec3<double> v;
  v.lanes.x = x;
  return v;
}
SD_INLINE PackedDoubleDouble load(const Vec3<DoubleDouble>& v) { return {v.lanes.hi, v.lanes.lo}; }
SD_INLINE Vec3<DoubleDouble> vec3(const PackedDoubleDouble& x) {
  Vec3<DoubleDouble> v;
  v.lanes.hi = x.hi;
  v.lanes.lo = x.lo;
  return v;
}
}  // namespace packed3
#endif

// ---- operations: packed for double where SD_PACKED3 is defined, coordinate by coordinate otherwise ----

/// Returns `expression` on the packed lanes where the build has them: for double, and with
/// `with_double_double` for double-double's sums too, whose packed lanes give the scalar's numbers
/// exactly. Otherwise the function goes on coordinate by coordinate.
#ifdef SD_PACKED3
#define SD_VEC3_PACKED_FOR(S, with_double_double, expression)                                                 \
  if constexpr (std::is_same<S, double>::value || (with_double_double && std::is_same<S, DoubleDouble>::value)) { \
    using namespace packed3;                                                                                 \
    return expression;                                                                                       \
  }
#else
#define SD_VEC3_PACKED_FOR(S, with_double_double, expression)
#endif
#define SD_VEC3_PACKED(S, expression) SD_VEC3_PACKED_FOR(S, false, expression)
#define SD_VEC3_PACKED_SUM(S, expression) SD_VEC3_PACKED_FOR(S, true, expression)

template <class S>
SD_INLINE Vec3<S> operator+(const Vec3<S>& a, const Vec3<S>& b) {
  SD_VEC3_PACKED_SUM(S, vec3(load(a) + load(b)))
  return Vec3<S>(a[0] + b[0], a[1] + b[1], a[2] + b[2]);
}
template <class S>
SD_INLINE Vec3<S> operator-(const Vec3<S>& a, const Vec3<S>& b) {
  SD_VEC3_PACKED_SUM(S, vec3(load(a) - load(b)))
  return Vec3<S>(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}
template <class S>
SD_INLINE Vec3<S> operator-(const Vec3<S>& a) {
  SD_VEC3_PACKED_SUM(S, vec3(-load(a)))
  return Vec3<S>(-a[0], -a[1], -a[2]);
}
template <class S>
SD_INLINE Vec3<S> operator*(const Vec3<S>& a, const S& k) {
  SD_VEC3_PACKED(S, vec3(load(a) * k))
  return Vec3<S>(a[0] * k, a[1] * k, a[2] * k);
}
template <class S>
SD_INLINE Vec3<S> operator*(const S& k, const Vec3<S>& a) {
  return a * k;
}
template <class S>
SD_INLINE Vec3<S> operator/(const Vec3<S>& a, const S& k) {
  return Vec3<S>(a[0] / k, a[1] / k, a[2] / k);
}
/// a × b
template <class S>
SD_INLINE Vec3<S> cross(const Vec3<S>& a, const Vec3<S>& b) {
  SD_VEC3_PACKED(S, vec3(packed3::cross(load(a), load(b))))
  return Vec3<S>(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
}
/// a · b
template <class S>
SD_INLINE S dot(const Vec3<S>& a, const Vec3<S>& b) {
  SD_VEC3_PACKED(S, sum3(load(a) * load(b)))
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
/// a · b + c · d (the scalar product of two 6-vectors by their halves)
template <class S>
SD_INLINE S dot_sum(const Vec3<S>& a, const Vec3<S>& b, const Vec3<S>& c, const Vec3<S>& d) {
  SD_VEC3_PACKED(S, sum3(load(a) * load(b) + load(c) * load(d)))
  return dot(a, b) + dot(c, d);
}
template <class S>
SD_INLINE bool operator==(const Vec3<S>& a, const Vec3<S>& b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}
template <class S>
SD_INLINE bool operator!=(const Vec3<S>& a, const Vec3<S>& b) {
  return !(a == b);
}

// For double, the same as non-templates, so that an Eigen 3-vector converts in a mixed expression.
SD_INLINE Vec3<double> operator+(const Vec3<double>& a, const Vec3<double>& b) { return operator+<double>(a, b); }
SD_INLINE Vec3<double> operator-(const Vec3<double>& a, const Vec3<double>& b) { return operator-<double>(a, b); }
SD_INLINE bool operator==(const Vec3<double>& a, const Vec3<double>& b) { return operator==<double>(a, b); }
SD_INLINE bool operator!=(const Vec3<double>& a, const Vec3<double>& b) { return operator!=<double>(a, b); }

#undef SD_VEC3_PACKED
#undef SD_VEC3_PACKED_SUM
#undef SD_VEC3_PACKED_FOR

template <class S>
SD_INLINE S Vec3<S>::dot(const Vec3& o) const {
  return spatial_dynamics::dot(*this, o);
}
template <class S>
SD_INLINE Vec3<S> Vec3<S>::cross(const Vec3& o) const {
  return spatial_dynamics::cross(*this, o);
}
template <class S>
Vec3<S> Vec3<S>::normalized() const {
  return *this / norm();
}
template <class S>
SD_INLINE Vec3<S>& Vec3<S>::operator+=(const Vec3& o) {
  return *this = *this + o;
}
template <class S>
SD_INLINE Vec3<S>& Vec3<S>::operator-=(const Vec3& o) {
  return *this = *this - o;
}
template <class S>
SD_INLINE Vec3<S>& Vec3<S>::operator*=(const S& k) {
  return *this = *this * k;
}

template <class S>
std::ostream& operator<<(std::ostream& out, const Vec3<S>& v) {
  return out << v.eigen().transpose();
}

/// a × b, forced inline (kept for the callers of Eigen's 3-vectors).
template <class S>
SD_INLINE Vec3<S> cross_3d(const Vec3<S>& a, const Vec3<S>& b) {
  return cross(a, b);
}

}  // namespace spatial_dynamics
