// A path through configuration space for the float128 tests' central differences
// (test_contact_dynamics.cpp, test_coriolis.cpp).
#pragma once

#include <Eigen/Geometry>

#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/reference/high_precision.hpp"
#include "spatial_dynamics/reference/spatial_matrices.hpp"

namespace sd_test {

/// q ⊕ t q̇, the motion at constant q̇ (q̈ = 0): t q̇ added to every coordinate, a free joint moved by
/// exp(t (ω; v)) with (ω; v) in its body axes — a screw, so that the path is right to second order
/// and beyond (series to θ⁴: for |t ω| ≤ 1e-6).
inline spatial_dynamics::reference::VecX<spatial_dynamics::Quad> advance(
    const spatial_dynamics::Model<spatial_dynamics::Quad>& model, const spatial_dynamics::reference::VecX<spatial_dynamics::Quad>& q,
    const spatial_dynamics::reference::VecX<spatial_dynamics::Quad>& qd, const spatial_dynamics::Quad& t) {
  namespace sd = spatial_dynamics;
  using Quad = sd::Quad;
  using Vec3Q = sd::reference::Vec3<Quad>;
  using Mat3Q = sd::reference::Mat3<Quad>;
  sd::reference::VecX<Quad> out = q;
  for (int i = 1; i < model.nbodies(); ++i) {
    const sd::Joint<Quad>& j = model.joints[i];
    if (j.coupled) continue;
    if (j.type != sd::JointType::Free) {
      for (int k = 0; k < j.nv; ++k) out[j.idx_q + k] += t * qd[j.idx_v + k];
      continue;
    }
    const Vec3Q w = t * qd.segment<3>(j.idx_v), v = t * qd.segment<3>(j.idx_v + 3);
    const Quad th2 = w.squaredNorm();
    const Mat3Q W = sd::reference::skew3(w);
    const Mat3Q V = Mat3Q::Identity() + (Quad(0.5) - th2 / 24 + th2 * th2 / 720) * W +
                    (Quad(1) / 6 - th2 / 120 + th2 * th2 / 5040) * W * W;  // the left Jacobian of SO(3)
    const Eigen::Quaternion<Quad> q0(q[j.idx_q + 6], q[j.idx_q + 3], q[j.idx_q + 4], q[j.idx_q + 5]);
    const Vec3Q xyz = (Quad(0.5) - th2 / 48 + th2 * th2 / 3840) * w;
    const Eigen::Quaternion<Quad> dq(Quad(1) - th2 / 8 + th2 * th2 / 384, xyz[0], xyz[1], xyz[2]);
    const Eigen::Quaternion<Quad> q1 = q0 * dq;
    out.segment<3>(j.idx_q) = q.segment<3>(j.idx_q) + q0.toRotationMatrix() * (V * v);
    out[j.idx_q + 3] = q1.x();
    out[j.idx_q + 4] = q1.y();
    out[j.idx_q + 5] = q1.z();
    out[j.idx_q + 6] = q1.w();
  }
  return out;
}

}  // namespace sd_test
