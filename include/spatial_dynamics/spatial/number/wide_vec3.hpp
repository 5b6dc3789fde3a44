// The products of a wide 3-vector Vec3<W>, W = WiderScalar<S> (double-double for double, double
// for float), with a rotation, a 3-vector or a number in S: what the ABA's gravity split
// (algorithms/gravity_split.hpp) carries gravity and its forces in. Each product is formed in W
// from the S operand as it is. For double where SD_PACKED3 is defined, on double-double's packed
// lanes (packed3_double_double.hpp); otherwise coordinate by coordinate.
#pragma once

#include <type_traits>

#include "spatial_dynamics/spatial/mat3.hpp"

namespace spatial_dynamics {
namespace detail {
/// Enables an operation for W the wider type of S (and not S itself).
template <class S, class W>
using IfWider = std::enable_if_t<std::is_same<W, WiderScalar<S>>::value && !std::is_same<W, S>::value>;
}  // namespace detail

/// E x
template <class S, class W, class = detail::IfWider<S, W>>
SD_INLINE Vec3<W> operator*(const Mat3<S>& E, const Vec3<W>& x) {
#ifdef SD_PACKED3
  if constexpr (std::is_same<S, double>::value) {
    using namespace packed3;
    return vec3(mat_vec(load(E.column[0]), load(E.column[1]), load(E.column[2]), load(x)));
  }
#endif
  return Vec3<W>(E(0, 0) * x[0] + E(0, 1) * x[1] + E(0, 2) * x[2], E(1, 0) * x[0] + E(1, 1) * x[1] + E(1, 2) * x[2],
                 E(2, 0) * x[0] + E(2, 1) * x[1] + E(2, 2) * x[2]);
}

/// k x
template <class S, class W, class = detail::IfWider<S, W>>
SD_INLINE Vec3<W> operator*(const S& k, const Vec3<W>& x) {
#ifdef SD_PACKED3
  if constexpr (std::is_same<S, double>::value) return packed3::vec3(packed3::scale(packed3::splat(k), packed3::load(x)));
#endif
  return Vec3<W>(k * x[0], k * x[1], k * x[2]);
}

/// a × b
template <class S, class W, class = detail::IfWider<S, W>>
SD_INLINE Vec3<W> cross(const Vec3<W>& a, const Vec3<S>& b) {
#ifdef SD_PACKED3
  if constexpr (std::is_same<S, double>::value) return packed3::vec3(packed3::cross(packed3::load(a), packed3::load(b)));
#endif
  return Vec3<W>(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
}

/// a × b = −(b × a)
template <class S, class W, class = detail::IfWider<S, W>>
SD_INLINE Vec3<W> cross(const Vec3<S>& a, const Vec3<W>& b) {
  return -cross(b, a);
}

}  // namespace spatial_dynamics
