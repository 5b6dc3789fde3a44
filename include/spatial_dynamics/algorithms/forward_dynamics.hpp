// Forward dynamics for any model: the ABA (RBDA Table 7.1) where it applies, and for a model with
// coupled mimic joints (a constraint the ABA's recursion cannot express) M q̈ = τ − h solved by
// the CRBA and a Cholesky factorisation (RBDA §6.1).
#pragma once

#include <Eigen/Cholesky>
#include <stdexcept>
#include <vector>

#include "spatial_dynamics/algorithms/aba.hpp"
#include "spatial_dynamics/algorithms/crba.hpp"
#include "spatial_dynamics/algorithms/rnea.hpp"
#include "spatial_dynamics/compiled/compiled_functions.hpp"
#include "spatial_dynamics/simd_backend.hpp"

namespace spatial_dynamics {
namespace detail {

template <class S>
const VectorX<S>& crba_forward_dynamics(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                        const ConstVectorRef<S>& qd, const ConstVectorRef<S>& tau,
                                        const ForceVector<S>* f_ext) {
  check_length("effort", tau.size(), model.nv);
  rnea_impl(model, data, q, qd, data.zero_v, f_ext);  // h = C q̇ + g − Jᵀ f_ext
  data.qdd = tau - data.tau;
  data.llt.compute(crba<S>(model, data, q));
  if (data.llt.info() != Eigen::Success)
    throw std::domain_error("the mass matrix is not positive definite (a massless subtree?): forward dynamics is undefined");
  data.llt.solveInPlace(data.qdd);
  check_finite_result(model, "forward dynamics: the acceleration", data.qdd);
  return data.qdd;
}

}  // namespace detail

/// q̈ = FD(q, q̇, τ) in data.qdd.
template <class S>
const VectorX<S>& forward_dynamics(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                   const ConstVectorRef<S>& qd, const ConstVectorRef<S>& tau) {
  if (!model.has_coupled_joints) return aba<S>(model, data, q, qd, tau);
  return detail::crba_forward_dynamics(model, data, q, qd, tau, static_cast<const ForceVector<S>*>(nullptr));
}

/// As above with external forces f_ext[i] on body i (body coordinates; entry 0 unused).
template <class S>
const VectorX<S>& forward_dynamics(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                   const ConstVectorRef<S>& qd, const ConstVectorRef<S>& tau,
                                   const std::vector<ForceVector<S>>& f_ext) {
  if (!model.has_coupled_joints) return aba<S>(model, data, q, qd, tau, f_ext);
  detail::check_external_forces(model, f_ext);
  return detail::crba_forward_dynamics(model, data, q, qd, tau, f_ext.data());
}

}  // namespace spatial_dynamics
