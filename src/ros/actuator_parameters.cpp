#include "spatial_dynamics/ros/actuator_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <vector>

namespace spatial_dynamics {
namespace {

const char* const kKeys = "armature, rotor_inertia, gear_ratio, damping, friction, friction_velocity";

/// A number of an ~actuators entry: finite and ≥ 0 (> 0 for friction_velocity).
double entry_value(XmlRpc::XmlRpcValue& value, const std::string& where, const std::string& key) {
  double x;
  if (value.getType() == XmlRpc::XmlRpcValue::TypeDouble) x = static_cast<double>(value);
  else if (value.getType() == XmlRpc::XmlRpcValue::TypeInt) x = static_cast<int>(value);
  else throw std::runtime_error("parameter " + where + " must be a number");
  const bool speed = key == "friction_velocity";
  if (!std::isfinite(x) || x < 0 || (speed && !(x > 0)))
    throw std::runtime_error("parameter " + where + " is " + std::to_string(x) + ": it must be finite and " +
                             (speed ? "above zero" : "not negative"));
  return x;
}

}  // namespace

const char* to_string(ActuatorModel model) {
  switch (model) {
    case ActuatorModel::RigidBody: return "rigid_body";
    case ActuatorModel::Urdf: return "urdf";
    case ActuatorModel::Parameters: return "parameters";
  }
  return "";
}

ActuatorModel parse_actuator_model(const std::string& value, const std::string& parameter) {
  for (const ActuatorModel model : {ActuatorModel::RigidBody, ActuatorModel::Urdf, ActuatorModel::Parameters})
    if (value == to_string(model)) return model;
  throw std::runtime_error("parameter " + parameter + " must be 'rigid_body', 'urdf' or 'parameters', not '" + value +
                           "'");
}

void apply_actuator_settings(const ActuatorSettings& settings, bool coupled_mimic_joints, Model<double>& model) {
  if (settings.model != ActuatorModel::Urdf) model.reset_actuator_terms();  // the URDF's damping and friction go
  if (settings.model != ActuatorModel::RigidBody && settings.actuators.valid()) {
    XmlRpc::XmlRpcValue actuators = settings.actuators;
    if (actuators.getType() != XmlRpc::XmlRpcValue::TypeStruct)
      throw std::runtime_error("parameter " + settings.actuators_parameter + " must be a dictionary of joints");
    for (auto& [joint, entry] : actuators) {
      const std::string where = settings.actuators_parameter + "/" + joint;
      if (!model.hasJoint(joint)) throw std::runtime_error("parameter " + where + ": the model has no joint '" + joint + "'");
      const int body = model.jointBody(joint);
      const Joint<double>& j = model.joints[body];
      if (model.floating_base && body == 1)
        throw std::runtime_error("parameter " + where + ": '" + joint + "' is the floating base's root joint, which has no actuator");
      if (coupled_mimic_joints && j.mimic.active())
        throw std::runtime_error("parameter " + where + ": joint '" + joint + "' mimics '" +
                                 model.joint_names[j.mimic.master_body] +
                                 "' and ~mimic_joints is 'coupled', so it has its master's actuator: set " +
                                 settings.actuators_parameter + "/" + model.joint_names[j.mimic.master_body]);
      if (entry.getType() != XmlRpc::XmlRpcValue::TypeStruct)
        throw std::runtime_error("parameter " + where + " must be a dictionary with some of " + kKeys);
      std::map<std::string, double> values;
      for (auto& [key, value] : entry) {
        static const std::set<std::string> known = {"armature", "rotor_inertia", "gear_ratio", "damping", "friction",
                                                    "friction_velocity"};
        if (!known.count(key))
          throw std::runtime_error("parameter " + where + "/" + key + ": unknown (expected " + kKeys + ")");
        values[key] = entry_value(value, where + "/" + key, key);
      }
      const bool rotor = values.count("rotor_inertia") || values.count("gear_ratio");
      if (rotor && values.count("armature"))
        throw std::runtime_error("parameter " + where + ": give armature, or rotor_inertia and gear_ratio, not both");
      if (rotor && !(values.count("rotor_inertia") && values.count("gear_ratio")))
        throw std::runtime_error("parameter " + where + "/" + (values.count("gear_ratio") ? "rotor_inertia" : "gear_ratio") +
                                 " is not set: armature = rotor_inertia · gear_ratio² needs both");
      if (rotor) values["armature"] = values["rotor_inertia"] * values["gear_ratio"] * values["gear_ratio"];
      const std::pair<const char*, std::vector<double>*> terms[] = {{"armature", &model.armature},
                                                                 {"damping", &model.damping},
                                                                 {"friction", &model.friction},
                                                                 {"friction_velocity", &model.friction_velocity}};
      for (const auto& [term, vector] : terms)  // each of the joint's coordinates
        if (values.count(term)) std::fill_n(vector->begin() + j.idx_v, j.nv, values[term]);
    }
  }
  model.finalize();
}

}  // namespace spatial_dynamics
