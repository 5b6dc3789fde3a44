// Coupled mimic joints: each mimic joint follows its master, q = k·q_master + offset,
// q̇ = k·q̇_master, q̈ = k·q̈_master, and disappears from the model's coordinates. With
// q̇ = G q̇_c the coupled system's torques are τ_c = Gᵀ τ, its mass matrix Gᵀ M G (virtual power).
#pragma once

#include <stdexcept>

#include "spatial_dynamics/model/model.hpp"

namespace spatial_dynamics {

template <class S>
Model<S> couple_mimic_joints(const Model<S>& independent) {
  Model<S> coupled = independent;
  const int n = coupled.nbodies();
  // Resolve chains (a mimic of a mimic) to the joint that has coordinates of its own.
  for (int i = 1; i < n; ++i) {
    Joint<S>& j = coupled.joints[i];
    if (!j.mimic.active()) continue;
    if (j.nv != 1) throw std::invalid_argument("joint '" + coupled.joint_names[i] + "': only 1-DoF joints can mimic");
    S k = j.mimic.multiplier, offset = j.mimic.offset;
    int master = j.mimic.master_body;
    for (int hops = 0; independent.joints[master].mimic.active(); ++hops) {
      if (hops > n) throw std::invalid_argument("joint '" + coupled.joint_names[i] + "': mimic relations form a cycle");
      const MimicRelation<S>& next = independent.joints[master].mimic;
      offset = k * next.offset + offset;  // q = k (k' q'' + o') + o
      k = k * next.multiplier;
      master = next.master_body;
    }
    if (!(k - k == S(0)) || !(offset - offset == S(0)))  // finite multipliers whose product overflows
      throw std::invalid_argument("joint '" + coupled.joint_names[i] +
                                  "': the multiplier or offset of its mimic chain is not finite");
    j.mimic = MimicRelation<S>{master, k, offset};
    j.coupled = true;
  }
  // Renumber the coordinates of the joints that keep their own; coupled ones take their master's.
  coupled.nq = coupled.nv = 0;
  for (int i = 1; i < n; ++i) {
    Joint<S>& j = coupled.joints[i];
    if (j.coupled) continue;
    j.idx_q = coupled.nq;
    j.idx_v = coupled.nv;
    coupled.nq += j.nq;
    coupled.nv += j.nv;
  }
  for (int i = 1; i < n; ++i) {
    Joint<S>& j = coupled.joints[i];
    if (!j.coupled) continue;
    j.idx_q = coupled.joints[j.mimic.master_body].idx_q;
    j.idx_v = coupled.joints[j.mimic.master_body].idx_v;
    coupled.has_coupled_joints = true;
  }
  // A joint with coordinates of its own keeps its actuators; a coupled one has its master's.
  independent.check_actuator_terms();
  coupled.reset_actuator_terms();
  for (int i = 1; i < n; ++i)
    if (!coupled.joints[i].coupled) coupled.copy_actuator_terms(independent, i, i);
  coupled.finalize();
  return coupled;
}

}  // namespace spatial_dynamics
