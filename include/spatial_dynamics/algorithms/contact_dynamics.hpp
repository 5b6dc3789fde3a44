// Dynamics with rigid contacts (model/contact_set.hpp). A contact holds its frame: its classical
// acceleration is zero, J_c q̈ + J̇_c q̇ = 0, with J_c the contact rows of the frame's Jacobian in the
// frame's axes and J̇_c q̇ the classical acceleration (α ; a + ω × v) at q̈ = 0 (RBDA §2.11: the spatial
// acceleration of the frame plus ω × v for its origin). Its wrench λ enters the equations of motion
// as J_cᵀ λ:
//   M q̈ + h = τ + J_cᵀ λ.
// inverse_dynamics_with_contacts: given q̈, the λ of minimum norm that balances a floating base's six
//   unactuated rows (least squares when the contacts cannot), then τ = ID(q, q̇, q̈) − J_cᵀ λ;
// forward_dynamics_with_contacts: given τ, q̈ and λ of the KKT system [M J_cᵀ; J_c 0] through the
//   Cholesky factor of M (RBDA §6.1): q̈ = q̈_free + M⁻¹ J_cᵀ λ with (J_c M⁻¹ J_cᵀ) λ = −J̇_c q̇ − J_c q̈_free,
//   λ of minimum norm when the contacts are redundant (q̈ is unique all the same).
#pragma once

#include <stdexcept>

#include "spatial_dynamics/algorithms/forward_dynamics.hpp"
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

/// J_c into cd.J and the contacts' classical accelerations into cd.acceleration, from an RNEA pass
/// (data.X_up, v, a with the base's acceleration a_0) and data.X_base. Column of joint j:
/// ^FX_0 (^jX_0)⁻¹ S_j, scaled by a coupled joint's multiplier onto its master's coordinate.
template <class S>
void contact_kinematics(const Model<S>& model, Data<S>& data, const ContactSet<S>& contacts, ContactData<S>& cd,
                        const MotionVector<S>& a_0) {
  cd.J.setZero();
  for (const Contact<S>& contact : contacts.contacts) {
    const Frame<S>& frame = model.frames[contact.frame];
    const int body = frame.body;
    const int first = contact.kind == ContactKind::Point ? 3 : 0;  // a point contact: the linear rows
    const int n = 6 - first;
    const PluckerTransform<S> X_F0 = frame.X_frame_body * data.X_base[body];
    for (int j = body; j > 0; j = model.parent[j]) {
      const Joint<S>& joint = model.joints[j];
      const S k_j = coupling_multiplier(joint);
      for (int k = 0; k < joint.nv; ++k) {
        const Vector6<S> column = X_F0.apply(data.X_base[j].applyInverse(body_subspace_column(model, data, j, k))).toVector();
        cd.J.block(contact.row, joint.idx_v + k, n, 1) += k_j * column.tail(n);
      }
    }
    // The frame's spatial velocity and acceleration (a_0 removed), then the origin's classical acceleration.
    const MotionVector<S> v = frame.X_frame_body.apply(data.v[body]);
    const MotionVector<S> a = frame.X_frame_body.apply(data.a[body] - data.X_base[body].apply(a_0));
    Vector6<S> classical;
    classical << a.angular.eigen(), (a.linear + cross(v.angular, v.linear)).eigen();
    cd.acceleration.segment(contact.row, n) = classical.tail(n);
  }
}

/// The base's acceleration in an RNEA pass: −a_g.
template <class S>
MotionVector<S> gravity_base_acceleration(const Model<S>& model) {
  return MotionVector<S>(Vector3<S>::Zero(), Vector3<S>(-model.gravity));
}

}  // namespace detail

/// J_c(q) into cd.J and J̇_c q̇ (the contacts' classical accelerations at q̈ = 0) into cd.acceleration.
template <class S>
const MatrixX<S>& contact_jacobian(const Model<S>& model, Data<S>& data, const ContactSet<S>& contacts,
                                   ContactData<S>& cd, const ConstVectorRef<S>& q, const ConstVectorRef<S>& qd) {
  detail::rnea_impl(model, data, q, qd, data.zero_v, static_cast<const ForceVector<S>*>(nullptr));
  update_body_poses(model, data);
  detail::contact_kinematics(model, data, contacts, cd, detail::gravity_base_acceleration(model));
  detail::check_finite_result(model, "contact Jacobian: the column", cd.J);
  return cd.J;
}

/// τ and λ with ID(q, q̇, q̈) = τ + J_cᵀ λ (cd.tau, cd.lambda): for a floating base, λ is the
/// minimum-norm least-squares solution of the base's six rows J_c,baseᵀ λ = ID_base, and cd.tau's
/// base rows hold the wrench the contacts leave on the base (root body axes, about its origin: zero
/// when they balance it); for a fixed base λ = 0. cd.acceleration: J_c q̈ + J̇_c q̇, how far the motion
/// breaks the contacts.
template <class S>
const VectorX<S>& inverse_dynamics_with_contacts(const Model<S>& model, Data<S>& data, const ContactSet<S>& contacts,
                                                 ContactData<S>& cd, const ConstVectorRef<S>& q,
                                                 const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd) {
  cd.tau = detail::rnea_impl(model, data, q, qd, qdd, static_cast<const ForceVector<S>*>(nullptr));
  update_body_poses(model, data);
  detail::contact_kinematics(model, data, contacts, cd, detail::gravity_base_acceleration(model));
  cd.lambda.setZero();
  if (model.floating_base && contacts.rows > 0) {
    const Eigen::Index base = model.joints[1].idx_v;
    cd.base_rows = cd.J.middleCols(base, 6).transpose();
    cd.base_solver.compute(cd.base_rows);
    cd.lambda = cd.base_solver.solve(cd.tau.segment(base, 6));
    cd.tau.noalias() -= cd.J.transpose() * cd.lambda;
  }
  detail::check_finite_result(model, "inverse dynamics with contacts: the joint force", cd.tau);
  return cd.tau;
}

/// q̈ and λ (cd.qdd, cd.lambda) of M q̈ + h = τ + J_cᵀ λ with J_c q̈ + J̇_c q̇ = 0; cd.acceleration
/// then holds J_c q̈ + J̇_c q̇ (zero up to rounding). A mass matrix that is not positive definite (a
/// massless floating root) throws std::domain_error.
template <class S>
const VectorX<S>& forward_dynamics_with_contacts(const Model<S>& model, Data<S>& data, const ContactSet<S>& contacts,
                                                 ContactData<S>& cd, const ConstVectorRef<S>& q,
                                                 const ConstVectorRef<S>& qd, const ConstVectorRef<S>& tau) {
  cd.qdd = detail::crba_forward_dynamics(model, data, q, qd, tau, static_cast<const ForceVector<S>*>(nullptr));
  detail::contact_kinematics(model, data, contacts, cd, detail::gravity_base_acceleration(model));  // J̇_c q̇
  cd.lambda.setZero();
  if (contacts.rows > 0) {
    cd.L_inv_Jt = cd.J.transpose();
    data.llt.matrixL().solveInPlace(cd.L_inv_Jt);             // L⁻¹ J_cᵀ
    cd.K.noalias() = cd.L_inv_Jt.transpose() * cd.L_inv_Jt;  // J_c M⁻¹ J_cᵀ
    cd.rhs = -cd.acceleration;
    cd.rhs.noalias() -= cd.J * cd.qdd;
    cd.K_solver.compute(cd.K);
    cd.lambda = cd.K_solver.solve(cd.rhs);
    data.qdd.noalias() = cd.J.transpose() * cd.lambda;
    data.llt.solveInPlace(data.qdd);  // M⁻¹ J_cᵀ λ
    cd.qdd += data.qdd;
    cd.acceleration.noalias() += cd.J * cd.qdd;  // J̇_c q̇ + J_c q̈
  }
  detail::check_finite_result(model, "forward dynamics with contacts: the acceleration", cd.qdd);
  return cd.qdd;
}

}  // namespace spatial_dynamics
