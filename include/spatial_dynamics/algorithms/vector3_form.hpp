// The 3-vectors a pass over the bodies computes on between its loads and stores, and the few
// operations it needs on them: sums, cross products, E x and Eᵀ x, a rigid inertia's product
// (eq. 25) and the products with a joint's axis. Chosen here, in one place: for double where
// SD_PACKED3 is defined, one packed register per 3-vector (packed3.hpp); otherwise Eigen's
// 3-vectors, with the axis-aligned shortcuts of model/joints/axis_operations.hpp. A pass written
// on vec3::Form<S> is one algorithm in every build.
#pragma once

#include <cstddef>

#include "spatial_dynamics/algorithms/joint_kernels.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/number/packed3.hpp"

namespace spatial_dynamics {
namespace vec3 {

/// What a form on one state (a Data<S>) asks of the joint models (joint_kernels.hpp): S q̇ and
/// S q̈ + c_J of a joint with several coordinates, and Sᵀ f stored or accumulated (coupled joints) into τ.
template <class F, class S>
struct OneStateJointTerms {
  using Scalar = S;
  template <class V>
  static SD_INLINE void joint_motion(const Model<S>& model, const Data<S>& data, int i, const S* qd, const S* qdd,
                                     V& vw, V& vv, V& aw, V& al) {
    const MotionVector<S> vJ = body_joint_motion(model, data, i, qd);  // S q̇
    const MotionVector<S> aJ = body_joint_motion(model, data, i, qdd) + body_joint_bias(model, data, i, qd);  // S q̈ + c_J
    vw = F::load(vJ.angular);
    vv = F::load(vJ.linear);
    aw = F::load(aJ.angular);
    al = F::load(aJ.linear);
  }
  /// U = I S of a 1-DoF joint by its halves (the 6-vector's coefficients 0–2 and 3–5): the
  /// combination of I's columns its axis takes, one column for a coordinate axis.
  template <class V>
  static SD_INLINE void inertia_times_axis(const Joint<S>& j, const Matrix6<S>& I, V& top, V& bottom) {
    const S* columns = I.data() + 6 * (one_dof_rotates(j) ? 0 : 3);
    switch (j.axis_kind) {
      case AxisKind::X: F::load_halves(columns, top, bottom); return;
      case AxisKind::Y: F::load_halves(columns + 6, top, bottom); return;
      case AxisKind::Z: F::load_halves(columns + 12, top, bottom); return;
      case AxisKind::General: break;
    }
    V top_k, bottom_k;
    F::load_halves(columns, top_k, bottom_k);
    top = top_k * j.axis.x();
    bottom = bottom_k * j.axis.x();
    for (int k = 1; k < 3; ++k) {
      F::load_halves(columns + 6 * k, top_k, bottom_k);
      top += top_k * j.axis[k];
      bottom += bottom_k * j.axis[k];
    }
  }
  /// A motion or force vector's halves, angular then linear, as (top ; bottom): each by a load
  /// that lies within one of store_six's stores, so that a vector just stored is read from the
  /// store buffer.
  template <class V, class SixVector>
  static SD_INLINE void load_six(const SixVector& x, V& top, V& bottom) {
    top = F::load(x.angular);
    bottom = F::load(x.linear);
  }
  /// As load_six, by F::load_halves (for packed 3-vectors two 4-lane loads rather than two loads
  /// and an insert each), for a vector stored long before (not by a store still in flight: a load
  /// that spans store_six's two stores waits for both to reach the cache).
  template <class V, class SixVector>
  static SD_INLINE void load_six_settled(const SixVector& x, V& top, V& bottom) {
    static_assert(sizeof(SixVector) == 6 * sizeof(S), "the halves of a 6-vector are contiguous");
    F::load_halves(x.angular.data(), top, bottom);
  }
  /// (top ; bottom) into a motion or force vector's halves, angular then linear (contiguous).
  template <class V, class SixVector>
  static SD_INLINE void store_six(const V& top, const V& bottom, SixVector& x) {
    static_assert(sizeof(SixVector) == 6 * sizeof(S), "the halves of a 6-vector are contiguous");
    F::store_halves(top, bottom, x.angular.data());
  }
  /// What is known of ^iX_λ(i)'s rotation (joint_kernels.hpp's body_up_rotation).
  static SD_INLINE RotationAboutAxis<S> up_rotation(const Data<S>& data, int i) { return body_up_rotation(data, i); }
  template <class V>
  static SD_INLINE void store_force(const Model<S>& model, const Data<S>& data, int i, const V& n, const V& f, S* tau,
                                    bool accumulate) {
    ForceVector<S> f_i;
    F::store(n, f_i.angular);
    F::store(f, f_i.linear);
    store_joint_force(model, data, i, f_i, tau, accumulate);
  }
};

/// Eigen's 3-vectors: every scalar, and double without SD_PACKED3.
template <class S>
struct ScalarForm : OneStateJointTerms<ScalarForm<S>, S> {
  using Vector = Vector3<S>;
  struct Rotation {  // a 3×3 matrix (a rotation E or Eᵀ, a rotational inertia), applied as E x
    Matrix3<S> E;
  };

  static SD_INLINE Vector load(const Vector3<S>& v) { return v; }
  static SD_INLINE Vector translation(const PluckerTransform<S>& X) { return X.r; }
  static SD_INLINE void store(const Vector& x, Vector3<S>& out) { out = x; }
  static SD_INLINE Vector load(const Packed3Storage& v) { return Vector(v.lane[0], v.lane[1], v.lane[2]); }
  static SD_INLINE void store(const Vector& x, Packed3Storage& out) {
    for (int k = 0; k < 3; ++k) out.lane[k] = x[k];
  }
  /// The halves p[0..2] and p[3..5] of a 6-vector's coefficients.
  static SD_INLINE void load_halves(const S* p, Vector& top, Vector& bottom) {
    top = Vector(p[0], p[1], p[2]);
    bottom = Vector(p[3], p[4], p[5]);
  }
  static SD_INLINE void store_halves(const Vector& top, const Vector& bottom, S* p) {
    for (int k = 0; k < 3; ++k) {
      p[k] = top[k];
      p[3 + k] = bottom[k];
    }
  }
  static SD_INLINE Vector times(const Rotation& R, const Vector& x) { return R.E * x; }
  static SD_INLINE Vector cross(const Vector& a, const Vector& b) { return cross_3d(a, b); }
  /// The 3×3 matrix with columns c0, c1, c2 (Eᵀ from E's rows, or a symmetric Ī by its columns).
  template <class Storage>
  static SD_INLINE Rotation columns(const Storage& c0, const Storage& c1, const Storage& c2) {
    Rotation R;
    R.E.col(0) = load(c0);
    R.E.col(1) = load(c1);
    R.E.col(2) = load(c2);
    return R;
  }
  /// A 3×3 matrix (a rotation E) from memory, and its transpose.
  static SD_INLINE Rotation rotation(const Matrix3<S>& M) { return {M}; }
  static SD_INLINE Rotation transposed(const Rotation& R) { return {R.E.transpose()}; }
  static SD_INLINE Vector column(const Rotation& R, int k) { return R.E.col(k); }
  /// E x for E the rotation about a coordinate axis `about` describes: lanes m = k + 1 and
  /// n = k + 2 (mod 3) become (c x_m + s x_n, c x_n − s x_m) (RBDA Table 2.2), lane k stays.
  static SD_INLINE void rotate_about_axis(const RotationAboutAxis<S>& about, Vector& x) {
    const int m = (about.axis + 1) % 3, n = (about.axis + 2) % 3;
    const S x_m = x[m], x_n = x[n];
    x[m] = about.c * x_m + about.s * x_n;
    x[n] = about.c * x_n - about.s * x_m;
  }
  /// x ← E x and y ← E y: by the two coordinates E mixes where `about` tells that it rotates
  /// about a coordinate axis, else by E's coefficients.
  static SD_INLINE void times_pair(const RotationAboutAxis<S>& about, const Rotation& E, Vector& x, Vector& y) {
    if (about.axis >= 0) {
      rotate_about_axis(about, x);
      rotate_about_axis(about, y);
      return;
    }
    x = E.E * x;
    y = E.E * y;
  }
  template <class Storage>
  static SD_INLINE void store_columns(const Matrix3<S>& M, Storage& c0, Storage& c1, Storage& c2) {
    store(Vector(M.col(0)), c0);
    store(Vector(M.col(1)), c1);
    store(Vector(M.col(2)), c2);
  }
  /// Eᵀ from the rows t0..t2 of E kept in a body's storage (the columns of Eᵀ), and r.
  template <class Body>
  static SD_INLINE Rotation transposed_rotation(const Body& b) {
    return columns(b.t0, b.t1, b.t2);
  }
  template <class Body>
  static SD_INLINE Vector translation(const Body& b) {
    return load(b.r);
  }

  /// x += k a, x × (k a) and a · x for the joint's axis a (one or two components for a coordinate axis).
  static SD_INLINE void add_axis(const Joint<S>& j, const S& k, Vector& x) { detail::add_along_axis(j, x, k); }
  static SD_INLINE Vector cross_axis(const Joint<S>& j, const Vector& x, const S& k) { return detail::cross_axis(j, x, k); }
  static SD_INLINE S dot_axis(const Joint<S>& j, const Vector& x) { return detail::dot_axis(j, x.data()); }
  /// k a, and R a (a column of R for a coordinate axis).
  static SD_INLINE Vector axis_times(const Joint<S>& j, const S& k) { return k * j.axis; }
  static SD_INLINE Vector times_axis(const Rotation& R, const Joint<S>& j) {
    switch (j.axis_kind) {
      case AxisKind::X: return R.E.col(0);
      case AxisKind::Y: return R.E.col(1);
      case AxisKind::Z: return R.E.col(2);
      case AxisKind::General: break;
    }
    return R.E * j.axis;
  }
  static SD_INLINE S dot(const Vector& a, const Vector& b) { return a.dot(b); }

  /// I (ω ; v) = (Ī_O ω + h × v ; m v − h × ω)   (eq. 25)
  static SD_INLINE void inertia_times(const RigidInertia<S>& I, const Vector& w, const Vector& v, Vector& n, Vector& f) {
    n = I.rotational_inertia * w + cross_3d(I.first_moment, v);
    f = I.mass * v - cross_3d(I.first_moment, w);
  }
  /// v ×* I v (rigid_inertia.hpp's biasForce).
  static SD_INLINE void bias_force(const RigidInertia<S>& I, const Vector& w, const Vector& v, Vector& n, Vector& f) {
    const ForceVector<S> p = I.biasForce(MotionVector<S>(w, v));
    n = p.angular;
    f = p.linear;
  }

  /// ^iX_λ(i) (joint_kernels.hpp) into data.X_up[i], and its E and r.
  static SD_INLINE void up_transform(const Model<S>& model, Data<S>& data, int i, const S* q, Rotation& E, Vector& r) {
    PluckerTransform<S>& X = data.X_up[i];
    body_up_transform(model, data, i, q, X);
    E.E = X.E;
    r = X.r;
  }
  /// As above, and into b as E's rows and r.
  template <class Body>
  static SD_INLINE void up_transform(const Model<S>& model, Data<S>& data, int i, const S* q, Body& b, Rotation& E,
                                     Vector& r) {
    up_transform(model, data, i, q, E, r);
    const PluckerTransform<S>& X = data.X_up[i];
    store(X.E.row(0).transpose(), b.t0);
    store(X.E.row(1).transpose(), b.t1);
    store(X.E.row(2).transpose(), b.t2);
    store(r, b.r);
  }
};

#ifdef SD_PACKED3
/// One packed register per 3-vector (double, AVX2 + FMA). Loads and stores move exactly three
/// doubles, so a later load meets one earlier store of the same size.
struct PackedForm : OneStateJointTerms<PackedForm, double> {
  using S = double;
  using Vector = packed3::Packed3;
  using Rotation = packed3::Columns;  // E by its columns

  static SD_INLINE Vector load(const Vector3<S>& v) { return packed3::load3(v); }
  /// X's r, the last member of its struct: read from the coefficient before it (E's last).
  static SD_INLINE Vector translation(const PluckerTransform<S>& X) {
    static_assert(offsetof(PluckerTransform<S>, r) == 9 * sizeof(S), "r follows E");
    return packed3::load_after(X.E.data() + 8);
  }
  static SD_INLINE void store(const Vector& x, Vector3<S>& out) { packed3::store3(x, out.data()); }
  static SD_INLINE Vector load(const Packed3Storage& v) { return packed3::load(v); }
  static SD_INLINE void store(const Vector& x, Packed3Storage& out) { packed3::store(x, out); }
  /// The halves p[0..2] and p[3..5] of a 6-vector's coefficients (two 4-lane loads inside it).
  static SD_INLINE void load_halves(const S* p, Vector& top, Vector& bottom) {
    top = packed3::load(p);
    bottom = packed3::load_after(p + 2);
  }
  /// The top half as four lanes (its pad on p[3], which the bottom half then overwrites).
  static SD_INLINE void store_halves(const Vector& top, const Vector& bottom, S* p) {
    packed3::store4(top, p);
    packed3::store3(bottom, p + 3);
  }
  static SD_INLINE Vector times(const Rotation& R, const Vector& x) { return packed3::mat_vec(R.c0, R.c1, R.c2, x); }
  static SD_INLINE Vector cross(const Vector& a, const Vector& b) { return packed3::cross(a, b); }
  /// The 3×3 matrix with columns c0, c1, c2 (Eᵀ from E's rows, or a symmetric Ī by its columns).
  static SD_INLINE Rotation columns(const Packed3Storage& c0, const Packed3Storage& c1, const Packed3Storage& c2) {
    return {load(c0), load(c1), load(c2)};
  }
  /// A 3×3 matrix (a rotation E) from memory, and its transpose.
  static SD_INLINE Rotation rotation(const Matrix3<S>& M) { return packed3::columns(M); }
  static SD_INLINE Rotation transposed(const Rotation& R) {
    Rotation T;
    packed3::transpose(R.c0, R.c1, R.c2, T.c0, T.c1, T.c2);
    return T;
  }
  static SD_INLINE Vector column(const Rotation& R, int k) { return k == 0 ? R.c0 : k == 1 ? R.c1 : R.c2; }
  /// x ← E x and y ← E y: by the two lanes E mixes where `about` tells that it rotates about a
  /// coordinate axis (packed3.hpp's AxisRotation), else by E's columns.
  static SD_INLINE void times_pair(const RotationAboutAxis<S>& about, const Rotation& E, Vector& x, Vector& y) {
    if (about.axis >= 0) {
      rotate_pair_about_axis(about, x, y);
      return;
    }
    x = times(E, x);
    y = times(E, y);
  }
  /// x ← E x and y ← E y for the rotation about a coordinate axis `about` describes.
  static SD_INLINE void rotate_pair_about_axis(const RotationAboutAxis<S>& about, Vector& x, Vector& y) {
    packed3::with_axis(about.axis, [&](auto k) SD_INLINE_LAMBDA {
      const packed3::AxisRotation<decltype(k)::value> rotation(about.s, about.c);
      x = rotation.times(x);
      y = rotation.times(y);
    });
  }
  static SD_INLINE void store_columns(const Matrix3<S>& M, Packed3Storage& c0, Packed3Storage& c1, Packed3Storage& c2) {
    const Rotation C = packed3::columns(M);
    store(C.c0, c0);
    store(C.c1, c1);
    store(C.c2, c2);
  }
  /// Eᵀ by its columns, the rows of E kept in a body's storage; and r.
  template <class Body>
  static SD_INLINE Rotation transposed_rotation(const Body& b) {
    return columns(b.t0, b.t1, b.t2);
  }
  template <class Body>
  static SD_INLINE Vector translation(const Body& b) {
    return load(b.r);
  }

  /// The joint's axis; lane 3 reads the member after it (plane_x), inside the struct.
  static SD_INLINE Vector axis(const Joint<S>& j) { return packed3::load(j.axis.data()); }
  /// k a, and R a (a column of R for a coordinate axis).
  static SD_INLINE Vector axis_times(const Joint<S>& j, const S& k) { return k * axis(j); }
  static SD_INLINE Vector times_axis(const Rotation& R, const Joint<S>& j) {
    switch (j.axis_kind) {
      case AxisKind::X: return R.c0;
      case AxisKind::Y: return R.c1;
      case AxisKind::Z: return R.c2;
      case AxisKind::General: break;
    }
    return times(R, axis(j));
  }
  /// a · b over lanes 0–2.
  static SD_INLINE S dot(const Vector& a, const Vector& b) {
    const Vector p = a * b;
    return p[0] + p[1] + p[2];
  }
  static SD_INLINE void add_axis(const Joint<S>& j, const S& k, Vector& x) { x += k * axis(j); }
  static SD_INLINE Vector cross_axis(const Joint<S>& j, const Vector& x, const S& k) {
    return packed3::cross(x, k * axis(j));
  }
  /// a · x: one lane for a coordinate axis.
  static SD_INLINE S dot_axis(const Joint<S>& j, const Vector& x) {
    switch (j.axis_kind) {
      case AxisKind::X: return x[0];
      case AxisKind::Y: return x[1];
      case AxisKind::Z: return x[2];
      case AxisKind::General: break;
    }
    return j.axis.x() * x[0] + j.axis.y() * x[1] + j.axis.z() * x[2];
  }

  static SD_INLINE void inertia_times(const RigidInertia<S>& I, const Vector& w, const Vector& v, Vector& n, Vector& f) {
    using namespace packed3;
    Packed3 I0, I1, I2;
    load_columns(I.rotational_inertia, I0, I1, I2);
    const Packed3 h = packed3::load(I.first_moment.data());  // lane 3 reads Ī_O(0, 0), inside the struct
    n = mat_vec(I0, I1, I2, w) + packed3::cross(h, v);
    f = I.mass * v - packed3::cross(h, w);
  }
  /// v ×* I v = (ω × Ī_O ω + h × (ω × v) ; m (ω × v) − ω × (h × ω)) (eq. 29 on eq. 25, as
  /// rigid_inertia.hpp's biasForce): without v × m v, zero but rounded to the size of m |v|².
  static SD_INLINE void bias_force(const RigidInertia<S>& I, const Vector& w, const Vector& v, Vector& n, Vector& f) {
    using namespace packed3;
    Packed3 I0, I1, I2;
    load_columns(I.rotational_inertia, I0, I1, I2);
    const Packed3 h = packed3::load(I.first_moment.data());  // lane 3 reads Ī_O(0, 0), inside the struct
    const Packed3 w_x_v = packed3::cross(w, v);
    n = packed3::cross(w, mat_vec(I0, I1, I2, w)) + packed3::cross(h, w_x_v);
    f = I.mass * w_x_v - packed3::cross(w, packed3::cross(h, w));
  }

  /// ^iX_λ(i)'s E and r, a 1-DoF joint's in registers (RBDA Table 4.1: E = E_J(θ) E_tree for a
  /// revolute joint, r = r_tree + E_treeᵀ (q a) for a prismatic one); into data.X_up[i] if
  /// `keep` (always for a joint with several coordinates).
  static SD_INLINE void up_transform(const Model<S>& model, Data<S>& data, int i, const S* q, Rotation& E, Vector& r,
                                     bool keep = true) {
    const Joint<S>& j = model.joints[i];
    if (j.nv != 1) {  // through data.X_up[i]
      PluckerTransform<S>& X = data.X_up[i];
      body_up_transform(model, data, i, q, X);
      E = packed3::columns(X.E);
      r = packed3::load3(X.r);
    } else {
      const PluckerTransform<S>& Xt = model.X_tree[i];
      E = packed3::columns(Xt.E);
      r = packed3::load3(Xt.r);
      if (one_dof_rotates(j) && j.axis_kind != AxisKind::General) {
        detail::packed_rotate_about_joint_axis(j, data.joint_sin[i], data.joint_cos[i], E.c0, E.c1, E.c2);
      } else if (one_dof_rotates(j)) {  // E = B0 + c B1 + s B2 (Data::up_rotation_terms)
        const auto& terms = data.up_rotation_terms[i];
        const Vector c = packed3::splat(data.joint_cos[i]), s = packed3::splat(data.joint_sin[i]);
        E.c0 = load(terms.B0[0]) + c * load(terms.B1[0]) + s * load(terms.B2[0]);
        E.c1 = load(terms.B0[1]) + c * load(terms.B1[1]) + s * load(terms.B2[1]);
        E.c2 = load(terms.B0[2]) + c * load(terms.B1[2]) + s * load(terms.B2[2]);
      } else {
        const S position = j.coupled ? j.mimic.multiplier * q[j.idx_q] + j.mimic.offset : q[j.idx_q];
        r += times(packed3::transposed_columns(Xt.E), position * axis(j));
      }
      if (keep) {
        PluckerTransform<S>& X = data.X_up[i];
        packed3::store3(E.c0, X.E.data());
        packed3::store3(E.c1, X.E.data() + 3);
        packed3::store3(E.c2, X.E.data() + 6);
        store(r, X.r);
      }
    }
  }
  /// As above (data.X_up[i] only for a joint with several coordinates), and into b as E's rows and r.
  template <class Body>
  static SD_INLINE void up_transform(const Model<S>& model, Data<S>& data, int i, const S* q, Body& b, Rotation& E,
                                     Vector& r) {
    up_transform(model, data, i, q, E, r, false);
    Rotation T;
    packed3::transpose(E.c0, E.c1, E.c2, T.c0, T.c1, T.c2);
    store(T.c0, b.t0);
    store(T.c1, b.t1);
    store(T.c2, b.t2);
    store(r, b.r);
  }
};
#endif

/// A motion (ω ; v) in the parent's coordinates taken to body i's by ^iX_λ = (E, r):
/// (E ω ; E (v − r × ω)) (eq. 11), in place. For every form F of a pass.
template <class F>
SD_INLINE void motion_to_child(const typename F::Rotation& E, const typename F::Vector& r, typename F::Vector& w,
                               typename F::Vector& v) {
  v = F::times(E, v - F::cross(r, w));
  w = F::times(E, w);
}

/// A force (n ; f) on body i taken to its parent's coordinates by ^iX_λᵀ, given Eᵀ:
/// (Eᵀ n + r × Eᵀ f ; Eᵀ f) (eq. 12), in place.
template <class F, class TransposedRotation>
SD_INLINE void force_to_parent(const TransposedRotation& Et, const typename F::Vector& r, typename F::Vector& n,
                               typename F::Vector& f) {
  f = F::times(Et, f);
  n = F::times(Et, n) + F::cross(r, f);
}

/// As above, E's structure known as far as `about` tells (F::up_rotation, Data::up_rotation_axis).
template <class F, class About>
SD_INLINE void motion_to_child(const About& about, const typename F::Rotation& E, const typename F::Vector& r,
                               typename F::Vector& w, typename F::Vector& v) {
  v -= F::cross(r, w);
  F::times_pair(about, E, w, v);
}

/// As above, given Eᵀ and what is known of its structure (`about_Et`: transposed(about) of E's).
template <class F, class About, class TransposedRotation>
SD_INLINE void force_to_parent(const About& about_Et, const TransposedRotation& Et, const typename F::Vector& r,
                               typename F::Vector& n, typename F::Vector& f) {
  F::times_pair(about_Et, Et, f, n);
  n += F::cross(r, f);
}

/// The choice, for S.
template <class S>
struct FormOf {
  using type = ScalarForm<S>;
};
#ifdef SD_PACKED3
template <>
struct FormOf<double> {
  using type = PackedForm;
};
#endif
template <class S>
using Form = typename FormOf<S>::type;

}  // namespace vec3
}  // namespace spatial_dynamics
