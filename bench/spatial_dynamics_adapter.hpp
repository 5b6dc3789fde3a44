// spatial_dynamics itself, in float or double: the model is cast from the double model and every
// input is converted (rounded, for float) outside the timed region.
#pragma once

#include <Eigen/Cholesky>

#include "benchmark_actuators.hpp"
#include "benchmark_contacts.hpp"
#include "benchmark_types.hpp"
#include "spatial_dynamics/algorithms.hpp"
#include "spatial_dynamics/algorithms/aba_refined.hpp"
#include "spatial_dynamics/algorithms/rnea_batch.hpp"
#include "spatial_dynamics/estimation/momentum_observer.hpp"
#include "spatial_dynamics/reference/high_precision.hpp"

namespace bench {

template <class S>
class SpatialDynamicsAdapter : public Adapter {
 public:
  explicit SpatialDynamicsAdapter(const spatial_dynamics::Model<double>& model)
      : model_(model.cast<S>()), actuated_model_(with_benchmark_actuators(model).cast<S>()), data_(model_), refinement_(model_), refinement_fine_(model_), llt_(model_.nv), rhs_(model_.nv), batch_(model_),
        batch_tau_(model_.nv, kBatchStates),
        observer_(actuated_model_, spatial_dynamics::VectorX<S>::Constant(model_.nv, S(50))),
        observer_result_(2 * model_.nv), parameters_(model_.inertial_parameters()), contacts_(benchmark_contacts(model_)),
        contact_data_(model_, contacts_), contact_result_(model_.nv + contacts_.rows) {}

  std::string library() const override { return "spatial_dynamics"; }
  std::string scalar() const override { return std::is_same<S, float>::value ? "float" : "double"; }
  bool supports(Algorithm a) const override {
    return (a != Algorithm::ContactId && a != Algorithm::ContactFd) || !contacts_.empty();
  }
  std::string method(Algorithm a) const override {
    switch (a) {
      case Algorithm::Rnea: return "rnea";
      case Algorithm::RneaBatch:
        return "rnea_batch (" + std::to_string(kBatchStates) + " states per call, " +
               std::to_string(spatial_dynamics::kDefaultBatchLanes<S>) + " lanes; time per state)";
      case Algorithm::Aba: return "aba";
      case Algorithm::AbaRefined:
        return std::string("aba_refined (") +
               (std::is_same<spatial_dynamics::DefaultResidualScalar, spatial_dynamics::DoubleDouble>::value
                    ? "double-double residual, sin and cos in long double"
                    : "long double residual") +
               ", float128 where that cannot resolve the result)";
      case Algorithm::Crba: return "crba";
      case Algorithm::CrbaCholesky: return "crba + nonlinear_effects + Eigen LLT";
      case Algorithm::Gravity: return "gravity_torques";
      case Algorithm::Fk: return "forward_kinematics";
      case Algorithm::RneaActuated: return "inverse_dynamics_actuated (armature, damping, friction)";
      case Algorithm::AbaActuated: return "forward_dynamics_actuated (armature, damping, friction; ABA)";
      case Algorithm::Coriolis: return "coriolis_matrix";
      case Algorithm::ObserverUpdate: return "MomentumObserver::update (armature, damping, friction; K = 50/s, 1 kHz)";
      case Algorithm::Regressor: return "joint_torque_regressor (error of Y π)";
      case Algorithm::ContactId: return "inverse_dynamics_with_contacts (error of (τ ; λ))";
      case Algorithm::ContactFd: return "forward_dynamics_with_contacts (error of (q̈ ; λ))";
    }
    return "";
  }

  void prepare(const std::vector<State>& states) override {
    for (const State& s : states) {
      q_.push_back(s.q.cast<S>());
      qd_.push_back(s.qd.cast<S>());
      qdd_.push_back(s.qdd.cast<S>());
      tau_.push_back(s.tau.cast<S>());
    }
    // The pool as columns, its first kBatchStates − 1 states repeated at the end, so that the
    // kBatchStates states from any k on are one block of columns.
    const int n = static_cast<int>(states.size());
    batch_q_.resize(model_.nq, n + kBatchStates - 1);
    batch_qd_.resize(model_.nv, n + kBatchStates - 1);
    batch_qdd_.resize(model_.nv, n + kBatchStates - 1);
    for (int c = 0; c < n + kBatchStates - 1; ++c) {
      batch_q_.col(c) = q_[c % n];
      batch_qd_.col(c) = qd_[c % n];
      batch_qdd_.col(c) = qdd_[c % n];
    }
  }

  int states_per_call(Algorithm a) const override { return a == Algorithm::RneaBatch ? kBatchStates : 1; }

  void run(Algorithm a, int k) override {
    namespace sd = spatial_dynamics;
    switch (a) {
      case Algorithm::Rnea: sd::rnea(model_, data_, q_[k], qd_[k], qdd_[k]); return;
      case Algorithm::RneaBatch:  // states k … k + kBatchStates − 1 of the pool
        sd::rnea_batch(model_, batch_, batch_q_.middleCols(k, kBatchStates), batch_qd_.middleCols(k, kBatchStates),
                       batch_qdd_.middleCols(k, kBatchStates), batch_tau_);
        return;
      case Algorithm::Aba: sd::aba(model_, data_, q_[k], qd_[k], tau_[k]); return;
      case Algorithm::AbaRefined:
        sd::aba_refined(model_, data_, refinement_, refinement_fine_, q_[k], qd_[k], tau_[k]);
        return;
      case Algorithm::Crba: sd::crba(model_, data_, q_[k]); return;
      case Algorithm::CrbaCholesky:  // q̈ = M⁻¹ (τ − h), M = LLᵀ
        llt_.compute(sd::crba(model_, data_, q_[k]));
        rhs_ = tau_[k] - sd::nonlinear_effects(model_, data_, q_[k], qd_[k]);
        llt_.solveInPlace(rhs_);
        return;
      case Algorithm::Gravity: sd::gravity_torques(model_, data_, q_[k]); return;
      case Algorithm::Fk: sd::forward_kinematics(model_, data_, q_[k]); return;
      case Algorithm::RneaActuated: sd::inverse_dynamics_actuated(actuated_model_, data_, q_[k], qd_[k], qdd_[k]); return;
      case Algorithm::AbaActuated: sd::forward_dynamics_actuated(actuated_model_, data_, q_[k], qd_[k], tau_[k]); return;
      case Algorithm::Coriolis: sd::coriolis_matrix(model_, data_, q_[k], qd_[k]); return;
      case Algorithm::ObserverUpdate: observer_.update(q_[k], qd_[k], tau_[k], S(1e-3)); return;
      case Algorithm::Regressor: sd::joint_torque_regressor(model_, data_, q_[k], qd_[k], qdd_[k]); return;
      case Algorithm::ContactId:
        sd::inverse_dynamics_with_contacts(model_, data_, contacts_, contact_data_, q_[k], qd_[k], qdd_[k]);
        return;
      case Algorithm::ContactFd:
        sd::forward_dynamics_with_contacts(model_, data_, contacts_, contact_data_, q_[k], qd_[k], tau_[k]);
        return;
    }
  }

  Eigen::VectorXd result(Algorithm a) override {
    switch (a) {
      case Algorithm::Rnea:
      case Algorithm::RneaActuated:
      case Algorithm::Gravity: return data_.tau.template cast<double>();
      case Algorithm::RneaBatch: return batch_tau_.col(0).template cast<double>();
      case Algorithm::Aba:
      case Algorithm::AbaActuated:
      case Algorithm::AbaRefined: return data_.qdd.template cast<double>();
      case Algorithm::CrbaCholesky: return rhs_.template cast<double>();
      case Algorithm::Crba: return Eigen::Map<const spatial_dynamics::VectorX<S>>(data_.M.data(), data_.M.size()).template cast<double>();
      case Algorithm::Coriolis: return Eigen::Map<const spatial_dynamics::VectorX<S>>(data_.C.data(), data_.C.size()).template cast<double>();
      case Algorithm::ObserverUpdate:
        observer_result_ << observer_.momentum(), observer_.explained_momentum_rate();
        return observer_result_.template cast<double>();
      case Algorithm::Regressor: return (data_.Y * parameters_).template cast<double>();
      case Algorithm::ContactId:
        contact_result_ << contact_data_.tau, contact_data_.lambda;
        return contact_result_.template cast<double>();
      case Algorithm::ContactFd:
        contact_result_ << contact_data_.qdd, contact_data_.lambda;
        return contact_result_.template cast<double>();
      case Algorithm::Fk: {
        Eigen::VectorXd poses(12 * (model_.nbodies() - 1));
        for (int i = 1; i < model_.nbodies(); ++i) {
          const spatial_dynamics::Matrix3<S> R = data_.X_base[i].rotation();
          for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) poses[12 * (i - 1) + 3 * r + c] = static_cast<double>(R(r, c));
          for (int c = 0; c < 3; ++c) poses[12 * (i - 1) + 9 + c] = static_cast<double>(data_.X_base[i].translation()[c]);
        }
        return poses;
      }
    }
    return {};
  }

 private:
  spatial_dynamics::Model<S> model_;
  spatial_dynamics::Model<S> actuated_model_;  // the same with the actuator terms (Data depends on the structure only)
  spatial_dynamics::Data<S> data_;
  spatial_dynamics::RefinementWorkspace<S> refinement_;
  spatial_dynamics::RefinementWorkspace<S, spatial_dynamics::Quad> refinement_fine_;
  Eigen::LLT<spatial_dynamics::MatrixX<S>> llt_;
  spatial_dynamics::VectorX<S> rhs_;
  std::vector<spatial_dynamics::VectorX<S>> q_, qd_, qdd_, tau_;
  static constexpr int kBatchStates = 64;  // a trajectory's worth per rnea_batch call
  spatial_dynamics::BatchData<S> batch_;
  spatial_dynamics::MatrixX<S> batch_q_, batch_qd_, batch_qdd_, batch_tau_;
  spatial_dynamics::MomentumObserver<S> observer_;  // on actuated_model_
  spatial_dynamics::VectorX<S> observer_result_;
  spatial_dynamics::VectorX<S> parameters_;  // π, for the regressor's Y π
  spatial_dynamics::ContactSet<S> contacts_;  // benchmark_contacts: empty for most models
  spatial_dynamics::ContactData<S> contact_data_;
  spatial_dynamics::VectorX<S> contact_result_;  // (τ ; λ) or (q̈ ; λ)
};

}  // namespace bench
