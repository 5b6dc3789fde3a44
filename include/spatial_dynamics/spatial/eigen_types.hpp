// Fixed-size Eigen aliases shared by every layer, templated on the scalar.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

// The small spatial operations below are called once or twice per body on the algorithms' hot
// paths; GCC's inlining budget runs out inside the large algorithm bodies, and an out-of-line
// call passes each 6-vector through memory. SD_INLINE forces them inline.
// SD_INLINE_LAMBDA does the same for a lambda (after its parameter list), e.g. the visitors of
// visit_joint (model/joints/joint_dispatch.hpp).
#if defined(__GNUC__)
#define SD_INLINE inline __attribute__((always_inline))
#define SD_INLINE_LAMBDA __attribute__((always_inline))
#else
#define SD_INLINE inline
#define SD_INLINE_LAMBDA
#endif

namespace spatial_dynamics {

template <class S> using Vector3 = Eigen::Matrix<S, 3, 1>;
template <class S> using Matrix3 = Eigen::Matrix<S, 3, 3>;
template <class S> using Vector6 = Eigen::Matrix<S, 6, 1>;
template <class S> using Matrix6 = Eigen::Matrix<S, 6, 6>;
template <class S> using VectorX = Eigen::Matrix<S, Eigen::Dynamic, 1>;
template <class S> using MatrixX = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>;
template <class S> using RowMajorMatrixX = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
template <class S> using Matrix6X = Eigen::Matrix<S, 6, Eigen::Dynamic>;

/// a × b of two 3-vectors, the same arithmetic as Eigen's cross(), but forced inline: Eigen's is
/// an ordinary inline function, which GCC's inliner leaves out of line once an algorithm body has
/// grown large, passing both vectors through memory on every call.
template <class S>
SD_INLINE Vector3<S> cross_3d(const Vector3<S>& a, const Vector3<S>& b) {
  return Vector3<S>(a.y() * b.z() - a.z() * b.y(), a.z() * b.x() - a.x() * b.z(), a.x() * b.y() - a.y() * b.x());
}

/// The 3-D cross-product matrix: skew(a) * b == a.cross(b) (the "a×" of Featherstone 2010).
template <class S>
Matrix3<S> skew(const Vector3<S>& a) {
  Matrix3<S> m;
  m << S(0), -a.z(), a.y(),
       a.z(), S(0), -a.x(),
       -a.y(), a.x(), S(0);
  return m;
}

}  // namespace spatial_dynamics
