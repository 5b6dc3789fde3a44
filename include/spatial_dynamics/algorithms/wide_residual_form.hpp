// The RNEA (rnea.hpp's rnea_passes) in double-double on the double model: aba_refined's residual
// τ − ID(q, q̇, x) and its products M δ (aba_refined.hpp). The model's constants stay doubles
// (the wide model holds the same values: Model::cast is exact), so each product with one is a
// double times a double-double; the state, the joint angles' sines and cosines and every 3-vector
// are double-double, three lanes at once in two registers (packed3_double_double.hpp). ^iX_λ is
// applied as its two factors, E_J(q) (E_tree x) and E_treeᵀ (E_Jᵀ y) (RBDA Table 4.1), the joint's
// rotation in double-double and the tree's in double. Taken where SD_PACKED3 is defined, for
// models whose joints all have one coordinate and none is coupled; other models take the RNEA on
// Model<DoubleDouble> (vector3_form.hpp's ScalarForm).
#pragma once

#include <stdexcept>
#include <vector>

#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/double_double.hpp"
#include "spatial_dynamics/spatial/wide_vector3.hpp"

namespace spatial_dynamics {

/// The residual RNEA's per-body buffers (one layout in every build): v, a, f and ^iX_λ's r in
/// double-double, the joint angle's sine and cosine, and for the inward pass the joint and its
/// tree rotation (the model's).
struct WideResidualWork {
  struct Body {
    WideVector3Storage<double> w, v, aw, al, n, f, r;
    DoubleDouble sin, cos;
    const Joint<double>* joint = nullptr;
    const Matrix3<double>* tree_E = nullptr;
  };
  std::vector<Body> rnea;
  explicit WideResidualWork(int bodies) : rnea(bodies) {}
};

/// Whether the residual RNEA of this file can take the model (where SD_PACKED3 is defined; else
/// the one on Model<DoubleDouble> does): every joint of one coordinate, none coupled.
template <class S>
bool wide_residual_form_takes(const Model<S>& model) {
  if (model.has_coupled_joints) return false;
  for (int i = 1; i < model.nbodies(); ++i)
    if (model.joints[i].nv != 1) return false;
  return true;
}

#ifdef SD_PACKED3
namespace vec3 {

/// The form of rnea_passes on WideResidualWork (see above).
struct WideResidualForm {
  using S = double;
  using Scalar = DoubleDouble;
  using Vector = packed3::PackedDoubleDouble;
  /// ^iX_λ's E = E_J E_tree (transposed: E_treeᵀ E_Jᵀ): the tree's columns (its rows when
  /// transposed) and the joint's rotation by the angle of sine s and cosine c about its axis
  /// (none for a prismatic joint; −s when transposed).
  struct Rotation {
    packed3::Packed3 c0, c1, c2;
    const Joint<double>* joint;
    DoubleDouble s, c;
    bool transposed;
  };
  /// The passes' RotationAboutAxis: the rotation's structure is in Rotation itself.
  struct NoRotationStructure {
    friend NoRotationStructure transposed(NoRotationStructure none) { return none; }
  };

  static SD_INLINE Vector load(const Vector3<S>& v) { return {packed3::load3(v), packed3::Packed3{}}; }
  static SD_INLINE Vector load(const WideVector3Storage<S>& s) { return {packed3::load(s.hi), packed3::load(s.lo)}; }
  static SD_INLINE void store(const Vector& x, WideVector3Storage<S>& s) {
    packed3::store(x.hi, s.hi);
    packed3::store(x.lo, s.lo);
  }
  static SD_INLINE Vector cross(const Vector& a, const Vector& b) { return packed3::cross(a, b); }

  /// The joint's axis a (double), and k a for a double-double k.
  static SD_INLINE packed3::Packed3 axis(const Joint<S>& j) { return packed3::make(j.axis.x(), j.axis.y(), j.axis.z()); }
  static SD_INLINE Vector axis_times(const Joint<S>& j, const Scalar& k) { return packed3::scale(axis(j), packed3::splat(k)); }

  /// y ← E_J y: c y − s (a × y) + (1 − c)(a · y) a (RBDA eq. 2.24 transposed, Rodrigues), by −s
  /// when transposed.
  static SD_INLINE Vector joint_rotation(const Rotation& R, const Vector& y) {
    const Joint<S>& j = *R.joint;
    if (j.type != JointType::Revolute) return y;
    const packed3::Packed3 a = axis(j);
    const DoubleDouble s = R.transposed ? -R.s : R.s;
    const Vector a_dot_y_a = packed3::scale(a, packed3::splat(lane_sum_product(a, y)));
    return packed3::splat(R.c) * y - packed3::splat(s) * packed3::cross(a, y) +
           packed3::splat(DoubleDouble(1.0) - R.c) * a_dot_y_a;
  }
  /// a · y for double a.
  static SD_INLINE DoubleDouble lane_sum_product(packed3::Packed3 a, const Vector& y) {
    return packed3::lane_sum(packed3::scale(a, y));
  }
  static SD_INLINE Vector times(const Rotation& R, const Vector& x) {
    if (R.transposed) return packed3::mat_vec(R.c0, R.c1, R.c2, joint_rotation(R, x));
    return joint_rotation(R, packed3::mat_vec(R.c0, R.c1, R.c2, x));
  }
  template <class Work>
  static SD_INLINE NoRotationStructure up_rotation(const Work&, int) {
    return {};
  }
  static SD_INLINE void times_pair(NoRotationStructure, const Rotation& E, Vector& x, Vector& y) {
    x = times(E, x);
    y = times(E, y);
  }

  /// ^iX_λ's E and r (r = r_tree + E_treeᵀ (q a) for a prismatic joint); the body keeps the
  /// joint's sine and cosine, set before (WideResidualWork).
  template <class Work, class Body>
  static SD_INLINE void up_transform(const Model<S>& model, Work&, int i, const Scalar* q, Body& b, Rotation& E,
                                     Vector& r) {
    const Joint<S>& j = model.joints[i];
    const PluckerTransform<S>& Xt = model.X_tree[i];
    packed3::load_columns(Xt.E, E.c0, E.c1, E.c2);
    E.joint = &j;
    E.s = b.sin;
    E.c = b.cos;
    E.transposed = false;
    r = load(Xt.r);
    if (j.type == JointType::Prismatic) {
      packed3::Packed3 t0, t1, t2;  // E_treeᵀ by its columns
      packed3::transpose(E.c0, E.c1, E.c2, t0, t1, t2);
      r += packed3::mat_vec(t0, t1, t2, axis_times(j, q[j.idx_q]));
    }
    store(r, b.r);
    b.joint = &j;
    b.tree_E = &Xt.E;
  }
  /// Eᵀ = E_treeᵀ E_Jᵀ from what up_transform left in the body, and r.
  template <class Body>
  static SD_INLINE Rotation transposed_rotation(const Body& b) {
    Rotation Et;
    const packed3::Columns rows = packed3::transposed_columns(*b.tree_E);
    Et.c0 = rows.c0;
    Et.c1 = rows.c1;
    Et.c2 = rows.c2;
    Et.joint = b.joint;
    Et.s = b.sin;
    Et.c = b.cos;
    Et.transposed = true;
    return Et;
  }
  template <class Body>
  static SD_INLINE Vector translation(const Body& b) {
    return load(b.r);
  }

  static SD_INLINE void add_axis(const Joint<S>& j, const Scalar& k, Vector& x) { x += axis_times(j, k); }
  static SD_INLINE Vector cross_axis(const Joint<S>& j, const Vector& x, const Scalar& k) {
    return packed3::splat(k) * packed3::cross(x, axis(j));
  }
  static SD_INLINE Scalar dot_axis(const Joint<S>& j, const Vector& x) { return lane_sum_product(axis(j), x); }

  /// I (ω ; v) = (Ī_O ω + h × v ; m v − h × ω)   (eq. 25)
  static SD_INLINE void inertia_times(const RigidInertia<S>& I, const Vector& w, const Vector& v, Vector& n, Vector& f) {
    packed3::Packed3 I0, I1, I2;
    packed3::load_columns(I.rotational_inertia, I0, I1, I2);
    const packed3::Packed3 h = packed3::load3(I.first_moment);
    n = packed3::mat_vec(I0, I1, I2, w) + packed3::cross(h, v);
    f = packed3::scale(packed3::splat(I.mass), v) - packed3::cross(h, w);
  }
  /// v ×* I v = (ω × Ī_O ω + h × (ω × v) ; m (ω × v) − ω × (h × ω)) (as vector3_form.hpp's).
  static SD_INLINE void bias_force(const RigidInertia<S>& I, const Vector& w, const Vector& v, Vector& n, Vector& f) {
    packed3::Packed3 I0, I1, I2;
    packed3::load_columns(I.rotational_inertia, I0, I1, I2);
    const packed3::Packed3 h = packed3::load3(I.first_moment);
    const Vector w_x_v = packed3::cross(w, v);
    n = packed3::cross(w, packed3::mat_vec(I0, I1, I2, w)) + packed3::cross(h, w_x_v);
    f = packed3::scale(packed3::splat(I.mass), w_x_v) - packed3::cross(w, packed3::cross(h, w));
  }

  // Joints with several coordinates and coupled joints are not taken (wide_residual_form_takes).
  template <class Work>
  static void joint_motion(const Model<S>&, const Work&, int, const Scalar*, const Scalar*, Vector&, Vector&, Vector&,
                           Vector&) {
    throw std::logic_error("the wide residual form takes 1-DoF joints only");
  }
  template <class Work>
  static void store_force(const Model<S>&, const Work&, int, const Vector&, const Vector&, Scalar*, bool) {
    throw std::logic_error("the wide residual form takes uncoupled 1-DoF joints only");
  }
};

}  // namespace vec3
#endif

}  // namespace spatial_dynamics
