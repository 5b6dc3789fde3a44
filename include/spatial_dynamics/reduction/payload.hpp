// Payloads: rigid bodies attached to model frames (a grasped box), added to the inertia of the
// frame's body (eq. 24, moved by eq. 26). Detaching is building again without it.
#pragma once

#include <map>
#include <stdexcept>
#include <string>

#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/model/physical_inertia.hpp"
#include "spatial_dynamics/reduction/reduce_model.hpp"

namespace spatial_dynamics {

struct Payload {
  double mass = 0;
  Eigen::Vector3d center_of_mass = Eigen::Vector3d::Zero();       // in the frame
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();              // about the centre of mass, frame axes
};

/// The spatial inertia of a payload in its frame's coordinates (eq. 25); throws SceneError naming
/// the frame when the payload is not a physical rigid body.
inline RigidInertia<double> payload_inertia(const std::string& frame, const Payload& payload) {
  const std::string problem = inertia_problem(payload.mass, payload.center_of_mass, payload.inertia);
  if (!problem.empty()) throw SceneError("payload on frame '" + frame + "': " + problem);
  return RigidInertia<double>::FromMassCenterInertia(payload.mass, payload.center_of_mass, payload.inertia);
}

/// The model with every payload added to the body carrying its frame. Throws SceneError naming the
/// frame for an unknown frame, an unphysical payload, or a body inertia that would overflow.
inline Model<double> with_payloads(const Model<double>& model, const std::map<std::string, Payload>& payloads) {
  Model<double> loaded = model;
  for (const auto& [frame_name, payload] : payloads) {
    if (!model.hasFrame(frame_name)) throw SceneError("payload: unknown frame '" + frame_name + "'");
    const Frame<double>& frame = model.frames[model.frameIndex(frame_name)];
    loaded.inertia[frame.body] += frame.X_frame_body.applyInverse(payload_inertia(frame_name, payload));  // I_B += Xᵀ I_F X
    if (!loaded.inertia[frame.body].allFinite())  // finite inputs, but an overflow (m c² with a huge c)
      throw SceneError("payload on frame '" + frame_name + "': the inertia of link '" + model.body_names[frame.body] +
                       "' with it is not finite (the mass or the centre of mass is too large)");
  }
  return loaded;
}

}  // namespace spatial_dynamics
