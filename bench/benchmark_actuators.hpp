// The actuator terms of the benchmark's rnea_actuated and aba_actuated rows: per velocity
// coordinate of a joint (none on a free root), armature in [0, 0.5], damping in [0, 2], Coulomb
// friction in [0, 1] and friction_velocity in [1e-3, 0.1], drawn from a generator seeded with the
// model's size, so that every adapter and the reference get the same terms.
#pragma once

#include <random>

#include "spatial_dynamics/model/model.hpp"

namespace bench {

/// Random terms as above on `model`'s joints from `rng` (the tests draw them too); finalizes the model.
inline void randomize_actuators(spatial_dynamics::Model<double>& model, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 1; i < model.nbodies(); ++i) {
    const auto& j = model.joints[i];
    if (j.coupled || (model.floating_base && i == 1)) continue;
    for (int k = j.idx_v; k < j.idx_v + j.nv; ++k) {
      model.armature[k] = 0.5 * u(rng);
      model.damping[k] = 2.0 * u(rng);
      model.friction[k] = u(rng);
      model.friction_velocity[k] = 1e-3 + 0.099 * u(rng);
    }
  }
  model.finalize();
}

/// The benchmark's: `rigid` with terms drawn from a generator seeded with its size.
inline spatial_dynamics::Model<double> with_benchmark_actuators(const spatial_dynamics::Model<double>& rigid) {
  spatial_dynamics::Model<double> model = rigid;
  std::mt19937 rng(1000 + model.nv);
  randomize_actuators(model, rng);
  return model;
}

}  // namespace bench
