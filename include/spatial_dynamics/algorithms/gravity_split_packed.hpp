// The ABA's gravity split (gravity_split.hpp) on packed 3-vectors where SD_PACKED3 is defined:
// gravity and the subtree's gravity force as double-double 3-vectors in register pairs
// (spatial/packed3_double_double.hpp), a rotation three broadcasts and three exact products.
// The split_gravity_* steps take this path for double and the scalar one otherwise.
#pragma once

#include <type_traits>

#include "spatial_dynamics/algorithms/gravity_split.hpp"
#include "spatial_dynamics/spatial/packed3_double_double.hpp"

namespace spatial_dynamics {
namespace detail {

#ifdef SD_PACKED3

SD_INLINE void gravity_split_start_packed(const Model<double>& model, Data<double>& data) {
  auto& base = data.packed_gravity_split[0];
  packed3::store(packed3::make(model.gravity[0], model.gravity[1], model.gravity[2]), base.gravity_hi);
  packed3::store(packed3::Packed3{}, base.gravity_lo);
}

/// As gravity_split_outward: g_i = E_i g_λ and the body's own force (g_i × h_i ; −m_i g_i).
SD_INLINE void gravity_split_outward_packed(const Model<double>& model, Data<double>& data, int i) {
  using namespace packed3;
  Packed3 c0, c1, c2;
  load_columns(data.X_up[i].E, c0, c1, c2);
  const auto& parent = data.packed_gravity_split[model.parent[i]];
  auto& body = data.packed_gravity_split[i];
  const PackedDoubleDouble g = mat_vec(c0, c1, c2, {load(parent.gravity_hi), load(parent.gravity_lo)});
  store(g.hi, body.gravity_hi);
  store(g.lo, body.gravity_lo);
  const RigidInertia<double>& I = model.inertia[i];
  const PackedDoubleDouble n = cross(g, load(I.first_moment.data()));  // the pad lane: Ī_O(0, 0)
  const PackedDoubleDouble f = scale(splat(-I.mass), g);
  store(n.hi, body.moment_hi);
  store(n.lo, body.moment_lo);
  store(f.hi, body.force_hi);
  store(f.lo, body.force_lo);
}

/// As gravity_split_inward: τ − Sᵀ f at body i's joint, then f_λ += (Eᵀ n + r × Eᵀ f ; Eᵀ f).
SD_INLINE void gravity_split_inward_packed(const Model<double>& model, Data<double>& data, int i,
                                           const ConstVectorRef<double>& tau) {
  using namespace packed3;
  const Joint<double>& j = model.joints[i];
  const auto& body = data.packed_gravity_split[i];
  const PackedDoubleDouble n{load(body.moment_hi), load(body.moment_lo)};
  const PackedDoubleDouble f{load(body.force_hi), load(body.force_lo)};
  double* out = data.tau_less_gravity.data();
  const int v = j.idx_v;
  if (j.nv == 1) {  // one lane of n or f, or the axis' dot product: no copy of the other lanes
    const PackedDoubleDouble& along = one_dof_rotates(j) ? n : f;
    DoubleDouble lanes[3];
    for (int k = 0; k < 3; ++k) lanes[k] = DoubleDouble(along.hi[k], along.lo[k]);
    out[v] = double(DoubleDouble(tau[v]) - detail::dot_axis(j, lanes));
  } else {
    DoubleDouble n_wide[3], f_wide[3], projected[6];
    for (int k = 0; k < 3; ++k) {
      n_wide[k] = DoubleDouble(body.moment_hi.lane[k], body.moment_lo.lane[k]);
      f_wide[k] = DoubleDouble(body.force_hi.lane[k], body.force_lo.lane[k]);
    }
    joint_project(j, data.joint_sin[i], data.joint_cos[i], n_wide, f_wide, projected);  // Sᵀ f, in double-double
    for (int k = 0; k < j.nv; ++k) out[v + k] = double(DoubleDouble(tau[v + k]) - projected[k]);
  }
  const int lambda = model.parent[i];
  if (lambda == 0) return;
  Packed3 c0, c1, c2, t0, t1, t2;
  load_columns(data.X_up[i].E, c0, c1, c2);
  transpose(c0, c1, c2, t0, t1, t2);
  const PackedDoubleDouble Et_f = mat_vec(t0, t1, t2, f);
  const Packed3 r = load_after(data.X_up[i].r.data() - 1);  // (r ; E(2, 2))
  auto& parent = data.packed_gravity_split[lambda];
  const PackedDoubleDouble moment =
      PackedDoubleDouble{load(parent.moment_hi), load(parent.moment_lo)} + (mat_vec(t0, t1, t2, n) + cross(r, Et_f));
  const PackedDoubleDouble force = PackedDoubleDouble{load(parent.force_hi), load(parent.force_lo)} + Et_f;
  store(moment.hi, parent.moment_hi);
  store(moment.lo, parent.moment_lo);
  store(force.hi, parent.force_hi);
  store(force.lo, parent.force_lo);
}

#endif  // SD_PACKED3

template <class S>
SD_INLINE void split_gravity_start(const Model<S>& model, Data<S>& data) {
#ifdef SD_PACKED3
  if constexpr (std::is_same<S, double>::value) return gravity_split_start_packed(model, data);
#endif
  gravity_split_start(model, data);
}

template <class S>
SD_INLINE void split_gravity_outward(const Model<S>& model, Data<S>& data, int i) {
#ifdef SD_PACKED3
  if constexpr (std::is_same<S, double>::value) return gravity_split_outward_packed(model, data, i);
#endif
  gravity_split_outward(model, data, i);
}

template <class S>
SD_INLINE void split_gravity_inward(const Model<S>& model, Data<S>& data, int i, const ConstVectorRef<S>& tau) {
#ifdef SD_PACKED3
  if constexpr (std::is_same<S, double>::value) return gravity_split_inward_packed(model, data, i, tau);
#endif
  gravity_split_inward(model, data, i, tau);
}

}  // namespace detail
}  // namespace spatial_dynamics
