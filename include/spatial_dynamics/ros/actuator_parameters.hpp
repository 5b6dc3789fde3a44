// The node's actuator model (README, "Actuator dynamics"): which actuator terms every answer
// includes (~actuator_model) and the per-joint values that override the URDF's
// (~actuators/<joint>/armature, rotor_inertia and gear_ratio, damping, friction, friction_velocity).
#pragma once

#include <string>

#include <xmlrpcpp/XmlRpcValue.h>

#include "spatial_dynamics/model/model.hpp"

namespace spatial_dynamics {

/// rigid_body: no actuator terms (armature 0, the URDF's damping and friction ignored); urdf: the
/// URDF's <dynamics damping friction> and any ~actuators entries; parameters: ~actuators only.
enum class ActuatorModel { RigidBody, Urdf, Parameters };

const char* to_string(ActuatorModel model);

struct ActuatorSettings {
  ActuatorModel model = ActuatorModel::RigidBody;
  std::string actuators_parameter;  // the resolved name of ~actuators, for messages
  XmlRpc::XmlRpcValue actuators;    // ~actuators' value; invalid when it is not set
};

/// ~actuator_model's value; throws std::runtime_error naming `parameter` for any other.
ActuatorModel parse_actuator_model(const std::string& value, const std::string& parameter);

/// Sets the model's actuator terms as `settings` say (armature = rotor_inertia · gear_ratio² where
/// those are given). Throws std::runtime_error naming the parameter (~actuators/<joint>/<key>) for
/// an entry that is not a dictionary, a joint the model does not have or that follows a master
/// (coupled mimic joints take the master's terms), an unknown key, armature given twice, a
/// rotor_inertia without gear_ratio or the reverse, or a value that is not a finite number ≥ 0
/// (friction_velocity > 0).
void apply_actuator_settings(const ActuatorSettings& settings, bool coupled_mimic_joints, Model<double>& model);

}  // namespace spatial_dynamics
