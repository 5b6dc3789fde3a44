// The RNEA (rnea.hpp's rnea_passes) in double-double on the double model: aba_refined's residual
// τ − ID(q, q̇, x) and its products M δ (aba_refined.hpp). The model's constants stay doubles
// (the wide model holds the same values: Model::cast is exact), so each product with one is a
// double times a double-double; the state, the joint angles' sines and cosines and every 3-vector
// are double-double, three lanes at once in two registers (packed3_double_double.hpp). ^iX_λ's
// rotation E = E_J(q) E_tree (RBDA Table 4.1) is formed once per body in double-double, from
// terms of the model's computed when the work is set up: E = B0 + c B1 + s B2 (Rodrigues'
// formula, RBDA eq. 2.24, times E_tree); where the joint rotates about a coordinate axis and the
// tree transform does not rotate (Data::up_rotation_axis), E's products mix two lanes
// (WideAxisRotation). Taken where SD_PACKED3 is defined, for models whose joints all have one
// coordinate and none is coupled; other models take the RNEA on Model<DoubleDouble>
// (vector3_form.hpp's ScalarForm).
#pragma once

#include <stdexcept>
#include <type_traits>
#include <vector>

#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/number/double_double.hpp"
#include "spatial_dynamics/spatial/number/wide_vector3.hpp"

namespace spatial_dynamics {

/// Whether the residual RNEA of this file can take the model (where SD_PACKED3 is defined; else
/// the one on Model<DoubleDouble> does): every joint of one coordinate, none coupled.
template <class S>
bool wide_residual_form_takes(const Model<S>& model) {
  if (model.has_coupled_joints) return false;
  for (int i = 1; i < model.nbodies(); ++i)
    if (model.joints[i].nv != 1) return false;
  return true;
}

/// The residual RNEA's per-body buffers (one layout in every build): v, a, f and ^iX_λ's r in
/// double-double, Eᵀ by its columns (E's rows) for the inward pass, the joint angle's sine and
/// cosine, and the coordinate axis of E (coordinate_axis_of_up_rotation; −1: none). Per body of
/// a model the form takes, E's terms B0..B2 (axis_operations.hpp's revolute_rotation_terms; a
/// prismatic joint's E_tree, 0 and 0) by their columns in double-double.
struct WideResidualWork {
  struct Body {
    WideVector3Storage<double> w, v, aw, al, n, f, r, Et0, Et1, Et2;
    DoubleDouble sin = DoubleDouble(0.0), cos = DoubleDouble(1.0);
    int axis = -1;
  };
  struct RotationTerms {
    WideVector3Storage<double> B0[3], B1[3], B2[3];
  };
  std::vector<Body> rnea;
  std::vector<RotationTerms> rotation_terms;

  template <class S>
  explicit WideResidualWork(const Model<S>& model) : rnea(model.nbodies()) {
    if constexpr (std::is_same<S, double>::value) {
      if (!wide_residual_form_takes(model)) return;
      rotation_terms.resize(model.nbodies());
      for (int i = 1; i < model.nbodies(); ++i) set_up_body(model, i);
    }
  }

 private:
  static void store(const DoubleDouble (&x)[3], WideVector3Storage<double>& s) {
    for (int k = 0; k < 3; ++k) {
      s.hi.lane[k] = x[k].hi;
      s.lo.lane[k] = x[k].lo;
    }
    s.hi.lane[3] = s.lo.lane[3] = 0.0;
  }
  void set_up_body(const Model<double>& model, int i) {
    const Joint<double>& j = model.joints[i];
    const Matrix3<double>& E_tree = model.X_tree[i].E;
    rnea[i].axis = coordinate_axis_of_up_rotation(model, i);
    detail::RevoluteRotationTerms terms{};
    if (j.type == JointType::Revolute) {
      terms = detail::revolute_rotation_terms(j.axis, E_tree);
    } else {  // E = E_tree
      for (int k = 0; k < 3; ++k)
        for (int m = 0; m < 3; ++m) terms.B[0][k][m] = E_tree(m, k);
    }
    RotationTerms& stored = rotation_terms[i];
    for (int k = 0; k < 3; ++k) {
      store(terms.B[0][k], stored.B0[k]);
      store(terms.B[1][k], stored.B1[k]);
      store(terms.B[2][k], stored.B2[k]);
    }
  }
};

#ifdef SD_PACKED3
namespace vec3 {

/// The form of rnea_passes on WideResidualWork (see above).
struct WideResidualForm {
  using S = double;
  using Scalar = DoubleDouble;
  using Vector = packed3::PackedDoubleDouble;
  /// ^iX_λ's E by its columns (Eᵀ's in the inward pass), formed where E does not rotate about a
  /// coordinate axis alone (the body's axis −1).
  struct Rotation {
    Vector c0, c1, c2;
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

  /// What the passes know of E beyond its columns (the body's axis, sine and cosine).
  template <class Work>
  static SD_INLINE RotationAboutAxis<Scalar> up_rotation(const Work& work, int i) {
    const auto& b = work.rnea[i];
    return {b.axis, b.sin, b.cos};
  }
  /// x ← E x and y ← E y: by the two lanes E mixes where `about` tells that it rotates about a
  /// coordinate axis (WideAxisRotation), else by E's columns.
  static SD_INLINE void times_pair(const RotationAboutAxis<Scalar>& about, const Rotation& E, Vector& x, Vector& y) {
    if (about.axis >= 0) {
      packed3::with_axis(about.axis, [&](auto k) SD_INLINE_LAMBDA {
        const packed3::WideAxisRotation<decltype(k)::value> rotation(about.s, about.c);
        x = rotation.times(x);
        y = rotation.times(y);
      });
      return;
    }
    x = packed3::mat_vec(E.c0, E.c1, E.c2, x);
    y = packed3::mat_vec(E.c0, E.c1, E.c2, y);
  }

  /// ^iX_λ's E = B0 + c B1 + s B2 by its columns, its rows into the body for the inward pass
  /// (where the body's axis is −1), and r (r = r_tree + E_treeᵀ (q a) for a prismatic joint); the
  /// body holds the joint's sine and cosine, set before (a prismatic joint's stay 0 and 1).
  template <class Work, class Body>
  static SD_INLINE void up_transform(const Model<S>& model, Work& work, int i, const Scalar* q, Body& b, Rotation& E,
                                     Vector& r) {
    const Joint<S>& j = model.joints[i];
    const PluckerTransform<S>& Xt = model.X_tree[i];
    if (b.axis < 0) {
      const auto& terms = work.rotation_terms[i];
      const Vector c = packed3::splat(b.cos), s = packed3::splat(b.sin);
      const auto column = [&](int k) SD_INLINE_LAMBDA {
        return load(terms.B0[k]) + c * load(terms.B1[k]) + s * load(terms.B2[k]);
      };
      E = {column(0), column(1), column(2)};
      Rotation Et;
      packed3::transpose(E.c0.hi, E.c1.hi, E.c2.hi, Et.c0.hi, Et.c1.hi, Et.c2.hi);
      packed3::transpose(E.c0.lo, E.c1.lo, E.c2.lo, Et.c0.lo, Et.c1.lo, Et.c2.lo);
      store(Et.c0, b.Et0);
      store(Et.c1, b.Et1);
      store(Et.c2, b.Et2);
    } else {
      E = Rotation{};  // not read: the products take the rotation's lanes
    }
    r = load(Xt.r);
    if (j.type == JointType::Prismatic) r += packed3::transposed_columns(Xt.E) * axis_times(j, q[j.idx_q]);
    store(r, b.r);
  }
  /// Eᵀ by its columns from the body (where its axis is −1), and r.
  template <class Body>
  static SD_INLINE Rotation transposed_rotation(const Body& b) {
    Rotation Et{};
    if (b.axis < 0) Et = {load(b.Et0), load(b.Et1), load(b.Et2)};
    return Et;
  }
  template <class Body>
  static SD_INLINE Vector translation(const Body& b) {
    return load(b.r);
  }

  static SD_INLINE void add_axis(const Joint<S>& j, const Scalar& k, Vector& x) { x += axis_times(j, k); }
  /// x × (k a); for a coordinate axis e_m, x × e_m is swap(x) by the signs of AxisRotation's sv at s = 1.
  static SD_INLINE Vector cross_axis(const Joint<S>& j, const Vector& x, const Scalar& k) {
    if (j.axis_kind == AxisKind::General) return packed3::splat(k) * packed3::cross(x, axis(j));
    Vector x_cross_axis;
    packed3::with_axis(static_cast<int>(j.axis_kind), [&](auto m) SD_INLINE_LAMBDA {
      using About = packed3::AxisRotation<decltype(m)::value>;
      const packed3::Packed3 signs = About(1.0, 0.0).sv;
      x_cross_axis = {signs * About::swap(x.hi), signs * About::swap(x.lo)};
    });
    return packed3::splat(k) * x_cross_axis;
  }
  /// a · x: one lane for a coordinate axis.
  static SD_INLINE Scalar dot_axis(const Joint<S>& j, const Vector& x) {
    using Wide = wide3::Form<S>;
    return j.axis_kind == AxisKind::General ? Wide::dot(j.axis, x) : Wide::lane(x, static_cast<int>(j.axis_kind));
  }

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
