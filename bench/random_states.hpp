// The benchmark's pool of states: q uniform in (−π, π) per joint (a uniform-direction unit
// quaternion and a position in (−1, 1)³ for a free root), q̇ and q̈ uniform in (−1, 1), and
// τ = RNEA(q, q̇, q̈) in double, the input of the forward dynamics rows.
#pragma once

#include <random>
#include <vector>

#include "benchmark_types.hpp"
#include "spatial_dynamics/algorithms.hpp"

namespace bench {

inline std::vector<State> random_states(const spatial_dynamics::Model<double>& model, int count, unsigned seed) {
  namespace sd = spatial_dynamics;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  sd::Data<double> data(model);
  std::vector<State> states;
  for (int s = 0; s < count; ++s) {
    State st;
    st.q.resize(model.nq);
    for (int i = 1; i < model.nbodies(); ++i) {
      const auto& j = model.joints[i];
      if (j.type == sd::JointType::Free) {
        for (int k = 0; k < 3; ++k) st.q[j.idx_q + k] = u(rng);
        Eigen::Vector4d quat(u(rng), u(rng), u(rng), u(rng));
        st.q.segment<4>(j.idx_q + 3) = quat.normalized();
      } else {
        st.q[j.idx_q] = M_PI * u(rng);
      }
    }
    st.qd = Eigen::VectorXd::NullaryExpr(model.nv, [&] { return u(rng); });
    st.qdd = Eigen::VectorXd::NullaryExpr(model.nv, [&] { return u(rng); });
    st.tau = sd::rnea(model, data, st.q, st.qd, st.qdd);
    states.push_back(st);
  }
  return states;
}

}  // namespace bench
