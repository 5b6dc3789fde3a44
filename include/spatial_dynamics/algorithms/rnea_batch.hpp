// Inverse dynamics of many states of one model: τ_k = ID(q_k, q̇_k, q̈_k) for the columns k of a
// trajectory. The states go through the RNEA's passes of rnea.hpp (RBDA Table 5.1) L at a time,
// one per lane, on the lanes' form (joint_kernels_lanes.hpp, spatial/number/lanes.hpp): every operation
// acts on all L states at once, which the compiler turns into vector instructions, and the joint
// dispatch and the loads of the model's constants are shared by the L states. Columns are taken in
// blocks of L; a last, partial block fills its unused lanes with a copy of its last state and
// discards their results. Each lane computes what the one-state RNEA on Eigen's 3-vectors computes
// for its state, formula by formula (bit for bit where the compiler fuses no multiply-adds).
#pragma once

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/joint_kernels_lanes.hpp"
#include "spatial_dynamics/algorithms/rnea.hpp"
#include "spatial_dynamics/compiled/compiled_functions.hpp"
#include "spatial_dynamics/model/batch_data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/simd_backend.hpp"

namespace spatial_dynamics {

/// Read-only and writable views of a matrix argument (states as columns); the scalar is deduced
/// from the Model. Any matrix or block of columns with contiguous columns binds without a copy.
template <class S>
using ConstMatrixRef = typename detail::NonDeduced<Eigen::Ref<const MatrixX<S>>>::type;
template <class S>
using MatrixRef = typename detail::NonDeduced<Eigen::Ref<MatrixX<S>>>::type;

namespace detail {

/// "state k: " in front of an error's message.
inline std::string at_state(Eigen::Index k, const std::string& message) {
  return "state " + std::to_string(k) + ": " + message;
}

/// Copies the columns c0 .. c0 + count − 1 into the lanes (lane l ≥ count repeats the last one)
/// and checks the unit norm of free joints' quaternions as joint_up_transform does.
template <class S, int L>
void gather_lanes(const Model<S>& model, BatchData<S, L>& data, const ConstMatrixRef<S>& q, const ConstMatrixRef<S>& qd,
                  const ConstMatrixRef<S>& qdd, Eigen::Index c0, int count) {
  const S* q_col[L];
  const S* qd_col[L];
  const S* qdd_col[L];
  for (int l = 0; l < L; ++l) {
    const Eigen::Index c = c0 + std::min(l, count - 1);
    q_col[l] = &q.coeffRef(0, c);
    qd_col[l] = &qd.coeffRef(0, c);
    qdd_col[l] = &qdd.coeffRef(0, c);
  }
  gather_columns(q_col, model.nq, data.q.data());
  gather_columns(qd_col, model.nv, data.qd.data());
  gather_columns(qdd_col, model.nv, data.qdd.data());
  for (int i = 1; model.floating_base && i < model.nbodies(); ++i) {
    const Joint<S>& j = model.joints[i];
    if (j.type != JointType::Free) continue;
    for (int l = 0; l < count; ++l) {
      const Eigen::Quaternion<S> quat(data.q[j.idx_q + 6][l], data.q[j.idx_q + 3][l], data.q[j.idx_q + 4][l],
                                      data.q[j.idx_q + 5][l]);
      using std::abs;
      if (!(abs(quat.squaredNorm() - S(1)) <= S(1e-6)))
        throw std::invalid_argument(at_state(c0 + l, "joint '" + model.joint_names[i] + "': the quaternion (q[" +
                                                         std::to_string(j.idx_q + 3) + ".." +
                                                         std::to_string(j.idx_q + 6) + "]) is not of unit norm"));
    }
  }
}

/// Whether x[0 .. n) are finite in every lane: Σ 0·x_k is 0 in a lane unless one of its x_k is
/// infinite or NaN (0·∞ = NaN). One vector operation per coordinate.
template <class S, int L>
SD_LANE_INLINE bool lanes_all_finite(const Lanes<S, L>* x, int n) {
  Lanes<S, L> sum = Lanes<S, L>::Zero();
  for (int k = 0; k < n; ++k) sum += S(0) * x[k];
  for (int l = 0; l < L; ++l)
    if (!(sum[l] == S(0))) return false;
  return true;
}

/// A non-finite τ among columns c0 .. c0 + count − 1: std::domain_error naming the state and joint.
template <class S>
void check_finite_columns(const Model<S>& model, const MatrixRef<S>& tau, Eigen::Index c0, Eigen::Index count) {
  if (tau.middleCols(c0, count).allFinite()) return;
  for (Eigen::Index c = c0; c < c0 + count; ++c) {
    try {
      check_finite_result(model, "inverse dynamics: the joint force", tau.col(c));
    } catch (const std::domain_error& e) {
      throw std::domain_error(at_state(c, e.what()));
    }
  }
}

}  // namespace detail

/// τ(:, k) = ID(q(:, k), q̇(:, k), q̈(:, k)) for every column k: q is nq × N, q̇ and q̈ nv × N, τ
/// nv × N (sized by the caller; N may be 0). The scalar rnea's formulas for each state: the same
/// numbers where the compiler fuses no multiply-adds (the portable build), the same to rounding
/// otherwise and where rnea takes the packed form (vector3_form.hpp). Errors as rnea's, their
/// message starting with "state k: ". No allocation.
template <class S, int L>
void rnea_batch(const Model<S>& model, BatchData<S, L>& data, const ConstMatrixRef<S>& q, const ConstMatrixRef<S>& qd,
                const ConstMatrixRef<S>& qdd, MatrixRef<S> tau) {
  detail::check_length("q (rows)", q.rows(), model.nq);
  detail::check_length("velocity (rows)", qd.rows(), model.nv);
  detail::check_length("acceleration (rows)", qdd.rows(), model.nv);
  detail::check_length("tau (rows)", tau.rows(), model.nv);
  const Eigen::Index n = q.cols();
  for (const auto& [what, cols] : {std::pair<const char*, Eigen::Index>{"velocity", qd.cols()},
                                   {"acceleration", qdd.cols()}, {"tau", tau.cols()}})
    if (cols != n)
      throw std::invalid_argument(std::string(what) + " has " + std::to_string(cols) + " columns (states); q has " +
                                  std::to_string(n));
  if (static_cast<int>(data.rnea.size()) != model.nbodies() || static_cast<int>(data.q.size()) != model.nq)
    throw std::invalid_argument("the batch workspace was made for another model");

  if (model.has_coupled_joints || model.has_multi_dof_tree_joints) {
    // A coupled mimic joint reads and accumulates its master's coordinate (joint_kernels.hpp,
    // body_up_transform … store_joint_force), and the lane kernels are written for 1-DoF joints
    // and a free root: such models take the one-state RNEA per state.
    for (Eigen::Index c = 0; c < n; ++c) {
      try {
        tau.col(c) = rnea<S>(model, data.single, q.col(c), qd.col(c), qdd.col(c));
      } catch (const std::domain_error& e) {
        throw std::domain_error(detail::at_state(c, e.what()));
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(detail::at_state(c, e.what()));
      }
    }
    return;
  }
  for (Eigen::Index c0 = 0; c0 < n; c0 += L) {
    const int count = static_cast<int>(std::min<Eigen::Index>(L, n - c0));
    detail::gather_lanes(model, data, q, qd, qdd, c0, count);
    detail::rnea_passes<vec3::LanesForm<S, L>>(model, data, data.q.data(), data.qd.data(), data.qdd.data(),
                                               static_cast<const ForceVector<S>*>(nullptr), model.gravity,
                                               data.tau.data());
    for (int k = 0; k < model.nv; ++k)
      for (int l = 0; l < count; ++l) tau(k, c0 + l) = data.tau[k][l];
    if (!detail::lanes_all_finite(data.tau.data(), model.nv)) detail::check_finite_columns(model, tau, c0, count);
  }
}

}  // namespace spatial_dynamics
