// Velocities and accelerations of a sampled trajectory by finite differences over unevenly spaced
// times: at point k, the first and second derivative of the quadratic through three neighbouring
// points (Lagrange interpolation) — points k−1, k, k+1 inside (central differences), the first or
// last three at the ends (one-sided). With evenly spaced times inside this is
// (x_{k+1} − x_{k−1}) / 2h and (x_{k+1} − 2x_k + x_{k−1}) / h², both with an error O(h²); at the ends
// the velocity is (∓3x_0 ± 4x_1 ∓ x_2) / 2h, O(h²), and the acceleration that of the neighbour,
// O(h). With only two points: the line through them (velocity only). ROS-free.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace spatial_dynamics {

/// x'(t_k) ≈ Σ_m first[m] x_{start+m} and x''(t_k) ≈ Σ_m second[m] x_{start+m}.
struct DifferenceWeights {
  std::size_t start = 0;
  std::size_t count = 0;  // 3, or 2 for a two-point trajectory (second[] then unused)
  std::array<double, 3> first{}, second{};
};

/// The weights at point k of strictly increasing times t (at least two).
inline DifferenceWeights difference_weights(const std::vector<double>& t, std::size_t k) {
  DifferenceWeights w;
  if (t.size() == 2) {  // the line through both points
    const double h = t[1] - t[0];
    w.count = 2;
    w.first = {-1.0 / h, 1.0 / h, 0.0};
    return w;
  }
  w.count = 3;
  w.start = std::min(k > 0 ? k - 1 : 0, t.size() - 3);
  // ℓ_m(t) = Π_{n≠m} (t − t_n)/(t_m − t_n): ℓ_m'(t_k) = Σ_{n≠m} (t_k − t_{n'}) / Π (t_m − t_n), ℓ_m'' = 2 / Π (t_m − t_n)
  for (std::size_t m = 0; m < 3; ++m) {
    const double tm = t[w.start + m];
    const double ta = t[w.start + (m + 1) % 3], tb = t[w.start + (m + 2) % 3];
    const double denominator = (tm - ta) * (tm - tb);
    w.first[m] = ((t[k] - ta) + (t[k] - tb)) / denominator;
    w.second[m] = 2.0 / denominator;
  }
  return w;
}

}  // namespace spatial_dynamics
