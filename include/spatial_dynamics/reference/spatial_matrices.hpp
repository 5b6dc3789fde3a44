// Spatial algebra of the reference implementation on plain 6×6 matrices, angular part first
// (Featherstone, Rigid Body Dynamics Algorithms, 2008, chapter 2; "A Beginner's Guide to 6-D
// Vectors (Part 1)", IEEE RAM 2010). Written from the book, independently of spatial/*.hpp.
#pragma once

#include <Eigen/Core>

namespace spatial_dynamics {
namespace reference {

template <class S> using Vec3 = Eigen::Matrix<S, 3, 1>;
template <class S> using Mat3 = Eigen::Matrix<S, 3, 3>;
template <class S> using Vec6 = Eigen::Matrix<S, 6, 1>;
template <class S> using Mat6 = Eigen::Matrix<S, 6, 6>;
template <class S> using Mat6X = Eigen::Matrix<S, 6, Eigen::Dynamic>;
template <class S> using VecX = Eigen::Matrix<S, Eigen::Dynamic, 1>;
template <class S> using MatX = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>;

/// A vector argument whose scalar is deduced from the model alone, so that any Eigen expression of
/// the right scalar binds to it.
template <class S> struct ArgumentOf { using type = VecX<S>; };
template <class S> using VectorArg = typename ArgumentOf<S>::type;

/// a× such that (a×) b = a × b.
template <class S>
Mat3<S> skew3(const Vec3<S>& a) {
  Mat3<S> m;
  m << S(0), -a(2), a(1),
       a(2), S(0), -a(0),
       -a(1), a(0), S(0);
  return m;
}

/// rot(E) = [E 0; 0 E]: a change of axes by the coordinate rotation E   (RBDA Table 2.2).
template <class S>
Mat6<S> rot(const Mat3<S>& E) {
  Mat6<S> X = Mat6<S>::Zero();
  X.template topLeftCorner<3, 3>() = E;
  X.template bottomRightCorner<3, 3>() = E;
  return X;
}

/// xlt(r) = [1 0; −r× 1]: a shift of the origin by r   (RBDA Table 2.2).
template <class S>
Mat6<S> xlt(const Vec3<S>& r) {
  Mat6<S> X = Mat6<S>::Identity();
  X.template bottomLeftCorner<3, 3>() = -skew3(r);
  return X;
}

/// ^BX_A = rot(E) xlt(r) = [E 0; −E r× E] for motion vectors, E rotating A coordinates into B
/// coordinates and r the position of B's origin in A coordinates   (RBDA Table 2.2).
template <class S>
Mat6<S> plucker(const Mat3<S>& E, const Vec3<S>& r) {
  return rot(E) * xlt(r);
}

/// v× = [ω× 0; v_O× ω×], the motion cross product: (v×) m = v × m   (RBDA eq. 2.31).
template <class S>
Mat6<S> crm(const Vec6<S>& v) {
  Mat6<S> m = Mat6<S>::Zero();
  m.template topLeftCorner<3, 3>() = skew3<S>(v.template head<3>());
  m.template bottomLeftCorner<3, 3>() = skew3<S>(v.template tail<3>());
  m.template bottomRightCorner<3, 3>() = skew3<S>(v.template head<3>());
  return m;
}

/// v×* = −(v×)ᵀ, the force cross product: (v×*) f = v ×* f   (RBDA eq. 2.32).
template <class S>
Mat6<S> crf(const Vec6<S>& v) {
  return -crm(v).transpose();
}

/// The rigid-body inertia about the body origin from mass m, first moment h = m c and rotational
/// inertia Ī_O = Ī_c + m c× c×ᵀ about the origin:
///   [Ī_c + m c×c×ᵀ, m c×; m c×ᵀ, m 1] = [Ī_O h×; −h× m 1]   (RBDA eq. 2.63).
template <class S>
Mat6<S> rigid_inertia(const S& m, const Vec3<S>& h, const Mat3<S>& I_origin) {
  Mat6<S> I;
  I.template topLeftCorner<3, 3>() = I_origin;
  I.template topRightCorner<3, 3>() = skew3(h);
  I.template bottomLeftCorner<3, 3>() = -skew3(h);
  I.template bottomRightCorner<3, 3>() = m * Mat3<S>::Identity();
  return I;
}

/// a_g = (0; g), the spatial acceleration of a gravitational field g; the base moves with
/// a_0 = −a_g in its place   (RBDA Table 5.1).
template <class S>
Vec6<S> gravity_acceleration(const Vec3<S>& g) {
  Vec6<S> a = Vec6<S>::Zero();
  a.template tail<3>() = g;
  return a;
}

}  // namespace reference
}  // namespace spatial_dynamics
