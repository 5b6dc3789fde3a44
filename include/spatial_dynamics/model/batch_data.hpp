// The workspace of the batched algorithms (rnea_batch.hpp): Data's per-body buffers, each entry
// holding L states side by side (spatial/number/lanes.hpp), plus one-state Data for the models the
// batched kernels leave to the one-state algorithms. Allocated once from a Model; a call never
// allocates. Like Data, it belongs to one thread.
#pragma once

#include <vector>

#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/number/lanes.hpp"

namespace spatial_dynamics {

template <class S, int L = kDefaultBatchLanes<S>>
struct BatchData {
  static_assert(L >= 1, "a batch has at least one lane");
  static constexpr int lanes = L;

  // Per body, L states each, as Data::RneaBody: v = (w ; v), a = (aw ; al), f = (n ; f) and ^iX_λ.
  struct RneaBody {
    LaneVector3<S, L> w, v, aw, al, n, f;
    LaneTransform<S, L> X;
  };
  std::vector<RneaBody> rnea;

  // The block's inputs and result, per coordinate.
  std::vector<Lanes<S, L>> q, qd, qdd, tau;

  Data<S> single;  // one state at a time (models with coupled mimic joints, planar or floating joints in the tree)

  explicit BatchData(const Model<S>& model)
      : rnea(model.nbodies()),
        q(model.nq, Lanes<S, L>::Zero()),
        qd(model.nv, Lanes<S, L>::Zero()),
        qdd(model.nv, Lanes<S, L>::Zero()),
        tau(model.nv, Lanes<S, L>::Zero()),
        single(model) {}
};

}  // namespace spatial_dynamics
