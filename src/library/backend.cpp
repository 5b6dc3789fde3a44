// One build of the compiled double instances (compiled/backend_table.hpp). CMakeLists.txt compiles
// this file twice, with SD_BACKEND_ENTRY and SD_BACKEND_NAME naming the build, portable and with
// -mavx2 -mfma, into two shared objects with hidden symbols and Eigen's alignment held at 16 bytes
// (Eigen's switch for the same layout of its fixed-size types on both sides).
#define SPATIAL_DYNAMICS_HEADER_ONLY 1  // the templates themselves, not the library's entry points

#include "spatial_dynamics/algorithms.hpp"
#include "spatial_dynamics/algorithms/aba_refined.hpp"
#include "spatial_dynamics/algorithms/rnea_batch.hpp"
#include "spatial_dynamics/compiled/backend_table.hpp"

namespace spatial_dynamics {
namespace detail {

__attribute__((visibility("default"))) const BackendTable& SD_BACKEND_ENTRY() {
  // Each entry: the template instance whose parameters are the entry's (the table's field type).
  static const BackendTable table{
      SD_BACKEND_NAME,
#define SD_COMPILED(member, ret, name, params, args) &spatial_dynamics::name,
#include "spatial_dynamics/compiled/compiled_functions.def"
  };
  return table;
}

}  // namespace detail
}  // namespace spatial_dynamics
