// URDF → Model (the URDF layer: doc/library.md). Fixed joints are merged into composite inertias (eq. 24)
// while their child links stay addressable as frames; an optional free root joint makes the
// model floating-base. Every rejection is a ModelError whose message names the link or joint.
#pragma once

#include <stdexcept>
#include <string>

#include <Eigen/Core>

#include "spatial_dynamics/model/model.hpp"

namespace urdf {
class ModelInterface;
}

namespace spatial_dynamics {

class ModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ModelBuildOptions {
  /// Attach the URDF root link to the base through a 6-DoF free joint:
  /// q = (x y z qx qy qz qw) first in q, q̇ = (ω; v) of the root link in its own frame first in q̇.
  bool floating_base = false;
  std::string root_joint_name = "root_joint";
  Eigen::Vector3d gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
};

/// Builds from URDF text. Throws ModelError on malformed XML or a rejected model.
Model<double> build_model_from_urdf_string(const std::string& urdf_xml, const ModelBuildOptions& options = {});

/// Builds from a URDF file. Throws ModelError when the file cannot be read or is rejected.
Model<double> build_model_from_urdf_file(const std::string& path, const ModelBuildOptions& options = {});

/// Builds from an already parsed urdfdom model.
Model<double> build_model(const urdf::ModelInterface& urdf_model, const ModelBuildOptions& options = {});

}  // namespace spatial_dynamics
