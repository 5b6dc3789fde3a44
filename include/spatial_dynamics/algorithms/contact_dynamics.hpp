// Dynamics with rigid contacts (model/contact_set.hpp). A contact holds its frame: its classical
// acceleration is zero, J_c q̈ + J̇_c q̇ = 0, with J_c the contact rows of the frame's Jacobian in the
// frame's axes and J̇_c q̇ the classical acceleration (α ; a + ω × v) at q̈ = 0 (RBDA §2.11: the spatial
// acceleration of the frame plus ω × v for its origin). Its wrench λ enters the equations of motion
// as J_cᵀ λ:
//   M q̈ + h = τ + J_cᵀ λ.
// inverse_dynamics_with_contacts: given q̈, the λ of minimum norm that balances a floating base's six
//   unactuated rows (least squares when the contacts cannot), then τ = ID(q, q̇, q̈) − J_cᵀ λ;
// forward_dynamics_with_contacts: given τ, q̈ and λ of the KKT system [M J_cᵀ; J_c 0] through the
//   factor M = Lᵀ L with M's tree sparsity (RBDA §6.5): q̈ = q̈_free + M⁻¹ J_cᵀ λ with
//   (J_c M⁻¹ J_cᵀ) λ = −J̇_c q̇ − J_c q̈_free, λ of minimum norm when the contacts are redundant (q̈ is
//   unique all the same).
// Both find λ from a small symmetric matrix (B Bᵀ for the base rows B, J_c M⁻¹ J_cᵀ) by its
// Cholesky factor. Fewer than six base rows (least squares), or a pivot below √ε of its diagonal
// entry (rank deficient: redundant contacts; or too ill-conditioned for the factor), hand the problem
// to a complete orthogonal decomposition (ContactData's rank rule), which gives the minimum-norm λ.
#pragma once

#include <cmath>
#include <stdexcept>
#include <vector>

#include "spatial_dynamics/algorithms/crba.hpp"
#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/kinematics.hpp"
#include "spatial_dynamics/algorithms/rnea.hpp"
#include "spatial_dynamics/model/contact_data.hpp"
#include "spatial_dynamics/model/contact_set.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/joints/body_joint.hpp"
#include "spatial_dynamics/model/model.hpp"

namespace spatial_dynamics {
namespace detail {

/// The base's acceleration in an RNEA pass: −a_g.
template <class S>
MotionVector<S> gravity_base_acceleration(const Model<S>& model) {
  return MotionVector<S>(Vector3<S>::Zero(), Vector3<S>(-model.gravity));
}

/// A contact's classical acceleration (α ; a + ω × v) (RBDA §2.11) into cd.acceleration, from its body's
/// velocity and acceleration of an RNEA pass less the base's a_0 = −a_g, given in the frame (^FX_0 a_0).
template <class S>
void contact_acceleration(const Model<S>& model, const Data<S>& data, const Contact<S>& contact, ContactData<S>& cd,
                          const MotionVector<S>& a_0) {
  const Frame<S>& frame = model.frames[contact.frame];
  const MotionVector<S> v = frame.X_frame_body.apply(data.v[frame.body]);
  const MotionVector<S> a = frame.X_frame_body.apply(data.a[frame.body]) - a_0;
  const Vec3<S> linear = a.linear + cross(v.angular, v.linear);
  for (int k = 0; k < 3; ++k) {
    if (contact.kind == ContactKind::Surface) cd.acceleration[contact.row + k] = a.angular[k];
    cd.acceleration[contact.row + (contact.kind == ContactKind::Surface ? 3 : 0) + k] = linear[k];
  }
}

/// J_c into cd.J and the contacts' classical accelerations at the pass's q̈ into cd.acceleration,
/// from an RNEA pass (v, a) and the CRBA's data.X_base and data.S_base (S̃_j: base axes, about body j's
/// origin p_j). Column of joint j: S̃_j = (ω ; v) moved to the frame's origin p_F, (ω ; v + ω ×
/// (p_F − p_j)), in the frame's axes (E_F0), scaled by a coupled joint's multiplier onto its master's
/// coordinate: one rotation per column instead of two transforms.
template <class S>
void contact_kinematics(const Model<S>& model, Data<S>& data, const ContactSet<S>& contacts, ContactData<S>& cd) {
  cd.J.setZero();
  for (const Contact<S>& contact : contacts.contacts) {
    const Frame<S>& frame = model.frames[contact.frame];
    const PluckerTransform<S> X_F0 = frame.X_frame_body * data.X_base[frame.body];
    const bool surface = contact.kind == ContactKind::Surface;
    const Eigen::Index linear_row = contact.row + (surface ? 3 : 0);
    for (int j = frame.body; j > 0; j = model.parent[j]) {
      const Joint<S>& joint = model.joints[j];
      const S k_j = coupling_multiplier(joint);
      const Vec3<S> p = X_F0.r - data.X_base[j].r;  // p_F − p_j
      for (int k = 0; k < joint.nv; ++k) {
        const MotionVector<S>& s = data.S_base[j][k];
        const Vec3<S> linear = X_F0.E * (s.linear + cross(s.angular, p));
        const Eigen::Index col = joint.idx_v + k;
        for (int m = 0; m < 3; ++m) cd.J(linear_row + m, col) += k_j * linear[m];
        if (!surface) continue;
        const Vec3<S> angular = X_F0.E * s.angular;
        for (int m = 0; m < 3; ++m) cd.J(contact.row + m, col) += k_j * angular[m];
      }
    }
    contact_acceleration(model, data, contact, cd, X_F0.apply(gravity_base_acceleration(model)));
  }
}

/// The pattern of a factor M = Lᵀ L (RBDA §6.5): row k of L is nonzero only at k and its ancestors
/// parent(k), parent(parent(k)), … (−1 ends), so column k only over k's subtree, rows k .. k +
/// subtree(k) − 1. The coordinates' tree of ContactData for M; a chain for a dense matrix.
template <class S>
struct TreePattern {
  const ContactData<S>& cd;
  int parent(int k) const { return cd.dof_parent[k]; }
  int subtree(int k) const { return cd.subtree_dofs[k]; }
};
struct ChainPattern {
  int n;
  int parent(int k) const { return k - 1; }
  int subtree(int k) const { return n - k; }
};
/// A spatial inertia's 6 × 6 matrix (RigidInertia::toMatrix): its linear block m 1 is diagonal, so
/// the three linear coordinates are leaves hanging from the angular chain 0 ← 1 ← 2 (no fill).
struct InertiaPattern {
  int parent(int k) const { return k < 3 ? k - 1 : 2; }
  int subtree(int k) const { return k < 3 ? 6 - k : 1; }
};

/// M = Lᵀ L into L (RBDA §6.5, the LTL factorisation, which keeps M's tree sparsity) row by row from
/// the last coordinate (Table 6.3 gets the same factor by outer products): each entry from
/// M_ij = L_ii L_ij + Σ_{i < k < i + subtree(i)} L_ki L_kj for j = i and its ancestors, a dot product
/// of two columns over i's subtree. False, at the first pivot L_ii² not above `guard` M_ii.
template <class Matrix, class Pattern>
bool ltl_factor(const Matrix& M, Matrix& L, const Pattern& pattern, const typename Matrix::Scalar& guard) {
  using S = typename Matrix::Scalar;
  using std::sqrt;
  for (int i = static_cast<int>(M.rows()) - 1; i >= 0; --i) {
    const int end = i + pattern.subtree(i);
    S pivot = M(i, i);
    for (int k = i + 1; k < end; ++k) pivot -= L(k, i) * L(k, i);
    if (pivot <= guard * M(i, i)) return false;
    L(i, i) = sqrt(pivot);
    for (int j = pattern.parent(i); j >= 0; j = pattern.parent(j)) {
      S sum = M(i, j);
      for (int k = i + 1; k < end; ++k) sum -= L(k, i) * L(k, j);
      L(i, j) = sum / L(i, i);
    }
  }
  return true;
}

/// Step i of x ← L⁻ᵀ x (Lᵀ y = x solved from the last coordinate up): x_i = (x_i − Σ_{i < k < i +
/// subtree(i)} L_ki x_k) / L_ii, taken for every i from the last down.
template <class Matrix, class Pattern, class Vector>
SD_INLINE void ltl_transpose_step(const Matrix& L, const Pattern& pattern, Vector& x, int i) {
  using S = typename Matrix::Scalar;
  const S inverse = S(1) / L(i, i);  // off the dependency chain of the x_i
  S sum = x[i];
  for (int k = i + 1; k < i + pattern.subtree(i); ++k) sum -= L(k, i) * x[k];
  x[i] = sum * inverse;
}

/// x ← (Lᵀ L)⁻¹ x: Lᵀ y = x from the last coordinate up (unless done), then L z = y from the first on
/// (z_i = y_i / L_ii, then column i's multiple taken from the rest of i's subtree).
template <class Matrix, class Pattern, class Vector>
void ltl_solve(const Matrix& L, const Pattern& pattern, Vector& x, bool transpose_done = false) {
  const int n = static_cast<int>(x.size());
  if (!transpose_done)
    for (int i = n - 1; i >= 0; --i) ltl_transpose_step(L, pattern, x, i);
  for (int i = 0; i < n; ++i) {
    x[i] *= typename Matrix::Scalar(1) / L(i, i);
    for (int k = i + 1; k < i + pattern.subtree(i); ++k) x[k] -= L(k, i) * x[i];
  }
}

/// A Gram matrix's factor: false when a pivot falls below √ε of its diagonal (G singular to rounding,
/// or too ill-conditioned for the factor: the caller turns to the COD).
template <class Matrix, class Pattern>
bool gram_factor(const Matrix& G, Matrix& L, const Pattern& pattern) {
  using std::sqrt;
  using Scalar = typename Matrix::Scalar;
  return ltl_factor(G, L, pattern, Scalar(sqrt(Eigen::NumTraits<Scalar>::epsilon())));
}

/// A contact's wrench in its frame from its rows of λ (a point: the force alone).
template <class S>
SD_INLINE ForceVector<S> contact_wrench(const Contact<S>& contact, const VectorX<S>& lambda) {
  const bool surface = contact.kind == ContactKind::Surface;
  ForceVector<S> wrench = ForceVector<S>::Zero();
  for (int m = 0; m < 3; ++m) {
    if (surface) wrench.angular[m] = lambda[contact.row + m];
    wrench.linear[m] = lambda[contact.row + (surface ? 3 : 0) + m];
  }
  return wrench;
}

/// λ's rows of a contact += its rows of the motion m (in its frame).
template <class S>
SD_INLINE void add_contact_rows(const Contact<S>& contact, const MotionVector<S>& m, VectorX<S>& lambda) {
  const bool surface = contact.kind == ContactKind::Surface;
  for (int k = 0; k < 3; ++k) {
    if (surface) lambda[contact.row + k] += m.angular[k];
    lambda[contact.row + (surface ? 3 : 0) + k] += m.linear[k];
  }
}

/// The base rows B = J_c,baseᵀ (6 × rows) into cd.base_rows from the contacts' ^FX_r (cd.contact_root):
/// column by column the root's share ^FX_rᵀ e of a unit wrench e along the row (zero off the root's tree).
template <class S>
void fill_base_rows(const ContactSet<S>& contacts, ContactData<S>& cd) {
  for (std::size_t c = 0; c < contacts.contacts.size(); ++c) {
    const Contact<S>& contact = contacts.contacts[c];
    const bool surface = contact.kind == ContactKind::Surface;
    for (int m = 0; m < contact_rows(contact.kind); ++m) {
      Vec3<S> unit;
      unit[m % 3] = S(1);
      const ForceVector<S> e = surface && m < 3 ? ForceVector<S>(unit, Vec3<S>()) : ForceVector<S>(Vec3<S>(), unit);
      const Vector6<S> column = cd.on_root[c] ? cd.contact_root[c].applyInverse(e).toVector() : Vector6<S>::Zero();
      cd.base_rows.col(contact.row + m) = column;
    }
  }
}

/// λ of minimum norm with B λ = b for the base rows B (six rows or more) by the Gram matrix:
/// λ = Bᵀ w with (B Bᵀ) w = b. With the root's S = 1 (a free joint), Bᵀ w gives each contact its rows
/// of ^FX_r w, and B Bᵀ = Σ ^FX_rᵀ P_c ^FX_r with P_c the selection of the contact's rows: as a
/// spatial inertia, a unit mass at the frame's origin (with a unit rotational inertia for a surface
/// contact), which ^FX_rᵀ · ^FX_r carries to root coordinates (plucker_transform.hpp, eq. 26); P_c is
/// invariant under rotation, so only its reference point moves. So formed from the contacts'
/// positions, B Bᵀ keeps λ as accurate as a decomposition of B (test_contact_dynamics). False, λ
/// untouched, when the factor shows B Bᵀ singular: B rank deficient.
template <class S>
bool base_gram_solve(const ContactSet<S>& contacts, ContactData<S>& cd, const Vector6<S>& b) {
  RigidInertia<S> gram = RigidInertia<S>::Zero();
  for (std::size_t c = 0; c < contacts.contacts.size(); ++c) {
    if (!cd.on_root[c]) continue;
    const bool surface = contacts.contacts[c].kind == ContactKind::Surface;
    const RigidInertia<S> P(S(1), Vec3<S>(), surface ? Mat3<S>::Identity() : Mat3<S>::Zero());
    gram += P.aboutPoint(-cd.contact_root[c].r);
  }
  cd.gram = gram.toMatrix();
  const InertiaPattern pattern;
  if (!gram_factor(cd.gram, cd.gram_factor, pattern)) return false;
  Vector6<S> w = b;
  ltl_solve(cd.gram_factor, pattern, w);
  cd.lambda.setZero();
  for (std::size_t c = 0; c < contacts.contacts.size(); ++c)
    if (cd.on_root[c]) add_contact_rows(contacts.contacts[c], cd.contact_root[c].apply(MotionVector<S>(w)), cd.lambda);
  return true;
}

}  // namespace detail

/// J_c(q) into cd.J and J̇_c q̇ (the contacts' classical accelerations at q̈ = 0) into cd.acceleration.
template <class S>
const MatrixX<S>& contact_jacobian(const Model<S>& model, Data<S>& data, const ContactSet<S>& contacts,
                                   ContactData<S>& cd, const ConstVectorRef<S>& q, const ConstVectorRef<S>& qd) {
  detail::rnea_impl<S, true>(model, data, q, qd, data.zero_v, nullptr, model.gravity);  // v, a at q̈ = 0
  detail::composite_inertias(model, data, q);                                          // X_base, S̃
  detail::contact_kinematics(model, data, contacts, cd);
  detail::check_finite_result(model, "contact Jacobian: the column", cd.J);
  return cd.J;
}

namespace detail {

/// inverse_dynamics_with_contacts below, with external forces f_ext[i] on body i (or none: nullptr).
template <class S>
const VectorX<S>& inverse_dynamics_with_contacts_impl(const Model<S>& model, Data<S>& data, const ContactSet<S>& contacts,
                                                      ContactData<S>& cd, const ConstVectorRef<S>& q,
                                                      const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd,
                                                      const ForceVector<S>* f_ext) {
  cd.tau = rnea_impl(model, data, q, qd, qdd, f_ext);
  const bool balance = model.floating_base && contacts.rows > 0;
  const int root = balance ? 1 : -1;  // the floating root body (a free joint: S = 1)
  const MotionVector<S> a_0 = detail::gravity_base_acceleration(model);
  const MotionVector<S> a_0_root = balance ? data.X_up[root].apply(a_0) : a_0;
  for (std::size_t c = 0; c < contacts.contacts.size(); ++c) {
    // ^FX_j for the bodies j of the frame's branch (cd.contact_branch), then ^FX_r (^FX_0 off the root's tree).
    const Frame<S>& frame = model.frames[contacts.contacts[c].frame];
    PluckerTransform<S>& X = cd.contact_root[c] = frame.X_frame_body;
    int j = frame.body;
    for (std::size_t t = 0; j > 0 && j != root; j = model.parent[j], ++t) {
      if (balance) cd.contact_branch[c][t] = X;
      X = X * data.X_up[j];
    }
    cd.on_root[c] = j == root;
    detail::contact_acceleration(model, data, contacts.contacts[c], cd, X.apply(cd.on_root[c] ? a_0_root : a_0));
  }
  cd.lambda.setZero();
  if (balance) {
    const Eigen::Index base = model.joints[root].idx_v;
    const Vector6<S> b = cd.tau.segment(base, 6);
    if (contacts.rows < 6 || !detail::base_gram_solve(contacts, cd, b)) {
      detail::fill_base_rows(contacts, cd);
      cd.base_solver.compute(cd.base_rows);
      cd.lambda = cd.base_solver.solve(b);
    }
    // τ −= J_cᵀ λ: each contact's wrench in the coordinates of each body j of its branch, f = ^FX_jᵀ λ
    // (what the RNEA's eq. 5.11 carries there), τ_j −= S_jᵀ f (eq. 5.10), on a coupled joint's master
    // coordinate scaled by k; the root's share of them all together, which leaves on the base rows the
    // wrench not balanced.
    ForceVector<S> f_root = ForceVector<S>::Zero();
    for (std::size_t c = 0; c < contacts.contacts.size(); ++c) {
      const ForceVector<S> wrench = detail::contact_wrench(contacts.contacts[c], cd.lambda);
      int i = model.frames[contacts.contacts[c].frame].body;
      for (std::size_t t = 0; i > 0 && i != root; i = model.parent[i], ++t) {
        const Joint<S>& joint = model.joints[i];
        S projected[6];
        body_joint_project(model, data, i, cd.contact_branch[c][t].applyInverse(wrench), projected);
        const S k_i = coupling_multiplier(joint);
        for (int l = 0; l < joint.nv; ++l) cd.tau[joint.idx_v + l] -= k_i * projected[l];
      }
      if (cd.on_root[c]) f_root += cd.contact_root[c].applyInverse(wrench);
    }
    S projected[6];
    body_joint_project(model, data, root, f_root, projected);
    for (int l = 0; l < 6; ++l) cd.tau[base + l] -= projected[l];
  }
  detail::check_finite_result(model, "inverse dynamics with contacts: the joint force", cd.tau);
  return cd.tau;
}

/// forward_dynamics_with_contacts below, with external forces f_ext[i] on body i (or none: nullptr).
template <class S>
const VectorX<S>& forward_dynamics_with_contacts_impl(const Model<S>& model, Data<S>& data, const ContactSet<S>& contacts,
                                                      ContactData<S>& cd, const ConstVectorRef<S>& q,
                                                      const ConstVectorRef<S>& qd, const ConstVectorRef<S>& tau,
                                                      const ForceVector<S>* f_ext) {
  detail::check_length("effort", tau.size(), model.nv);
  detail::rnea_impl(model, data, q, qd, data.zero_v, f_ext);  // h − Σ J_iᵀ f_ext,i; J̇_c q̇'s v, a
  const detail::TreePattern<S> tree{cd};
  if (!detail::ltl_factor(crba<S>(model, data, q), cd.L, tree, S(0)))  // crba: also X_base and S̃ for J_c
    throw std::domain_error("the mass matrix is not positive definite (a massless subtree?): forward dynamics is undefined");
  cd.qdd = tau - data.tau;
  for (int i = model.nv - 1; i >= 0; --i) detail::ltl_transpose_step(cd.L, tree, cd.qdd, i);  // z = L⁻ᵀ (τ − h)
  cd.lambda.setZero();
  if (contacts.rows > 0) {
    detail::contact_kinematics(model, data, contacts, cd);  // J_c, J̇_c q̇
    cd.L_inv_Jt = cd.J.transpose();
    // Y = L⁻ᵀ J_cᵀ: a contact's columns are zero but on its coordinates (cd.contact_dofs, the last
    // first) and stay so; ltl_transpose_step's sum over those alone, the contact's columns together.
    for (std::size_t c = 0; c < contacts.contacts.size(); ++c) {
      const std::vector<int>& dofs = cd.contact_dofs[c];
      const int first = contacts.contacts[c].row, end = first + contact_rows(contacts.contacts[c].kind);
      for (std::size_t t = 0; t < dofs.size(); ++t) {
        const int i = dofs[t];
        for (std::size_t u = 0; u < t; ++u) {
          const S l = cd.L(dofs[u], i);
          for (int r = first; r < end; ++r) cd.L_inv_Jt(i, r) -= l * cd.L_inv_Jt(dofs[u], r);
        }
        const S inverse = S(1) / cd.L(i, i);
        for (int r = first; r < end; ++r) cd.L_inv_Jt(i, r) *= inverse;
      }
    }
    cd.K.noalias() = cd.L_inv_Jt.transpose() * cd.L_inv_Jt;  // J_c M⁻¹ J_cᵀ
    cd.rhs = -cd.acceleration;
    cd.rhs.noalias() -= cd.L_inv_Jt.transpose() * cd.qdd;  // − J_c q̈_free = − Yᵀ z
    if (detail::gram_factor(cd.K, cd.K_factor, detail::ChainPattern{contacts.rows})) {
      cd.lambda = cd.rhs;
      detail::ltl_solve(cd.K_factor, detail::ChainPattern{contacts.rows}, cd.lambda);
    } else {
      cd.K_solver.compute(cd.K);
      cd.lambda = cd.K_solver.solve(cd.rhs);
    }
    cd.qdd.noalias() += cd.L_inv_Jt * cd.lambda;  // z + Y λ
  }
  detail::ltl_solve(cd.L, tree, cd.qdd, true);  // q̈ = L⁻¹ (z + Y λ)
  if (contacts.rows > 0) cd.acceleration.noalias() += cd.J * cd.qdd;  // J̇_c q̇ + J_c q̈
  detail::check_finite_result(model, "forward dynamics with contacts: the acceleration", cd.qdd);
  return cd.qdd;
}

}  // namespace detail

/// τ and λ with ID(q, q̇, q̈) = τ + J_cᵀ λ (cd.tau, cd.lambda): for a floating base, λ is the
/// minimum-norm least-squares solution of the base's six rows J_c,baseᵀ λ = ID_base, and cd.tau's
/// base rows hold the wrench the contacts leave on the base (root body axes, about its origin: zero
/// when they balance it); for a fixed base λ = 0. cd.acceleration: J_c q̈ + J̇_c q̇, how far the motion
/// breaks the contacts. cd.J is not computed; cd.base_rows (J_c,baseᵀ) only when the contacts cannot
/// balance the base (fewer than six rows, or rank deficient).
template <class S>
const VectorX<S>& inverse_dynamics_with_contacts(const Model<S>& model, Data<S>& data, const ContactSet<S>& contacts,
                                                 ContactData<S>& cd, const ConstVectorRef<S>& q,
                                                 const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd) {
  return detail::inverse_dynamics_with_contacts_impl(model, data, contacts, cd, q, qd, qdd,
                                                     static_cast<const ForceVector<S>*>(nullptr));
}

/// As above with external forces f_ext[i] on body i (body coordinates; entry 0 unused), as rnea takes
/// them: ID(q, q̇, q̈, f_ext) = τ + J_cᵀ λ, so the contacts balance what the external forces leave.
template <class S>
const VectorX<S>& inverse_dynamics_with_contacts(const Model<S>& model, Data<S>& data, const ContactSet<S>& contacts,
                                                 ContactData<S>& cd, const ConstVectorRef<S>& q,
                                                 const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd,
                                                 const std::vector<ForceVector<S>>& f_ext) {
  detail::check_external_forces(model, f_ext);
  return detail::inverse_dynamics_with_contacts_impl(model, data, contacts, cd, q, qd, qdd, f_ext.data());
}

/// q̈ and λ (cd.qdd, cd.lambda) of M q̈ + h = τ + J_cᵀ λ with J_c q̈ + J̇_c q̇ = 0; cd.acceleration
/// then holds J_c q̈ + J̇_c q̇ (zero up to rounding). With M = Lᵀ L (cd.L) and z = L⁻ᵀ (τ − h):
/// Y = L⁻ᵀ J_cᵀ (cd.L_inv_Jt), K = Yᵀ Y, K λ = −J̇_c q̇ − Yᵀ z, q̈ = L⁻¹ (z + Y λ). A mass matrix that
/// is not positive definite (a massless floating root) throws std::domain_error.
template <class S>
const VectorX<S>& forward_dynamics_with_contacts(const Model<S>& model, Data<S>& data, const ContactSet<S>& contacts,
                                                 ContactData<S>& cd, const ConstVectorRef<S>& q,
                                                 const ConstVectorRef<S>& qd, const ConstVectorRef<S>& tau) {
  return detail::forward_dynamics_with_contacts_impl(model, data, contacts, cd, q, qd, tau,
                                                     static_cast<const ForceVector<S>*>(nullptr));
}

/// As above with external forces f_ext[i] on body i (body coordinates; entry 0 unused):
/// M q̈ + h = τ + Σ J_iᵀ f_ext,i + J_cᵀ λ.
template <class S>
const VectorX<S>& forward_dynamics_with_contacts(const Model<S>& model, Data<S>& data, const ContactSet<S>& contacts,
                                                 ContactData<S>& cd, const ConstVectorRef<S>& q,
                                                 const ConstVectorRef<S>& qd, const ConstVectorRef<S>& tau,
                                                 const std::vector<ForceVector<S>>& f_ext) {
  detail::check_external_forces(model, f_ext);
  return detail::forward_dynamics_with_contacts_impl(model, data, contacts, cd, q, qd, tau, f_ext.data());
}

}  // namespace spatial_dynamics
