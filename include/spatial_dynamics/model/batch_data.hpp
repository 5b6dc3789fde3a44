// The workspace of the batched algorithms (rnea_batch.hpp), allocated once from a Model; a call
// never allocates. Like Data, it belongs to one thread. L, the number of states a block would hold
// side by side, is kept in the type for the callers that name it.
#pragma once

#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/number/lanes.hpp"

namespace spatial_dynamics {

template <class S, int L = kDefaultBatchLanes<S>>
struct BatchData {
  static_assert(L >= 1, "a batch has at least one lane");
  static constexpr int lanes = L;

  Data<S> single;  // the one-state RNEA's buffers

  explicit BatchData(const Model<S>& model) : single(model) {}
};

}  // namespace spatial_dynamics
