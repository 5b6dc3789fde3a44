#include "native_adapter.hpp"

#include "spatial_dynamics_adapter.hpp"

#ifndef SD_BENCH_NATIVE_FLAGS
#define SD_BENCH_NATIVE_FLAGS "unknown"
#endif

namespace bench {

std::unique_ptr<Adapter> make_native_spatial_dynamics_adapter(const spatial_dynamics::Model<double>& model,
                                                              bool single_precision) {
  if (single_precision) return std::make_unique<SpatialDynamicsAdapter<float>>(model);
  return std::make_unique<SpatialDynamicsAdapter<double>>(model);
}

const char* native_build_flags() { return SD_BENCH_NATIVE_FLAGS; }

}  // namespace bench
