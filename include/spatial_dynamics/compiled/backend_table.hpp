// One build of the compiled double instances (simd_backend.hpp): a table of entry points, one
// per algorithm, each the header template instantiated with that build's flags. The library
// holds two (portable, avx2_fma), each in a shared object of its own with hidden symbols, so
// that the inline functions of the two builds are never merged. The f_ext and qd pointers are
// null for the overloads without them.
#pragma once

#include <vector>

#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/jacobian.hpp"
#include "spatial_dynamics/algorithms/rnea_batch.hpp"
#include "spatial_dynamics/model/batch_data.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/spatial/double_double.hpp"

namespace spatial_dynamics {

template <class S, class W>
struct RefinementWorkspace;

namespace detail {

struct BackendTable {
  using Vec = ConstVectorRef<double>;
  using Forces = std::vector<ForceVector<double>>;
  const char* name;
  const VectorX<double>& (*rnea)(const Model<double>&, Data<double>&, const Vec& q, const Vec& qd, const Vec& qdd,
                                 const Forces* f_ext);
  const VectorX<double>& (*gravity_torques)(const Model<double>&, Data<double>&, const Vec& q);
  const VectorX<double>& (*nonlinear_effects)(const Model<double>&, Data<double>&, const Vec& q, const Vec& qd);
  const VectorX<double>& (*aba)(const Model<double>&, Data<double>&, const Vec& q, const Vec& qd, const Vec& tau,
                                const Forces* f_ext);
  const VectorX<double>& (*forward_dynamics)(const Model<double>&, Data<double>&, const Vec& q, const Vec& qd,
                                             const Vec& tau, const Forces* f_ext);
  const VectorX<double>& (*inverse_dynamics_actuated)(const Model<double>&, Data<double>&, const Vec& q, const Vec& qd,
                                                      const Vec& qdd, const Forces* f_ext);
  const VectorX<double>& (*forward_dynamics_actuated)(const Model<double>&, Data<double>&, const Vec& q, const Vec& qd,
                                                      const Vec& tau, const Forces* f_ext);
  const VectorX<double>& (*aba_refined)(const Model<double>&, Data<double>&, RefinementWorkspace<double, DoubleDouble>&,
                                        const Vec& q, const Vec& qd, const Vec& tau, int max_iterations);
  const VectorX<double>& (*aba_refined_long_double)(const Model<double>&, Data<double>&,
                                                    RefinementWorkspace<double, long double>&, const Vec& q,
                                                    const Vec& qd, const Vec& tau, int max_iterations);
  const MatrixX<double>& (*crba)(const Model<double>&, Data<double>&, const Vec& q);
  void (*forward_kinematics)(const Model<double>&, Data<double>&, const Vec& q, const Vec* qd);
  const Matrix6X<double>& (*frame_jacobian)(const Model<double>&, Data<double>&, const Vec& q, int frame,
                                            ReferenceFrame reference);
  void (*rnea_batch)(const Model<double>&, BatchData<double, kDefaultBatchLanes<double>>&,
                     const ConstMatrixRef<double>& q, const ConstMatrixRef<double>& qd,
                     const ConstMatrixRef<double>& qdd, MatrixRef<double> tau);
};

/// The build `request` names: "portable", "avx2_fma", or "" for the one the CPU runs best.
/// Throws std::invalid_argument naming SPATIAL_DYNAMICS_SIMD for another name, or for
/// "avx2_fma" on a CPU without AVX2 and FMA.
const BackendTable& simd_backend_table(const char* request);

}  // namespace detail
}  // namespace spatial_dynamics
