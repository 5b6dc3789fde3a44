// The CRBA's carry of a column to a run of revolute ancestors in base coordinates, several
// ancestors at once (spatial/number/lanes.hpp): used by crba.hpp on deep trees.
#pragma once

#include <algorithm>

#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/number/lanes.hpp"

namespace spatial_dynamics {
namespace detail {

/// M_ji = a_j · (n + f × (p_j − p_i)) for the bodies j = first … last of a run of revolute
/// joints (Data::revolute_run_start), L of them at a time: (n, f) is column `col`'s F in base
/// orientation about body i's origin p_i. The same formula as carry_column_in_base, lane by lane.
template <class S>
SD_INLINE void carry_over_revolute_run(const Model<S>& model, Data<S>& data, const Vector3<S>& n, const Vector3<S>& f,
                                       const Vector3<S>& p_i, int first, int last, int col) {
  constexpr int L = kRegisterLanes<S>;
  using Lane = Lanes<S, L>;
  const int stride = static_cast<int>(data.base_origin_and_axis.size()) / 6;
  const S* soa = data.base_origin_and_axis.data();
  S* M = data.M.data();
  const Eigen::Index m_stride = data.M.outerStride();
  const Eigen::Index row0 = model.joints[first].idx_v;
  for (int j = first; j <= last; j += L) {
    const Lane dx = Lane::Load(soa + j) - p_i.x(), dy = Lane::Load(soa + stride + j) - p_i.y(),
               dz = Lane::Load(soa + 2 * stride + j) - p_i.z();
    const Lane nx = n.x() + (f.y() * dz - f.z() * dy), ny = n.y() + (f.z() * dx - f.x() * dz),
               nz = n.z() + (f.x() * dy - f.y() * dx);  // n_j = n + f × (p_j − p_i)
    const Lane m = Lane::Load(soa + 3 * stride + j) * nx + Lane::Load(soa + 4 * stride + j) * ny +
                   Lane::Load(soa + 5 * stride + j) * nz;  // M_ji = a_j · n_j
    const int count = std::min(L, last - j + 1);
    for (int l = 0; l < count; ++l) {
      const Eigen::Index row = row0 + (j - first) + l;
      M[row + col * m_stride] = m[l];
      M[col + row * m_stride] = m[l];
    }
  }
}

}  // namespace detail
}  // namespace spatial_dynamics
