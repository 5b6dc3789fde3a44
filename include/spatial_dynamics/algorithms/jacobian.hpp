// Frame Jacobian J(q) (6 × nv): the spatial velocity of a frame is J q̇ = Σ_j ^FX_j S_j q̇_j
// over the joints j between the frame's body and the base (v_i = Σ X S q̇ unrolled from
// v_i = ^iX_λ v_λ + S_i q̇_i); columns of other joints are zero.
#pragma once

#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/model/joints/body_joint.hpp"
#include "spatial_dynamics/algorithms/kinematics.hpp"
#include "spatial_dynamics/compiled/compiled_functions.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/simd_backend.hpp"

namespace spatial_dynamics {

enum class ReferenceFrame {
  Local,        // frame coordinates, about the frame origin
  RootAligned,  // axes of the base (root) frame, about the frame origin
};

/// Jacobian of model frame `frame` at q, in data.J.
template <class S>
const Matrix6X<S>& frame_jacobian(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q, int frame,
                                  ReferenceFrame reference) {
  forward_kinematics<S>(model, data, q);
  data.J.setZero();
  PluckerTransform<S> X_F0 = data.X_frame_base[frame];
  if (reference == ReferenceFrame::RootAligned) X_F0 = PluckerTransform<S>(X_F0.E.transpose(), Vector3<S>::Zero()) * X_F0;
  for (int j = model.frames[frame].body; j > 0; j = model.parent[j]) {
    const PluckerTransform<S> X_Fj = X_F0 * data.X_base[j].inverse();        // ^FX_j = ^FX_0 (^jX_0)^-1
    const Joint<S>& joint = model.joints[j];
    const S scale = coupling_multiplier(joint);  // a coupled joint moves with its master's coordinate
    for (int k = 0; k < joint.nv; ++k)
      data.J.col(joint.idx_v + k) += scale * X_Fj.apply(body_subspace_column(model, data, j, k)).toVector();
  }
  detail::check_finite_result(model, "frame Jacobian: the column", data.J);
  return data.J;
}

}  // namespace spatial_dynamics
