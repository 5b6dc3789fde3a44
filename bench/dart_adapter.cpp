#include "dart_adapter.hpp"

#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/DegreeOfFreedom.hpp>
#include <dart/dynamics/FreeJoint.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/utils/urdf/DartLoader.hpp>

namespace bench {
namespace {

using dart::dynamics::SkeletonPtr;

class DartAdapter : public Adapter {
 public:
  DartAdapter(const spatial_dynamics::Model<double>& model, SkeletonPtr skeleton)
      : model_(model), skeleton_(std::move(skeleton)) {
    skeleton_->setGravity(model.gravity);
    // DartLoader makes URDF mimic joints MIMIC actuators (their motion prescribed by the master):
    // every joint is a plain force-driven coordinate here, as in the other libraries.
    for (std::size_t i = 0; i < skeleton_->getNumJoints(); ++i)
      skeleton_->getJoint(i)->setActuatorType(dart::dynamics::Joint::FORCE);
    for (std::size_t i = 0; i < skeleton_->getNumDofs(); ++i) {
      dart::dynamics::DegreeOfFreedom* dof = skeleton_->getDof(i);
      dof->setDampingCoefficient(0.0);
      dof->setSpringStiffness(0.0);
      dof->setCoulombFriction(0.0);
    }
    // Our velocity index → DART dof index, by joint name; the free root joint maps to DART's root.
    for (int i = 1; i < model.nbodies(); ++i) {
      const auto& j = model.joints[i];
      dart::dynamics::Joint* joint = j.type == spatial_dynamics::JointType::Free ? skeleton_->getRootJoint()
                                                                                    : skeleton_->getJoint(model.joint_names[i]);
      if (!joint) throw std::runtime_error("joint '" + model.joint_names[i] + "' not found in the DART skeleton");
      for (int k = 0; k < j.nv; ++k) ours_to_dart_.push_back(static_cast<int>(joint->getIndexInSkeleton(k)));
      dart::dynamics::BodyNode* body = skeleton_->getBodyNode(model.body_names[i]);
      if (!body) throw std::runtime_error("link '" + model.body_names[i] + "' not found in the DART skeleton");
      bodies_.push_back(body);
    }
  }

  std::string library() const override { return "dart"; }
  bool supports(Algorithm a) const override {
    return a == Algorithm::Rnea || a == Algorithm::Aba || a == Algorithm::Crba || a == Algorithm::Gravity ||
           a == Algorithm::Fk;
  }
  std::string method(Algorithm a) const override {
    switch (a) {
      case Algorithm::Rnea: return "Skeleton::computeInverseDynamics";
      case Algorithm::Aba: return "Skeleton::computeForwardDynamics";
      case Algorithm::Crba: return "Skeleton::getMassMatrix";
      case Algorithm::Gravity: return "Skeleton::getGravityForces";
      case Algorithm::Fk: return "BodyNode::getWorldTransform (every body)";
      default: return "";
    }
  }

  void prepare(const std::vector<State>& states) override {
    for (const State& s : states) {
      Eigen::VectorXd q(model_.nv);
      for (int i = 1; i < model_.nbodies(); ++i) {
        const auto& j = model_.joints[i];
        if (j.type == spatial_dynamics::JointType::Free) {
          // DART's FreeJoint positions: rotation vector (log map) then translation.
          Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
          T.linear() = Eigen::Quaterniond(s.q[j.idx_q + 6], s.q[j.idx_q + 3], s.q[j.idx_q + 4], s.q[j.idx_q + 5]).toRotationMatrix();
          T.translation() = s.q.segment<3>(j.idx_q);
          const Eigen::Vector6d p = dart::dynamics::FreeJoint::convertToPositions(T);
          for (int k = 0; k < 6; ++k) q[ours_to_dart_[j.idx_v + k]] = p[k];
        } else {
          q[ours_to_dart_[j.idx_v]] = s.q[j.idx_q];
        }
      }
      q_.push_back(q);
      qd_.push_back(permute(s.qd));  // FreeJoint velocities are (ω; v) in the root body frame, as ours
      qdd_.push_back(permute(s.qdd));
      tau_.push_back(permute(s.tau));
    }
  }

  void run(Algorithm a, int k) override {
    skeleton_->setPositions(q_[k]);
    switch (a) {
      case Algorithm::Rnea:
        skeleton_->setVelocities(qd_[k]);
        skeleton_->setAccelerations(qdd_[k]);
        skeleton_->computeInverseDynamics(false, false, false);
        return;
      case Algorithm::Aba:
        skeleton_->setVelocities(qd_[k]);
        skeleton_->setForces(tau_[k]);
        skeleton_->computeForwardDynamics();
        return;
      case Algorithm::Crba: skeleton_->getMassMatrix(); return;
      case Algorithm::Gravity: skeleton_->getGravityForces(); return;
      case Algorithm::Fk:
        for (dart::dynamics::BodyNode* b : bodies_) b->getWorldTransform();
        return;
      default: return;
    }
  }

  Eigen::VectorXd result(Algorithm a) override {
    const int nv = model_.nv;
    switch (a) {
      case Algorithm::Rnea: return unpermute(skeleton_->getForces());
      case Algorithm::Aba: return unpermute(skeleton_->getAccelerations());
      case Algorithm::Gravity: return unpermute(skeleton_->getGravityForces());
      case Algorithm::Crba: {
        const Eigen::MatrixXd& M = skeleton_->getMassMatrix();
        Eigen::VectorXd out(nv * nv);
        for (int c = 0; c < nv; ++c)
          for (int r = 0; r < nv; ++r) out[c * nv + r] = M(ours_to_dart_[r], ours_to_dart_[c]);
        return out;
      }
      case Algorithm::Fk: {
        Eigen::VectorXd poses(12 * bodies_.size());
        for (std::size_t i = 0; i < bodies_.size(); ++i) {
          const Eigen::Isometry3d& T = bodies_[i]->getWorldTransform();
          for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) poses[12 * i + 3 * r + c] = T.linear()(r, c);
          for (int c = 0; c < 3; ++c) poses[12 * i + 9 + c] = T.translation()[c];
        }
        return poses;
      }
      default: return {};
    }
  }

 private:
  Eigen::VectorXd permute(const Eigen::VectorXd& ours) const {
    Eigen::VectorXd d(ours.size());
    for (int i = 0; i < ours.size(); ++i) d[ours_to_dart_[i]] = ours[i];
    return d;
  }
  Eigen::VectorXd unpermute(const Eigen::VectorXd& d) const {
    Eigen::VectorXd ours(d.size());
    for (int i = 0; i < d.size(); ++i) ours[i] = d[ours_to_dart_[i]];
    return ours;
  }

  const spatial_dynamics::Model<double>& model_;
  SkeletonPtr skeleton_;
  std::vector<int> ours_to_dart_;
  std::vector<dart::dynamics::BodyNode*> bodies_;
  std::vector<Eigen::VectorXd> q_, qd_, qdd_, tau_;
};

}  // namespace

std::unique_ptr<Adapter> make_dart_adapter(const spatial_dynamics::Model<double>& model, const std::string& urdf_text,
                                           std::string& why) {
  dart::utils::DartLoader::Options options;
  options.mDefaultRootJointType =
      model.floating_base ? dart::utils::DartLoader::RootJointType::FLOATING : dart::utils::DartLoader::RootJointType::FIXED;
  // A link without <inertial> is massless in URDF; DART's default would give it 1 kg.
  options.mDefaultInertia = dart::dynamics::Inertia(0.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero());
  dart::utils::DartLoader loader(options);
  SkeletonPtr skeleton = loader.parseSkeletonString(urdf_text, dart::common::Uri("file:///benchmark.urdf"));
  if (!skeleton) {
    why = "DartLoader could not parse the URDF";
    return nullptr;
  }
  if (static_cast<int>(skeleton->getNumDofs()) != model.nv) {
    why = "DART skeleton has " + std::to_string(skeleton->getNumDofs()) + " DoFs, the model " + std::to_string(model.nv);
    return nullptr;
  }
  try {
    return std::make_unique<DartAdapter>(model, std::move(skeleton));
  } catch (const std::exception& e) {
    why = e.what();
    return nullptr;
  }
}

}  // namespace bench
