// What the benchmark measures: the algorithms, the random states they run on, and the interface
// every library's adapter implements. All results are handed back in spatial_dynamics'
// conventions (joint order by name, velocity coordinates of the free joint as (ω; v) in the root
// link's frame) so that one reference serves every library.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace bench {

// RneaActuated, AbaActuated: inverse_dynamics_actuated and forward_dynamics_actuated with the
// actuator terms of benchmark_actuators.hpp (ours only).
// Coriolis: coriolis_matrix; ObserverUpdate: one MomentumObserver::update (with the actuator terms),
// its result p = M q̇ and u = τ_m − τ_a + Cᵀ q̇ − g (ours only).
// Regressor: joint_torque_regressor, its result Y π against the reference's τ (ours only).
// ContactId, ContactFd: inverse_dynamics_with_contacts ((τ ; λ)) and forward_dynamics_with_contacts
// ((q̈ ; λ)) on the models with benchmark_contacts (ours only).
enum class Algorithm { Rnea, RneaBatch, Aba, AbaRefined, Crba, CrbaCholesky, Gravity, Fk, RneaActuated, AbaActuated,
                       Coriolis, ObserverUpdate, Regressor, ContactId, ContactFd };

inline const std::vector<Algorithm>& all_algorithms() {
  static const std::vector<Algorithm> all = {Algorithm::Rnea,         Algorithm::RneaBatch, Algorithm::Aba, Algorithm::AbaRefined,
                                             Algorithm::Crba,         Algorithm::CrbaCholesky,
                                             Algorithm::Gravity,      Algorithm::Fk,        Algorithm::RneaActuated,
                                             Algorithm::AbaActuated,  Algorithm::Coriolis,  Algorithm::ObserverUpdate,
                                             Algorithm::Regressor,    Algorithm::ContactId, Algorithm::ContactFd};
  return all;
}

/// The CSV names (lower case; scripts and plots read them by these names).
inline const char* name(Algorithm a) {
  switch (a) {
    case Algorithm::Rnea: return "rnea";
    case Algorithm::RneaBatch: return "rnea_batch";
    case Algorithm::Aba: return "aba";
    case Algorithm::AbaRefined: return "aba_refined";
    case Algorithm::Crba: return "crba";
    case Algorithm::CrbaCholesky: return "crba_cholesky";
    case Algorithm::Gravity: return "gravity";
    case Algorithm::Fk: return "fk";
    case Algorithm::RneaActuated: return "rnea_actuated";
    case Algorithm::AbaActuated: return "aba_actuated";
    case Algorithm::Coriolis: return "coriolis_matrix";
    case Algorithm::ObserverUpdate: return "observer_update";
    case Algorithm::Regressor: return "joint_torque_regressor";
    case Algorithm::ContactId: return "inverse_dynamics_with_contacts";
    case Algorithm::ContactFd: return "forward_dynamics_with_contacts";
  }
  return "?";
}

/// The rows with actuator terms (benchmark_actuators.hpp), run on the shared robots only.
inline bool is_actuated(Algorithm a) { return a == Algorithm::RneaActuated || a == Algorithm::AbaActuated; }

/// Forward dynamics algorithms take τ and return q̈; the others are checked against their own
/// reference (τ, M, g or body poses).
inline bool is_forward_dynamics(Algorithm a) {
  return a == Algorithm::Aba || a == Algorithm::AbaRefined || a == Algorithm::CrbaCholesky || a == Algorithm::AbaActuated;
}

/// One random state in spatial_dynamics' coordinates: q ∈ U(−π, π) (a unit quaternion for a free
/// joint, position in U(−1, 1)), q̇, q̈ ∈ U(−1, 1), and τ = RNEA(q, q̇, q̈) in double, which every
/// forward dynamics is fed.
struct State {
  Eigen::VectorXd q, qd, qdd, tau;
};

/// A library's view of one model. Constructed per model; `prepare` converts the state pool into
/// the library's own coordinates outside the timed region; `run` is the timed call; `result`
/// returns the last result in spatial_dynamics' conventions (τ or q̈ as nv-vectors, M as an nv×nv
/// matrix flattened column-major, FK as 12 numbers per moving body: R row-major, then p).
class Adapter {
 public:
  virtual ~Adapter() = default;
  virtual std::string library() const = 0;
  virtual std::string scalar() const { return "double"; }
  virtual bool supports(Algorithm a) const = 0;
  virtual std::string method(Algorithm a) const = 0;  // what the library calls, for the table
  virtual void prepare(const std::vector<State>& states) = 0;
  virtual void run(Algorithm a, int state) = 0;
  /// States one run() evaluates (a batched algorithm: the pool's states from `state` on, cyclically);
  /// its times are reported per state. result() is then that of state `state`.
  virtual int states_per_call(Algorithm) const { return 1; }
  virtual Eigen::VectorXd result(Algorithm a) = 0;
  /// result() copied into `out`, the form the benchmark reads: Eigen's dynamic storage is
  /// allocated and freed on the adapter's side, whose alignment settings may differ
  /// (native_adapter.hpp).
  virtual void result_into(Algorithm a, std::vector<double>& out) {
    const Eigen::VectorXd x = result(a);
    out.assign(x.data(), x.data() + x.size());
  }
};

}  // namespace bench
