// The declarations of the library's compiled double entry points (compiled_functions.def), made
// where SD_COMPILED_DOUBLE is defined (simd_backend.hpp). Each algorithm header includes this,
// so that a call in double binds to the library's function wherever the template is visible.
#pragma once

#include <string>
#include <vector>

#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/model/batch_data.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/simd_backend.hpp"
#include "spatial_dynamics/spatial/number/double_double.hpp"

namespace spatial_dynamics {

template <class S, class W>
struct RefinementWorkspace;  // aba_refined.hpp
template <class S>
struct ContactSet;  // model/contact_set.hpp
template <class S>
struct ContactData;  // model/contact_data.hpp
enum class ReferenceFrame;   // jacobian.hpp

#ifdef SD_COMPILED_DOUBLE
#define SD_DEFAULT(value) = value
#define SD_COMPILED(member, ret, name, params, args) ret name params;
#include "spatial_dynamics/compiled/compiled_functions.def"
#endif

}  // namespace spatial_dynamics
