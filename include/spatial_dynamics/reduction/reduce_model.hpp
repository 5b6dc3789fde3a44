// Reduced models: locked joints become fixed and everything they carry merges into composite
// inertias (eq. 24, moved by eq. 26); kept joints stay, in their original order. Every frame of
// the full model stays addressable. The reduced model gives the same torques, mass matrix and
// forward dynamics for the kept joints as the full model with the locked joints held still.
// A floating model's free root joint is always kept.
#pragma once

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "spatial_dynamics/model/joints/body_joint.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/reduction/scene.hpp"

namespace spatial_dynamics {

/// Thrown for a scene that names an unknown joint or link; the message names it.
class SceneError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

namespace detail {
/// Finite locked positions can still overflow what depends on them (a prismatic joint locked at
/// 1e300 m puts its subtree's inertia at 1e600): that is an error naming the body, not a model.
template <class S>
[[noreturn]] void throw_too_large(const Model<S>& full, int body, const std::string& what) {
  throw SceneError("locking the joints makes the " + what + " of link '" + full.body_names[body] +
                   "' not finite (a locked position is too large)");
}
}  // namespace detail

template <class S>
Model<S> reduce_model(const Model<S>& full, const Scene& scene) {
  using detail::throw_too_large;
  const int n = full.nbodies();
  std::vector<char> kept(n, 0);
  for (const std::string& name : scene.kept_joints) {
    if (!full.hasJoint(name)) throw SceneError("unknown joint '" + name + "' in the joints to keep");
    kept[full.jointBody(name)] = 1;
  }
  for (const auto& [name, position] : scene.locked_positions) {
    if (!full.hasJoint(name)) throw SceneError("unknown joint '" + name + "' in the locked positions");
    if (kept[full.jointBody(name)]) throw SceneError("joint '" + name + "' is both kept and locked");
    if (!std::isfinite(position)) throw SceneError("locked position of joint '" + name + "' is not finite");
  }
  for (int i = 1; i < n; ++i) {
    if (full.joints[i].nv == 1) continue;
    if (scene.locked_positions.count(full.joint_names[i]))
      throw SceneError(full.floating_base && i == 1
                           ? "the free root joint '" + full.joint_names[i] + "' cannot be locked"
                           : "joint '" + full.joint_names[i] + "' has " + std::to_string(full.joints[i].nv) +
                                 " coordinates (a locked position is one value), so it cannot be locked");
    kept[i] = 1;  // a floating base stays floating; a planar or floating joint in the tree stays too
  }

  Model<S> reduced;
  reduced.name = full.name;
  reduced.floating_base = full.floating_base;
  reduced.gravity = full.gravity;
  // owner[i]: the reduced body that carries full body i; to_owner[i] = ^iX_owner(i).
  std::vector<int> owner(n, 0), new_index(n, -1);
  std::vector<PluckerTransform<S>> to_owner(n);
  new_index[0] = 0;
  reduced.parent.push_back(-1);
  reduced.joints.push_back(full.joints[0]);
  reduced.X_tree.push_back(full.X_tree[0]);
  reduced.inertia.push_back(RigidInertia<S>::Zero());
  reduced.body_names.push_back(full.body_names[0]);
  reduced.joint_names.push_back(full.joint_names[0]);
  for (int i = 1; i < n; ++i) {
    const int lambda = full.parent[i];
    if (kept[i]) {
      owner[i] = new_index[i] = reduced.nbodies();
      to_owner[i] = PluckerTransform<S>::Identity();
      Joint<S> joint = full.joints[i];
      joint.idx_q = reduced.nq;
      joint.idx_v = reduced.nv;
      reduced.nq += joint.nq;
      reduced.nv += joint.nv;
      reduced.parent.push_back(owner[lambda]);
      reduced.joints.push_back(joint);
      reduced.X_tree.push_back(full.X_tree[i] * to_owner[lambda]);  // ^JX_λ ^λX_owner(λ)
      if (!reduced.X_tree.back().allFinite()) throw_too_large(full, i, "joint frame");
      reduced.inertia.push_back(RigidInertia<S>::Zero());
      reduced.body_names.push_back(full.body_names[i]);
      reduced.joint_names.push_back(full.joint_names[i]);
    } else {
      const auto it = scene.locked_positions.find(full.joint_names[i]);
      const S q = it == scene.locked_positions.end() ? S(0) : S(it->second);
      PluckerTransform<S> X_up;
      joint_up_transform(full, i, &q, X_up);
      owner[i] = owner[lambda];
      to_owner[i] = X_up * to_owner[lambda];  // ^iX_λ ^λX_owner
    }
  }
  for (int i = 0; i < n; ++i) {
    reduced.inertia[owner[i]] += to_owner[i].applyInverse(full.inertia[i]);  // eqs. 24, 26
    if (!reduced.inertia[owner[i]].allFinite()) throw_too_large(full, i, "inertia");
  }
  for (const Frame<S>& frame : full.frames) {
    reduced.frames.push_back({frame.name, owner[frame.body], frame.X_frame_body * to_owner[frame.body]});
    if (!reduced.frames.back().X_frame_body.allFinite()) throw_too_large(full, frame.body, "frame '" + frame.name + "'");
  }
  // Kept joints keep their actuators; a locked one's go with its coordinate.
  full.check_actuator_terms();
  reduced.reset_actuator_terms();
  for (int i = 1; i < n; ++i)
    if (kept[i]) reduced.copy_actuator_terms(full, i, new_index[i]);
  // Mimic records survive when the master is kept.
  for (int i = 1; i < reduced.nbodies(); ++i) {
    MimicRelation<S>& mimic = reduced.joints[i].mimic;
    if (mimic.active()) mimic.master_body = new_index[mimic.master_body];
  }
  reduced.finalize();
  return reduced;
}

/// The joints on the paths between `root_link` and each tip link.
template <class S>
Scene scene_from_root_and_tips(const Model<S>& full, const RootTipScene& spec) {
  auto body_of = [&](const std::string& link, const char* role) {
    if (!full.hasFrame(link)) throw SceneError("unknown " + std::string(role) + " link '" + link + "'");
    return full.frames[full.frameIndex(link)].body;
  };
  const int root = body_of(spec.root_link, "root");
  if (spec.tip_links.empty()) throw SceneError("no tip links given for root link '" + spec.root_link + "'");
  std::set<int> kept;
  for (const std::string& tip : spec.tip_links) {
    int a = body_of(tip, "tip"), b = root;
    // Walk both up to their common ancestor: the joints passed on either side are on the path.
    while (a != b) {
      if (a > b) { kept.insert(a); a = full.parent[a]; }
      else { kept.insert(b); b = full.parent[b]; }
    }
  }
  Scene scene;
  for (int i : kept) scene.kept_joints.push_back(full.joint_names[i]);
  scene.locked_positions = spec.locked_positions;
  return scene;
}

}  // namespace spatial_dynamics
