// One scene's external-torque estimate (doc/external_torques.md): the momentum observer on the
// scene's model, fed joint by joint from joint_states, with its gains, collision thresholds and
// wrench frames checked against that model, restarts on a gap or a stamp going backwards, the
// tare, and the collision state. ROS-free: it takes plain vectors, so it is tested without a
// master; the node publishes what it returns (external_torque_monitor.hpp).
#pragma once

#include <Eigen/Core>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "spatial_dynamics/estimation/external_wrench.hpp"
#include "spatial_dynamics/estimation/momentum_observer.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/ros/external_torque_settings.hpp"

namespace spatial_dynamics {

class ExternalTorqueEstimator {
 public:
  /// The observer of `model` (a scene's; its coordinates are its joints). `leaf_links`: the robot's
  /// URDF leaf links, the default frames (those the model has). `locked_joints`: joints of the robot
  /// the scene locks, whose effort is ignored. `tare`: a tare to carry over, by joint name. Throws
  /// std::invalid_argument naming the parameter when a gain or threshold is not positive and
  /// finite, or names a joint or frame the model does not have.
  ExternalTorqueEstimator(std::shared_ptr<const Model<double>> model, const ExternalTorqueSettings& settings,
                          const std::vector<std::string>& leaf_links, std::vector<std::string> locked_joints,
                          const std::map<std::string, double>& tare = {});

  /// What one sample gives.
  struct Estimate {
    bool restarted = false;           // the observer started again here (r̂ = 0)
    std::string restart_reason;       // why: "first sample", "a gap of 0.25 s", "the stamp went back ..."
    const Eigen::VectorXd* torques = nullptr;  // r̂ by coordinate
    std::vector<ExternalWrench<double>> wrenches;  // at each frame()
    bool collision_changed = false;   // in_collision differs from the previous sample's
    bool in_collision = false;
    std::vector<int> over_threshold;  // coordinates with |r̂| over their threshold
    int best_frame = -1;              // the frame whose wrench explains r̂ best (smallest residual)
  };

  /// The sample at `stamp` (s) with the scene's q, q̇ and measured effort (coordinate order). A
  /// gap over max_gap or a stamp before the previous one restarts the observer. Throws
  /// std::invalid_argument, and the sample is skipped, for a non-finite value (naming the joint)
  /// or the previous sample's stamp again.
  const Estimate& update(double stamp, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                         const Eigen::VectorXd& effort);

  /// The current r̂ becomes the zero (MomentumObserver::tare); false before the first estimate.
  bool tare();
  /// The tare by joint name (to carry over to a rebuilt model).
  std::map<std::string, double> tareByJoint() const;

  const Model<double>& model() const { return *model_; }
  const std::vector<std::string>& jointNames() const { return joint_names_; }
  const std::vector<std::string>& frames() const { return frame_names_; }
  const std::vector<std::string>& lockedJoints() const { return locked_joints_; }
  long restarts() const { return restarts_; }
  /// The largest |r̂| since the last call, and its joint.
  std::pair<double, std::string> takeLargest();

 private:
  std::shared_ptr<const Model<double>> model_;
  std::vector<std::string> joint_names_, frame_names_, locked_joints_;
  std::vector<int> frames_;
  Eigen::VectorXd thresholds_;  // +inf where a joint has none
  double max_gap_;
  MomentumObserver<double> observer_;
  Data<double> data_;  // the wrench fits'
  Estimate estimate_;
  double last_stamp_ = 0.0;
  bool has_stamp_ = false;
  long restarts_ = 0;
  double largest_ = 0.0;
  int largest_joint_ = -1;
};

}  // namespace spatial_dynamics
