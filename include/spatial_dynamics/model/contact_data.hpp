// Work space and results of the contact algorithms (algorithms/contact_dynamics.hpp) for one model
// and one ContactSet, sized once so that the calls do not allocate.
#pragma once

#include <Eigen/QR>
#include <algorithm>

#include "spatial_dynamics/model/contact_set.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/eigen_types.hpp"

namespace spatial_dynamics {

template <class S>
struct ContactData {
  MatrixX<S> J;              // J_c (rows × nv): the contacts' rows of their frames' Jacobians (contact axes)
  VectorX<S> acceleration;   // the contacts' classical accelerations J_c q̈ + J̇_c q̇ (J̇_c q̇ at q̈ = 0)
  VectorX<S> lambda;         // the contact wrenches, stacked (point: force; surface: moment, force)
  VectorX<S> tau;            // joint forces with ID = τ + J_cᵀ λ; a floating base's rows: the wrench left over
  VectorX<S> qdd;            // constrained accelerations
  VectorX<S> rhs;            // −(J̇_c q̇ + J_c q̈_free)
  MatrixX<S> L_inv_Jt;       // L⁻¹ J_cᵀ (nv × rows), L the Cholesky factor of M
  MatrixX<S> K;              // J_c M⁻¹ J_cᵀ (rows × rows)
  MatrixX<S> base_rows;      // J_c's base columns transposed (6 × rows)
  Eigen::CompleteOrthogonalDecomposition<MatrixX<S>> K_solver;     // minimum-norm λ of K λ = rhs
  Eigen::CompleteOrthogonalDecomposition<MatrixX<S>> base_solver;  // minimum-norm λ of the base rows

  ContactData(const Model<S>& model, const ContactSet<S>& contacts)
      : J(MatrixX<S>::Zero(contacts.rows, model.nv)),
        acceleration(VectorX<S>::Zero(contacts.rows)),
        lambda(VectorX<S>::Zero(contacts.rows)),
        tau(VectorX<S>::Zero(model.nv)),
        qdd(VectorX<S>::Zero(model.nv)),
        rhs(VectorX<S>::Zero(contacts.rows)),
        L_inv_Jt(MatrixX<S>::Zero(model.nv, contacts.rows)),
        K(MatrixX<S>::Zero(contacts.rows, contacts.rows)),
        base_rows(MatrixX<S>::Zero(6, contacts.rows)),
        K_solver(contacts.rows, contacts.rows),
        base_solver(6, contacts.rows) {
    // Rank: a pivot below 100 ε · size of the largest is rounding, not a direction the contacts hold
    // (redundant contacts leave pivots of a few ε; Eigen's default, ε · size, splits them by chance).
    using std::max;
    const S tolerance = S(100) * Eigen::NumTraits<S>::epsilon() * S(max(contacts.rows, 6));
    K_solver.setThreshold(tolerance);
    base_solver.setThreshold(tolerance);
  }
};

}  // namespace spatial_dynamics
