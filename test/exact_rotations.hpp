// The float128 tests' model: rotations made orthogonal in float128 (test_reference.cpp,
// test_coriolis.cpp).
#pragma once

#include <Eigen/Geometry>

#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/reference/high_precision.hpp"

namespace sd_test {

/// The model in float128 with its rotations orthogonal and its joint axes of unit length to
/// float128 precision. Rounded to double they are off by ~1e-16, and where E Eᵀ ≠ 1 formulas that
/// agree for a rotation part ways: the library's CRBA carries columns in base coordinates on deep
/// trees (Eᵀ taken as E⁻¹) and shifts a prismatic joint's origin as Eᵀ(q a), the reference
/// multiplies 6×6 matrices. On the same exact rotations they must agree to float128 rounding.
inline spatial_dynamics::Model<spatial_dynamics::Quad> with_exact_rotations(const spatial_dynamics::Model<double>& model_d) {
  using Quad = spatial_dynamics::Quad;
  spatial_dynamics::Model<Quad> model = model_d.cast<Quad>();
  for (int i = 1; i < model.nbodies(); ++i) {
    model.X_tree[i].E = Eigen::Quaternion<Quad>(model.X_tree[i].E.eigen()).normalized().toRotationMatrix();
    model.joints[i].axis.normalize();
  }
  model.finalize();  // the joint types take the axes again
  return model;
}

}  // namespace sd_test
