// The wrench at a frame that best explains a joint-force residual r̂, an estimate of τ_ext
// (momentum_observer.hpp): a wrench F applied at the frame acts on the joints as τ_ext = Jᵀ F
// (virtual power, with J the frame's Jacobian), so F is the least-squares solution of Jᵀ F = r̂
// over the joints that move the frame (the other columns of J are zero). It is solved through the
// 6 × 6 normal matrix J Jᵀ = V Λ Vᵀ: F = Σ_k v_k (v_kᵀ J r̂) / λ_k over the directions with
// σ_k = √λ_k ≥ 1e-6 σ_max, the minimum-norm solution. Fewer than six such directions (a frame
// moved by fewer than six joints, or a singular pose) are reported as the rank, not inverted. The
// residual over every coordinate compares frames: the one with the smallest explains r̂ best.
#pragma once

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>
#include <string>

#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/jacobian.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"

namespace spatial_dynamics {

template <class S>
struct ExternalWrench {
  ForceVector<S> wrench = ForceVector<S>::Zero();  // (moment ; force) in the frame's axes, about its origin
  int rank = 0;         // the directions of F that r̂ determines (6: all of them)
  S condition{0};       // σ_max / σ_min over those directions
  S residual{0};        // ‖Jᵀ F − r̂‖ over every coordinate: what no wrench at this frame explains (the
                        // coordinates that do not move the frame count whole)
  bool determined() const { return rank == 6; }
};

/// The wrench at model frame `frame` (index into model.frames) that best explains the joint
/// forces r (nv, e.g. the momentum observer's r̂) at configuration q. Uses data.J (frame_jacobian).
template <class S>
ExternalWrench<S> external_wrench(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q, int frame,
                                  const ConstVectorRef<S>& r) {
  if (frame < 0 || frame >= static_cast<int>(model.frames.size()))
    throw std::out_of_range("external wrench: frame index " + std::to_string(frame) + " is not one of the model's " +
                            std::to_string(model.frames.size()) + " frames");
  detail::check_length("joint forces", r.size(), model.nv);
  const Matrix6X<S>& J = frame_jacobian(model, data, q, frame, ReferenceFrame::Local);
  const Matrix6<S> normal = J.lazyProduct(J.transpose());  // J Jᵀ
  Vector6<S> projected = Vector6<S>::Zero();                // J r̂
  for (int k = 0; k < model.nv; ++k) projected += J.col(k) * r[k];
  const Eigen::SelfAdjointEigenSolver<Matrix6<S>> eigen(normal);
  const Vector6<S>& lambda = eigen.eigenvalues();  // ascending
  ExternalWrench<S> out;
  using std::sqrt;
  const S lambda_max = lambda[5], lambda_min_kept = lambda_max * S(1e-12);
  Vector6<S> F = Vector6<S>::Zero();
  for (int k = 5; k >= 0 && lambda_max > S(0) && lambda[k] >= lambda_min_kept; --k) {
    const Vector6<S> v = eigen.eigenvectors().col(k);
    F += v * (v.dot(projected) / lambda[k]);
    out.condition = sqrt(lambda_max / lambda[k]);
    ++out.rank;
  }
  out.wrench = ForceVector<S>(F);
  S squared(0);
  for (int k = 0; k < model.nv; ++k) {
    const S e = J.col(k).dot(F) - r[k];
    squared += e * e;
  }
  out.residual = sqrt(squared);
  if (!F.allFinite() || !(out.residual - out.residual == S(0)))
    throw std::domain_error("external wrench at frame '" + model.frames[frame].name +
                            "' is not finite: the joint forces are so large that the fit overflows");
  return out;
}

}  // namespace spatial_dynamics
