// Centre of mass and centroidal momentum (Orin, Goswami and Lee, "Centroidal dynamics of a humanoid
// robot", Autonomous Robots 35, 2013): c = Σ m_i c_i / m, ċ = J_com q̇, and the centroidal momentum
// matrix A_G with h_G = A_G q̇ — the system's spatial momentum about the centre of mass in base axes
// (angular; linear). Column k of A_G is the momentum of the subtree a joint moves at unit q̇_k,
// Iᶜ_i S̃_i (the composite inertias of the CRBA, crba.hpp) moved to the centre of mass.
#pragma once

#include <stdexcept>

#include "spatial_dynamics/algorithms/crba.hpp"
#include "spatial_dynamics/algorithms/energy.hpp"
#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"

namespace spatial_dynamics {
namespace detail {

/// m = Σ m_i; a model without mass has no centre of mass (std::domain_error).
template <class S>
S total_mass(const Model<S>& model) {
  S mass(0);
  for (int i = 1; i < model.nbodies(); ++i) mass += model.inertia[i].mass;
  if (!(mass > S(0))) throw std::domain_error("centre of mass: the model's bodies have no mass");
  return mass;
}

/// c from the composite inertias of the roots (data.Ic about each root's origin p_r, base axes):
/// m c = Σ_r (m_r p_r + h_r).
template <class S>
Vec3<S> center_of_mass_from_composites(const Model<S>& model, const Data<S>& data, const S& mass) {
  Vec3<S> first_moment = Vec3<S>::Zero();
  for (int r = 1; r < model.nbodies(); ++r)
    if (model.parent[r] == 0) first_moment += data.Ic[r].mass * data.X_base[r].r + data.Ic[r].first_moment;
  return first_moment * (S(1) / mass);
}

}  // namespace detail

/// The centre of mass c(q) in base coordinates.
template <class S>
Vector3<S> center_of_mass(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q) {
  const S mass = detail::total_mass(model);
  detail::composite_inertias(model, data, q);
  const Vector3<S> c = detail::center_of_mass_from_composites(model, data, mass).eigen();
  detail::check_finite_value(model, "centre of mass", c);
  return c;
}

/// ċ = (linear momentum) / m, in base coordinates.
template <class S>
Vector3<S> center_of_mass_velocity(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                   const ConstVectorRef<S>& qd) {
  const S mass = detail::total_mass(model);
  return (total_momentum(model, data, q, qd).linear * (S(1) / mass)).eigen();
}

/// A_G(q) into data.A_G (6 × nv): h_G = A_G q̇, the momentum about the centre of mass in base axes
/// (angular rows first). Column of joint i's S̃_i: Iᶜ_i S̃_i about p_i moved to c (eq. 26's shift of
/// a force); a coupled joint's column adds k times to its master's.
template <class S>
const Matrix6X<S>& centroidal_momentum_matrix(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q) {
  const S mass = detail::total_mass(model);
  detail::composite_inertias(model, data, q);
  const Vec3<S> c = detail::center_of_mass_from_composites(model, data, mass);
  if (model.has_coupled_joints) data.A_G.setZero();
  for (int i = 1; i < model.nbodies(); ++i) {
    const Joint<S>& joint = model.joints[i];
    const S k_i = coupling_multiplier(joint);
    for (int k = 0; k < joint.nv; ++k) {
      const Vector6<S> column = (data.Ic[i] * data.S_base[i][k]).aboutPoint(c - data.X_base[i].r).toVector();
      if (model.has_coupled_joints)
        data.A_G.col(joint.idx_v + k) += k_i * column;
      else
        data.A_G.col(joint.idx_v + k) = column;
    }
  }
  detail::check_finite_result(model, "centroidal momentum matrix: the column", data.A_G);
  return data.A_G;
}

/// h_G = A_G q̇: the momentum about the centre of mass in base axes.
template <class S>
ForceVector<S> centroidal_momentum(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                   const ConstVectorRef<S>& qd) {
  detail::check_length("velocity", qd.size(), model.nv);
  return ForceVector<S>(Vector6<S>(centroidal_momentum_matrix(model, data, q) * qd));
}

/// J_com(q) into data.J_com (3 × nv): ċ = J_com q̇, the linear rows of A_G over m.
template <class S>
const MatrixX<S>& center_of_mass_jacobian(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q) {
  const S mass = detail::total_mass(model);
  data.J_com = centroidal_momentum_matrix(model, data, q).template bottomRows<3>() * (S(1) / mass);
  return data.J_com;
}

}  // namespace spatial_dynamics
