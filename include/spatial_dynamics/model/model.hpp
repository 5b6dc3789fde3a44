// The immutable kinematic tree (the model layer: doc/library.md). Body 0 is the fixed base: the URDF root
// link (and everything fixed to it) for a fixed-base model, an empty "universe" for a floating
// one. Bodies 1..N each have one joint connecting them to parent[i] < i, so index order is a
// topological order. Plain data, like spatial_v2's model struct.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "spatial_dynamics/model/frame.hpp"
#include "spatial_dynamics/model/joint.hpp"
#include "spatial_dynamics/model/physical_inertia.hpp"
#include "spatial_dynamics/spatial/eigen_types.hpp"
#include "spatial_dynamics/spatial/plucker_transform.hpp"
#include "spatial_dynamics/spatial/rigid_inertia.hpp"

namespace spatial_dynamics {

template <class S>
struct Model {
  std::string name;  // the robot's name (URDF <robot name>)
  int nq = 0;  // configuration size (a free root adds 7)
  int nv = 0;  // velocity size = number of degrees of freedom (a free root adds 6)
  bool floating_base = false;
  bool has_coupled_joints = false;  // some joints follow a master's coordinate (couple_mimic_joints)
  // Some joint other than a free root has several coordinates (planar, or floating inside the
  // tree): the packed and batched paths, written for 1-DoF trees, leave such models to the
  // generic passes. Set by finalize().
  bool has_multi_dof_tree_joints = false;

  // Per body, index 0 = fixed base. Entries 0 of joints/X_tree/joint_names are unused.
  std::vector<int> parent;
  std::vector<Joint<S>> joints;
  std::vector<PluckerTransform<S>> X_tree;  // ^{J_i}X_{parent}: parent body → joint i frame
  std::vector<RigidInertia<S>> inertia;     // body inertia in body coordinates (eq. 25)
  std::vector<std::string> body_names;      // the URDF link that defines each body's frame
  std::vector<std::string> joint_names;

  std::vector<Frame<S>> frames;  // every URDF link, in URDF tree order

  Vector3<S> gravity = Vector3<S>(S(0), S(0), S(-9.81));  // in base coordinates

  // The actuators, per velocity coordinate (a coupled mimic joint has its master's): armature, the
  // reflected rotor inertia J_rotor G² (kg m² or kg), part of M in rnea, crba and aba; viscous
  // damping (N m s/rad or N s/m) and Coulomb friction (N m or N), ramping linearly through zero
  // below friction_velocity (rad/s or m/s): the joint forces of actuator_forces
  // (algorithms/actuator_dynamics.hpp). finalize() sizes empty ones to nv: 0, and 1e-3 for the speed.
  // (std::vector, as every member: a Model may be built in one build of the code and freed in
  // another, and Eigen's dynamic allocation differs between SSE and AVX builds.)
  std::vector<S> armature, damping, friction, friction_velocity;
  bool has_armature = false;  // some armature is not zero (set by finalize())

  int nbodies() const { return static_cast<int>(parent.size()); }

  /// Index of the frame called `name`; throws std::out_of_range naming it when unknown.
  int frameIndex(const std::string& name) const {
    const auto it = frame_index_.find(name);
    if (it == frame_index_.end()) throw std::out_of_range("unknown frame '" + name + "'");
    return it->second;
  }
  bool hasFrame(const std::string& name) const { return frame_index_.count(name) != 0; }

  /// Body whose joint is called `name`; throws std::out_of_range naming it when unknown.
  int jointBody(const std::string& name) const {
    const auto it = joint_index_.find(name);
    if (it == joint_index_.end()) throw std::out_of_range("unknown joint '" + name + "'");
    return it->second;
  }
  bool hasJoint(const std::string& name) const { return joint_index_.count(name) != 0; }

  /// Names of the velocity coordinates, in order: a 1-DoF joint's name, `<joint>/wx` … `/vz` for a
  /// free joint, `<joint>/x`, `/y`, `/yaw` for a planar one (model/joints/<type>.hpp).
  std::vector<std::string> velocityNames() const {
    std::vector<std::string> names;
    for (int i = 1; i < nbodies(); ++i) {
      if (joints[i].coupled) continue;  // no coordinate of its own
      for (std::string& name : visit_joint(joints[i], [&](const auto& joint) { return joint.velocity_names(joint_names[i]); }))
        names.push_back(std::move(name));
    }
    return names;
  }

  /// Names of the configuration coordinates, in order: as velocityNames, except a free joint's
  /// seven, `<joint>/x`, `/y`, `/z`, `/qx`, `/qy`, `/qz`, `/qw`.
  std::vector<std::string> positionNames() const {
    std::vector<std::string> names;
    for (int i = 1; i < nbodies(); ++i) {
      if (joints[i].coupled) continue;
      for (std::string& name : visit_joint(joints[i], [&](const auto& joint) { return joint.position_names(joint_names[i]); }))
        names.push_back(std::move(name));
    }
    return names;
  }

  /// The bodies' inertial parameters π (10 per body 1..N, in body order; RigidInertia::toParameters):
  /// τ = Y π with Y the joint-torque regressor (algorithms/regressor.hpp).
  VectorX<S> inertial_parameters() const {
    VectorX<S> pi(10 * (nbodies() - 1));
    for (int i = 1; i < nbodies(); ++i) inertia[i].toParameters(pi.data() + 10 * (i - 1));
    return pi;
  }

  /// Sets every body's inertia from π (inertial_parameters' layout). Throws std::invalid_argument,
  /// leaving the model as it was, for a wrong length or a body that is not physical (finite, mass
  /// ≥ 0, rotational inertia about the centre of mass positive semi-definite with the triangle
  /// inequality; a massless body with no first moment and no rotational inertia), naming its link.
  void set_inertial_parameters(const VectorX<S>& pi) {
    if (pi.size() != 10 * (nbodies() - 1))
      throw std::invalid_argument("inertial parameters: " + std::to_string(pi.size()) + " values for " +
                                  std::to_string(nbodies() - 1) + " bodies (10 each)");
    std::vector<RigidInertia<S>> bodies(inertia.begin(), inertia.end());
    for (int i = 1; i < nbodies(); ++i) {
      const RigidInertia<S> body = RigidInertia<S>::FromParameters(pi.data() + 10 * (i - 1));
      const std::string problem = rigid_inertia_problem(body);
      if (!problem.empty()) throw std::invalid_argument("inertial parameters of link '" + body_names[i] + "': " + problem);
      bodies[i] = body;
    }
    inertia = std::move(bodies);
  }

  /// Sizes the actuator terms for nv coordinates with their defaults (no actuator dynamics).
  void reset_actuator_terms() {
    armature.assign(nv, S(0));
    damping.assign(nv, S(0));
    friction.assign(nv, S(0));
    friction_velocity.assign(nv, S(1e-3));
  }

  /// Body `to`'s joint takes the actuator terms of body `from` of `source`: the same joint in
  /// another numbering of the coordinates (a reduced or coupled model).
  void copy_actuator_terms(const Model& source, int from, int to) {
    const int n = joints[to].nv, a = source.joints[from].idx_v, b = joints[to].idx_v;
    for (int k = 0; k < n; ++k) {
      armature[b + k] = source.armature[a + k];
      damping[b + k] = source.damping[a + k];
      friction[b + k] = source.friction[a + k];
      friction_velocity[b + k] = source.friction_velocity[a + k];
    }
  }

  /// Rebuilds the name lookups and the derived flags, sizes empty actuator terms and checks them
  /// (std::invalid_argument naming the coordinate and the term); the model builder calls it once,
  /// after filling the vectors.
  void finalize() {
    frame_index_.clear();
    joint_index_.clear();
    for (int f = 0; f < static_cast<int>(frames.size()); ++f) frame_index_[frames[f].name] = f;
    for (int i = 1; i < nbodies(); ++i) joint_index_[joint_names[i]] = i;
    for (int i = 1; i < nbodies(); ++i) joints[i].update_model();
    has_multi_dof_tree_joints = false;
    for (int i = 1; i < nbodies(); ++i)
      if (joints[i].nv > 1 && !(floating_base && i == 1)) has_multi_dof_tree_joints = true;
    if (armature.empty() && damping.empty() && friction.empty() && friction_velocity.empty()) reset_actuator_terms();
    check_actuator_terms();
    has_armature = false;
    for (const S& a : armature) has_armature = has_armature || a != S(0);
  }

  /// Each actuator term sized nv, finite and not negative, each friction_velocity above zero.
  void check_actuator_terms() const {
    const std::vector<std::string> names = velocityNames();
    const std::pair<const char*, const std::vector<S>*> terms[] = {
        {"armature", &armature}, {"damping", &damping}, {"friction", &friction}, {"friction_velocity", &friction_velocity}};
    for (const auto& [term, values] : terms) {
      if (static_cast<int>(values->size()) != nv)
        throw std::invalid_argument(std::string("the model's ") + term + " has " + std::to_string(values->size()) +
                                    " entries for " + std::to_string(nv) + " velocity coordinates");
      using std::isfinite;
      for (int k = 0; k < nv; ++k) {
        const S x = (*values)[k];
        const bool speed = values == &friction_velocity;
        if (!isfinite(x) || x < S(0) || (speed && !(x > S(0))))
          throw std::invalid_argument("coordinate '" + (k < static_cast<int>(names.size()) ? names[k] : std::to_string(k)) +
                                      "': " + term + " must be finite and " + (speed ? "above zero" : "not negative"));
      }
    }
  }

  /// The same model in another scalar type (e.g. a high-precision reference).
  template <class T>
  Model<T> cast() const {
    Model<T> m;
    m.name = name;
    m.nq = nq;
    m.nv = nv;
    m.floating_base = floating_base;
    m.has_coupled_joints = has_coupled_joints;
    m.parent = parent;
    for (const auto& j : joints) m.joints.push_back(j.template cast<T>());
    for (const auto& x : X_tree) m.X_tree.push_back(x.template cast<T>());
    for (const auto& in : inertia) m.inertia.push_back(in.template cast<T>());
    m.body_names = body_names;
    m.joint_names = joint_names;
    for (const auto& f : frames) m.frames.push_back(f.template cast<T>());
    m.gravity = gravity.template cast<T>();
    m.armature.assign(armature.begin(), armature.end());
    m.damping.assign(damping.begin(), damping.end());
    m.friction.assign(friction.begin(), friction.end());
    m.friction_velocity.assign(friction_velocity.begin(), friction_velocity.end());
    m.finalize();
    return m;
  }

 private:
  std::unordered_map<std::string, int> frame_index_;
  std::unordered_map<std::string, int> joint_index_;
};

}  // namespace spatial_dynamics
