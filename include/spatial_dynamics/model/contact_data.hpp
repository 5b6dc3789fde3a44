// Work space and results of the contact algorithms (algorithms/contact_dynamics.hpp) for one model
// and one ContactSet, sized once so that the calls do not allocate.
#pragma once

#include <Eigen/QR>
#include <algorithm>
#include <vector>

#include "spatial_dynamics/model/contact_set.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/eigen_types.hpp"
#include "spatial_dynamics/spatial/plucker_transform.hpp"

namespace spatial_dynamics {

template <class S>
struct ContactData {
  MatrixX<S> J;              // J_c (rows × nv): the contacts' rows of their frames' Jacobians (contact axes);
                             // contact_jacobian and forward_dynamics_with_contacts (not inverse dynamics)
  VectorX<S> acceleration;   // the contacts' classical accelerations J_c q̈ + J̇_c q̇ (J̇_c q̇ at q̈ = 0)
  VectorX<S> lambda;         // the contact wrenches, stacked (point: force; surface: moment, force)
  VectorX<S> tau;            // joint forces with ID = τ + J_cᵀ λ; a floating base's rows: the wrench left over
  VectorX<S> qdd;            // constrained accelerations
  VectorX<S> rhs;            // −(J̇_c q̇ + J_c q̈_free)
  MatrixX<S> L_inv_Jt;       // L⁻ᵀ J_cᵀ (nv × rows), M = Lᵀ L (L below)
  MatrixX<S> K;              // J_c M⁻¹ J_cᵀ = (L⁻ᵀ J_cᵀ)ᵀ (L⁻ᵀ J_cᵀ) (rows × rows)
  MatrixX<S> base_rows;      // J_c's base columns transposed (6 × rows), for base_solver (inverse dynamics
                             // fills it when it turns to base_solver)
  Eigen::CompleteOrthogonalDecomposition<MatrixX<S>> K_solver;     // minimum-norm λ of K λ = rhs (fallback)
  Eigen::CompleteOrthogonalDecomposition<MatrixX<S>> base_solver;  // minimum-norm λ of the base rows (fallback)
  // Forward dynamics: M = Lᵀ L with L lower triangular and M's tree sparsity (RBDA §6.5, the LTL
  // factorisation): L(k, i) ≠ 0 only for i = k or i an ancestor of coordinate k in dof_parent.
  MatrixX<S> L;
  std::vector<int> dof_parent;    // each velocity coordinate's parent coordinate (−1 at a root)
  std::vector<int> subtree_dofs;  // each coordinate's subtree: itself and the next subtree_dofs − 1
  std::vector<std::vector<int>> contact_dofs;  // per contact: the coordinates its J_c rows can depend on, the
                                              // last first (its frame's body's last and their ancestors)
  // With coupled joints (M = Gᵀ M_free G, another pattern), or coordinates not numbered depth first,
  // the coordinates are taken as a chain (parent k − 1, subtree k .. nv − 1) and L is dense.
  MatrixX<S> K_factor;  // K = Lᵀ L, L dense
  // Inverse dynamics: per contact ^FX_r (r the floating root) and whether the frame is on the root's
  // tree; with six rows or more, the base rows' Gram matrix B Bᵀ = Lᵀ L and L.
  std::vector<PluckerTransform<S>> contact_root;
  std::vector<char> on_root;
  std::vector<std::vector<PluckerTransform<S>>> contact_branch;  // with a floating base: ^FX_j for the
                                                                 // bodies j from the frame's to the root's child
  Matrix6<S> gram, gram_factor;

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
        base_solver(6, contacts.rows),
        L(MatrixX<S>::Zero(model.nv, model.nv)),
        dof_parent(model.nv, -1),
        subtree_dofs(model.nv, 1),
        contact_dofs(contacts.contacts.size()),
        K_factor(MatrixX<S>::Zero(contacts.rows, contacts.rows)),
        contact_root(contacts.contacts.size()),
        on_root(contacts.contacts.size(), 0),
        contact_branch(contacts.contacts.size()),
        gram(Matrix6<S>::Zero()),
        gram_factor(Matrix6<S>::Zero()) {
    // Rank: a pivot below 100 ε · size of the largest is rounding, not a direction the contacts hold
    // (redundant contacts leave pivots of a few ε; Eigen's default, ε · size, splits them by chance).
    using std::max;
    const S tolerance = S(100) * Eigen::NumTraits<S>::epsilon() * S(max(contacts.rows, 6));
    K_solver.setThreshold(tolerance);
    base_solver.setThreshold(tolerance);
    // The coordinates' tree: a joint's first coordinate hangs from the last of its nearest ancestor
    // with coordinates, the others from the one before. The LTL factorisation below needs every
    // subtree numbered contiguously after its root (depth first), so that L's columns are contiguous.
    bool tree = !model.has_coupled_joints;
    for (int i = 1; i < model.nbodies(); ++i) {
      const Joint<S>& joint = model.joints[i];
      int up = -1;
      for (int b = model.parent[i]; b > 0 && up < 0; b = model.parent[b])
        if (model.joints[b].nv > 0) up = model.joints[b].idx_v + model.joints[b].nv - 1;
      for (int k = 0; k < joint.nv; ++k) {
        const int dof = joint.idx_v + k;
        dof_parent[dof] = k == 0 ? up : dof - 1;
        if (dof_parent[dof] >= dof) tree = false;
      }
    }
    subtree_dofs.assign(model.nv, 1);
    for (int k = model.nv - 1; k >= 0 && tree; --k)
      if (dof_parent[k] >= 0) subtree_dofs[dof_parent[k]] += subtree_dofs[k];
    for (int k = 0; k < model.nv && tree; ++k) {  // each range [k, k + subtree) inside its parent's
      const int up = dof_parent[k];
      if (up >= 0 && k + subtree_dofs[k] > up + subtree_dofs[up]) tree = false;
    }
    if (!tree)
      for (int k = 0; k < model.nv; ++k) {
        dof_parent[k] = k - 1;
        subtree_dofs[k] = model.nv - k;
      }
    for (std::size_t c = 0; c < contacts.contacts.size(); ++c) {
      int top = model.nv - 1;  // the frame's body's last coordinate, or its nearest ancestor's
      if (tree) {
        top = -1;
        for (int b = model.frames[contacts.contacts[c].frame].body; b > 0 && top < 0; b = model.parent[b])
          if (model.joints[b].nv > 0) top = model.joints[b].idx_v + model.joints[b].nv - 1;
      }
      for (int k = top; k >= 0; k = dof_parent[k]) contact_dofs[c].push_back(k);
      if (model.floating_base)
        for (int b = model.frames[contacts.contacts[c].frame].body; b > 1; b = model.parent[b]) contact_branch[c].emplace_back();
    }
  }
};

}  // namespace spatial_dynamics
