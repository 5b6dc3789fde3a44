// The float128 reference for one state: the same algorithms on the double model converted
// exactly (Model::cast), fed the same double inputs converted exactly.
#pragma once

#include "benchmark_actuators.hpp"
#include "benchmark_contacts.hpp"
#include "benchmark_types.hpp"
#include "spatial_dynamics/algorithms.hpp"
#include "spatial_dynamics/estimation/momentum_observer.hpp"
#include "spatial_dynamics/reference/high_precision.hpp"
#include "spatial_dynamics/reference/pseudo_inverse.hpp"

namespace bench {

class Reference {
 public:
  using Quad = spatial_dynamics::Quad;
  using VectorQ = spatial_dynamics::VectorX<Quad>;

  /// `with_actuated`: also the rows with actuator terms (rnea_actuated, aba_actuated).
  Reference(const spatial_dynamics::Model<double>& model, bool with_actuated)
      : model_(model.cast<Quad>()), actuated_model_(with_benchmark_actuators(model).cast<Quad>()), data_(model_),
        observer_(actuated_model_, VectorQ::Constant(model_.nv, Quad(50))), with_actuated_(with_actuated),
        contacts_(benchmark_contacts(model_)), contact_data_(model_, contacts_) {}

  /// Computes every reference result for state s; the mass matrix only when `with_mass_matrix`
  /// (O(n²) in software quad precision: the caller budgets it on large models).
  void compute(const State& s, bool with_mass_matrix) {
    namespace sd = spatial_dynamics;
    const VectorQ q = sd::to_quad(s.q), qd = sd::to_quad(s.qd), qdd = sd::to_quad(s.qdd), tau = sd::to_quad(s.tau);
    tau_ = sd::rnea(model_, data_, q, qd, qdd);
    qdd_ = sd::aba(model_, data_, q, qd, tau);
    if (with_actuated_) {
      tau_actuated_ = sd::inverse_dynamics_actuated(actuated_model_, data_, q, qd, qdd);
      qdd_actuated_ = sd::forward_dynamics_actuated(actuated_model_, data_, q, qd, tau);
    }
    g_ = sd::gravity_torques(model_, data_, q);
    has_mass_matrix_ = with_mass_matrix;
    if (with_mass_matrix) {
      const spatial_dynamics::MatrixX<Quad>& M = sd::crba(model_, data_, q);
      M_ = Eigen::Map<const VectorQ>(M.data(), M.size());
      const spatial_dynamics::MatrixX<Quad>& C = sd::coriolis_matrix(model_, data_, q, qd);
      C_ = Eigen::Map<const VectorQ>(C.data(), C.size());
    }
    if (!contacts_.empty()) contacts(s, q, qd);
    observer_.reset();  // one update's p and u: its first after a reset
    observer_.update(q, qd, tau, Quad(1e-3));
    observer_result_.resize(2 * model_.nv);
    observer_result_ << observer_.momentum(), observer_.explained_momentum_rate();
    sd::forward_kinematics(model_, data_, q);
    poses_.resize(12 * (model_.nbodies() - 1));
    for (int i = 1; i < model_.nbodies(); ++i) {
      const spatial_dynamics::Matrix3<Quad> R = data_.X_base[i].rotation();
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) poses_[12 * (i - 1) + 3 * r + c] = R(r, c);
      for (int c = 0; c < 3; ++c) poses_[12 * (i - 1) + 9 + c] = data_.X_base[i].translation()[c];
    }
  }

  bool has(Algorithm a) const {
    if (a == Algorithm::ContactId) return !contacts_.empty();
    if (a == Algorithm::ContactFd) return !contacts_.empty() && has_mass_matrix_;
    return ((a != Algorithm::Crba && a != Algorithm::Coriolis) || has_mass_matrix_) && (!is_actuated(a) || with_actuated_);
  }

  const VectorQ& of(Algorithm a) const {
    switch (a) {
      case Algorithm::Rnea:
      case Algorithm::Regressor:
      case Algorithm::RneaBatch: return tau_;
      case Algorithm::Gravity: return g_;
      case Algorithm::Crba: return M_;
      case Algorithm::Fk: return poses_;
      case Algorithm::RneaActuated: return tau_actuated_;
      case Algorithm::AbaActuated: return qdd_actuated_;
      case Algorithm::Coriolis: return C_;
      case Algorithm::ObserverUpdate: return observer_result_;
      case Algorithm::ContactId: return contact_id_;
      case Algorithm::ContactFd: return contact_fd_;
      default: return qdd_;  // every forward dynamics
    }
  }

 private:
  /// The contact rows' references, dense: J_c and J̇_c q̇ from contact_jacobian in float128, then
  /// (τ ; λ) with λ = pinv(J_c,baseᵀ) ID_base and τ = ID − J_cᵀ λ, and (q̈ ; λ) = pinv([M −J_cᵀ; J_c 0])
  /// (τ − h ; −J̇_c q̇) (with the mass matrix only, budgeted like it).
  void contacts(const State& s, const VectorQ& q, const VectorQ& qd) {
    namespace sd = spatial_dynamics;
    namespace ref = spatial_dynamics::reference;
    using MatrixQ = sd::MatrixX<Quad>;
    const MatrixQ J = sd::contact_jacobian(model_, data_, contacts_, contact_data_, q, qd);
    const VectorQ Jdot_qd = contact_data_.acceleration;
    const Quad threshold(1e-25);
    const VectorQ lambda = ref::pseudo_inverse_solve<Quad>(MatrixQ(J.leftCols(6).transpose()), VectorQ(tau_.head(6)), threshold);
    contact_id_.resize(model_.nv + contacts_.rows);
    contact_id_ << tau_ - J.transpose() * lambda, lambda;
    if (!has_mass_matrix_) return;
    const int n = model_.nv, m = contacts_.rows;
    MatrixQ kkt = MatrixQ::Zero(n + m, n + m);
    kkt.topLeftCorner(n, n) = sd::crba(model_, data_, q);
    kkt.topRightCorner(n, m) = -J.transpose();
    kkt.bottomLeftCorner(m, n) = J;
    VectorQ rhs(n + m);
    rhs << sd::to_quad(s.tau) - sd::nonlinear_effects(model_, data_, q, qd), -Jdot_qd;
    contact_fd_ = ref::pseudo_inverse_solve<Quad>(kkt, rhs, threshold);
  }

  spatial_dynamics::Model<Quad> model_, actuated_model_;
  spatial_dynamics::Data<Quad> data_;
  spatial_dynamics::MomentumObserver<Quad> observer_;  // on actuated_model_
  VectorQ tau_, qdd_, g_, M_, C_, poses_, tau_actuated_, qdd_actuated_, observer_result_;
  bool has_mass_matrix_ = false;
  bool with_actuated_ = false;
  spatial_dynamics::ContactSet<Quad> contacts_;  // benchmark_contacts: empty for most models
  spatial_dynamics::ContactData<Quad> contact_data_;
  VectorQ contact_id_, contact_fd_;
};

}  // namespace bench
