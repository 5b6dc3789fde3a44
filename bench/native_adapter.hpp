// spatial_dynamics compiled for this machine (-march=native: AVX, FMA), as the peers' figures in
// the speed targets were: the adapter lives in a shared library of its own, built with
// -march=native, EIGEN_MAX_ALIGN_BYTES=16 (Eigen's documented switch for ABI compatibility with
// SSE2 code: the fixed-size types, and so the Model<double> handed in, have the same layout on
// both sides) and hidden symbols (its algorithm instances are its own, never merged with the
// portable ones of the benchmark executable). Eigen's dynamic storage is still allocated with
// 64-byte alignment inside, so results leave only through Adapter::result_into.
#pragma once

#include <memory>

#include "benchmark_types.hpp"
#include "spatial_dynamics/model/model.hpp"

namespace bench {

/// The adapter for `model` in double, or float with `single_precision`.
__attribute__((visibility("default"))) std::unique_ptr<Adapter> make_native_spatial_dynamics_adapter(
    const spatial_dynamics::Model<double>& model, bool single_precision);

/// The flags the library was compiled with, for results.md.
__attribute__((visibility("default"))) const char* native_build_flags();

}  // namespace bench
