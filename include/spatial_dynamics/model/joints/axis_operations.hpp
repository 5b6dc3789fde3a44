// What the joint types share: products with a coordinate axis e_k that read one component or
// two (the coordinate rotations about an axis are spatial/rotations.hpp's).
#pragma once

#include <string>

#include "spatial_dynamics/spatial/cross.hpp"
#include "spatial_dynamics/spatial/eigen_types.hpp"
#include "spatial_dynamics/spatial/number/lane_trigonometry.hpp"
#include "spatial_dynamics/spatial/force_vector.hpp"
#include "spatial_dynamics/spatial/motion_vector.hpp"
#include "spatial_dynamics/spatial/plucker_transform.hpp"
#include "spatial_dynamics/spatial/rotations.hpp"

namespace spatial_dynamics {

/// Who a joint type's transform works for, for its error messages: the joint's name and its first
/// coordinate in q.
struct JointLabel {
  const std::string& name;
  int idx_q;
};

namespace detail {

/// q e_k.
template <class S, int k>
SD_INLINE Vec3<S> unit_axis(const S& q) {
  return Vec3<S>(k == 0 ? q : S(0), k == 1 ? q : S(0), k == 2 ? q : S(0));
}

/// x × (q e_k): (x × e_k)_k = 0, (x × e_k)_{k+1} = x_{k+2}, (x × e_k)_{k+2} = −x_{k+1} (indices mod 3).
template <int k, class S>
SD_INLINE Vec3<S> cross_unit_axis(const Vec3<S>& x, const S& q) {
  return cross(x, unit_axis<S, k>(q));
}

/// sin θ and cos θ of one angle: the batched routine on one lane (lane_trigonometry.hpp, within
/// 1 ulp for double and |θ| ≤ 1e5); other scalars and larger angles take std::sin and std::cos.
template <class S>
SD_INLINE void joint_sin_cos(const S& angle, S& s, S& c) {
  Lanes<S, 1> sine, cosine;
  sincos_lanes(Lanes<S, 1>::Constant(angle), sine, cosine);
  s = sine[0];
  c = cosine[0];
}

}  // namespace detail
}  // namespace spatial_dynamics
