// The 1-DoF shortcuts of the packed and lane passes, on a Joint's axis and AxisKind: products with
// the axis that read one component, or two, when it is a coordinate axis.
#pragma once

#include "spatial_dynamics/model/joint.hpp"
#include "spatial_dynamics/model/joints/axis_operations.hpp"

namespace spatial_dynamics {
namespace detail {

/// a · x, reading one component for an axis-aligned joint; x is a 3-array of any scalar.
template <class S, class T>
SD_INLINE T dot_axis(const Joint<S>& j, const T* x) {
  switch (j.axis_kind) {
    case AxisKind::X: return x[0];
    case AxisKind::Y: return x[1];
    case AxisKind::Z: return x[2];
    case AxisKind::General: break;
  }
  return j.axis[0] * x[0] + j.axis[1] * x[1] + j.axis[2] * x[2];
}

/// k · a.
template <class S>
SD_INLINE Vector3<S> scaled_axis(const Joint<S>& j, const S& k) {
  switch (j.axis_kind) {
    case AxisKind::X: return Vector3<S>(k, S(0), S(0));
    case AxisKind::Y: return Vector3<S>(S(0), k, S(0));
    case AxisKind::Z: return Vector3<S>(S(0), S(0), k);
    case AxisKind::General: break;
  }
  return Vector3<S>(j.axis.x() * k, j.axis.y() * k, j.axis.z() * k);
}

/// x × (k a): two products for a coordinate axis (x × e_x = (0, x_z, −x_y), cyclic).
template <class S>
SD_INLINE Vector3<S> cross_axis(const Joint<S>& j, const Vector3<S>& x, const S& k) {
  switch (j.axis_kind) {
    case AxisKind::X: return Vector3<S>(S(0), x.z() * k, -(x.y() * k));
    case AxisKind::Y: return Vector3<S>(-(x.z() * k), S(0), x.x() * k);
    case AxisKind::Z: return Vector3<S>(x.y() * k, -(x.x() * k), S(0));
    case AxisKind::General: break;
  }
  return cross_3d(x, Vector3<S>(j.axis.x() * k, j.axis.y() * k, j.axis.z() * k));
}

/// x += k a.
template <class S>
SD_INLINE void add_along_axis(const Joint<S>& j, Vector3<S>& x, const S& k) {
  switch (j.axis_kind) {
    case AxisKind::X: x.x() += k; return;
    case AxisKind::Y: x.y() += k; return;
    case AxisKind::Z: x.z() += k; return;
    case AxisKind::General: x += j.axis * k; return;
  }
}

/// Σ_k a_k I.col(offset + k): I (0 ; a) (offset 3) or I (a ; 0) (offset 0) of a 6 × 6 matrix, one
/// column of I for a coordinate axis.
template <class S>
SD_INLINE Vector6<S> combine_columns_along_axis(const Joint<S>& j, const Matrix6<S>& I, int offset) {
  switch (j.axis_kind) {
    case AxisKind::X: return I.col(offset);
    case AxisKind::Y: return I.col(offset + 1);
    case AxisKind::Z: return I.col(offset + 2);
    case AxisKind::General: break;
  }
  return I.template middleCols<3>(offset) * j.axis;
}

#ifdef SD_PACKED3
/// E ← E_J(θ) E on E's columns c0..c2 held packed: for a coordinate axis rows (m, n) as
/// rotate_rows turns them, c_k ← (c on lanes m, n; 1 elsewhere) ∘ c_k + (s, −s on lanes m, n) ∘
/// (c_k with lanes m and n swapped); a general axis multiplies by rot(a, θ)ᵀ (RBDA eq. 2.24).
SD_INLINE void packed_rotate_about_joint_axis(const Joint<double>& j, double s, double c, packed3::Packed3& c0,
                                              packed3::Packed3& c1, packed3::Packed3& c2) {
  using namespace packed3;
  if (j.axis_kind != AxisKind::General) {
    with_axis(static_cast<int>(j.axis_kind), [&](auto axis) SD_INLINE_LAMBDA {
      const AxisRotation<decltype(axis)::value> E_J(s, c);
      c0 = E_J.times(c0);
      c1 = E_J.times(c1);
      c2 = E_J.times(c2);
    });
    return;
  }
  // rot(a, θ)ᵀ = c 1 − s a× + (1 − c) a aᵀ, by its rows r0..r2.
  const Vector3<double>& a = j.axis;
  const Packed3 axis = make(a.x(), a.y(), a.z());
  const double k = 1 - c;
  const Packed3 r0 = (k * a.x()) * axis + make(c, -s * a.z(), s * a.y());
  const Packed3 r1 = (k * a.y()) * axis + make(s * a.z(), c, -s * a.x());
  const Packed3 r2 = (k * a.z()) * axis + make(-s * a.y(), s * a.x(), c);
  c0 = mat_vec(r0, r1, r2, c0);
  c1 = mat_vec(r0, r1, r2, c1);
  c2 = mat_vec(r0, r1, r2, c2);
}
#endif

/// E = E_J(θ) E_tree for the rotation about the joint's axis (RBDA Table 4.1, revolute). The
/// packed form reads E_tree, not a fresh copy of it: 32-byte loads of a matrix just written by
/// smaller stores would wait for them (failed store forwarding).
template <class S>
SD_INLINE void rotate_about_joint_axis(const Joint<S>& j, const Matrix3<S>& E_tree, const S& s, const S& c,
                                       Matrix3<S>& E) {
#ifdef SD_PACKED3
  if constexpr (std::is_same<S, double>::value) {
    using namespace packed3;
    Packed3 c0, c1, c2;
    load_columns(E_tree, c0, c1, c2);
    packed_rotate_about_joint_axis(j, s, c, c0, c1, c2);
    store3(c0, E.data());
    store3(c1, E.data() + 3);
    store3(c2, E.data() + 6);
    return;
  }
#endif
  E = E_tree;
  switch (j.axis_kind) {
    case AxisKind::X: rotate_rows(E, 1, 2, c, s); return;
    case AxisKind::Y: rotate_rows(E, 2, 0, c, s); return;
    case AxisKind::Z: rotate_rows(E, 0, 1, c, s); return;
    case AxisKind::General: rotate_about_axis(E, j.axis, c, s); return;
  }
}

}  // namespace detail
}  // namespace spatial_dynamics
