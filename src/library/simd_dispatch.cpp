// The library's double entry points (declared at the end of each algorithm header): each forwards
// to the build chosen once, at the first call, from the CPU and SPATIAL_DYNAMICS_SIMD
// (simd_backend.hpp). One indirect call per algorithm call.
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

#include "spatial_dynamics/algorithms.hpp"
#include "spatial_dynamics/algorithms/aba_refined.hpp"
#include "spatial_dynamics/algorithms/rnea_batch.hpp"
#include "spatial_dynamics/compiled/backend_table.hpp"
#include "spatial_dynamics/simd_backend.hpp"

namespace spatial_dynamics {
namespace detail {

// The two builds (src/library/backend.cpp), each in a shared object of its own.
const BackendTable& sd_backend_portable();
const BackendTable& sd_backend_avx2_fma();

namespace {

bool cpu_has_avx2_fma() {
#if defined(__x86_64__) || defined(__i386__)
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
  return false;
#endif
}

/// The build SPATIAL_DYNAMICS_SIMD asks for, or the CPU's best: chosen at the first call. A bad
/// request throws, and so does every later call (the choice is not cached until one is made).
const BackendTable& chosen_backend() {
  static const BackendTable& table = simd_backend_table(std::getenv("SPATIAL_DYNAMICS_SIMD"));
  return table;
}

}  // namespace

const BackendTable& simd_backend_table(const char* request) {
  if (request == nullptr || *request == '\0') return cpu_has_avx2_fma() ? sd_backend_avx2_fma() : sd_backend_portable();
  if (std::strcmp(request, "portable") == 0) return sd_backend_portable();
  if (std::strcmp(request, "avx2_fma") == 0) {
    if (!cpu_has_avx2_fma())
      throw std::invalid_argument("SPATIAL_DYNAMICS_SIMD=avx2_fma: this CPU has no AVX2 and FMA (use portable, or unset it)");
    return sd_backend_avx2_fma();
  }
  throw std::invalid_argument("SPATIAL_DYNAMICS_SIMD='" + std::string(request) +
                              "': expected 'portable' or 'avx2_fma' (or unset: chosen from the CPU)");
}

}  // namespace detail

using detail::chosen_backend;
using Vec = detail::BackendTable::Vec;
using Forces = detail::BackendTable::Forces;

const char* simd_backend() { return chosen_backend().name; }

const VectorX<double>& rnea(const Model<double>& model, Data<double>& data, const Vec& q, const Vec& qd,
                            const Vec& qdd) {
  return chosen_backend().rnea(model, data, q, qd, qdd, nullptr);
}
const VectorX<double>& rnea(const Model<double>& model, Data<double>& data, const Vec& q, const Vec& qd, const Vec& qdd,
                            const Forces& f_ext) {
  return chosen_backend().rnea(model, data, q, qd, qdd, &f_ext);
}
const VectorX<double>& gravity_torques(const Model<double>& model, Data<double>& data, const Vec& q) {
  return chosen_backend().gravity_torques(model, data, q);
}
const VectorX<double>& nonlinear_effects(const Model<double>& model, Data<double>& data, const Vec& q, const Vec& qd) {
  return chosen_backend().nonlinear_effects(model, data, q, qd);
}
const VectorX<double>& aba(const Model<double>& model, Data<double>& data, const Vec& q, const Vec& qd,
                           const Vec& tau) {
  return chosen_backend().aba(model, data, q, qd, tau, nullptr);
}
const VectorX<double>& aba(const Model<double>& model, Data<double>& data, const Vec& q, const Vec& qd, const Vec& tau,
                           const Forces& f_ext) {
  return chosen_backend().aba(model, data, q, qd, tau, &f_ext);
}
const VectorX<double>& forward_dynamics(const Model<double>& model, Data<double>& data, const Vec& q, const Vec& qd,
                                        const Vec& tau) {
  return chosen_backend().forward_dynamics(model, data, q, qd, tau, nullptr);
}
const VectorX<double>& forward_dynamics(const Model<double>& model, Data<double>& data, const Vec& q, const Vec& qd,
                                        const Vec& tau, const Forces& f_ext) {
  return chosen_backend().forward_dynamics(model, data, q, qd, tau, &f_ext);
}
const VectorX<double>& inverse_dynamics_actuated(const Model<double>& model, Data<double>& data, const Vec& q,
                                                 const Vec& qd, const Vec& qdd) {
  return chosen_backend().inverse_dynamics_actuated(model, data, q, qd, qdd, nullptr);
}
const VectorX<double>& inverse_dynamics_actuated(const Model<double>& model, Data<double>& data, const Vec& q,
                                                 const Vec& qd, const Vec& qdd, const Forces& f_ext) {
  return chosen_backend().inverse_dynamics_actuated(model, data, q, qd, qdd, &f_ext);
}
const VectorX<double>& forward_dynamics_actuated(const Model<double>& model, Data<double>& data, const Vec& q,
                                                 const Vec& qd, const Vec& tau) {
  return chosen_backend().forward_dynamics_actuated(model, data, q, qd, tau, nullptr);
}
const VectorX<double>& forward_dynamics_actuated(const Model<double>& model, Data<double>& data, const Vec& q,
                                                 const Vec& qd, const Vec& tau, const Forces& f_ext) {
  return chosen_backend().forward_dynamics_actuated(model, data, q, qd, tau, &f_ext);
}
const VectorX<double>& aba_refined(const Model<double>& model, Data<double>& data,
                                   RefinementWorkspace<double, DoubleDouble>& ws, const Vec& q, const Vec& qd,
                                   const Vec& tau, int max_iterations) {
  return chosen_backend().aba_refined(model, data, ws, q, qd, tau, max_iterations);
}
const VectorX<double>& aba_refined(const Model<double>& model, Data<double>& data,
                                   RefinementWorkspace<double, long double>& ws, const Vec& q, const Vec& qd,
                                   const Vec& tau, int max_iterations) {
  return chosen_backend().aba_refined_long_double(model, data, ws, q, qd, tau, max_iterations);
}
const MatrixX<double>& crba(const Model<double>& model, Data<double>& data, const Vec& q) {
  return chosen_backend().crba(model, data, q);
}
void forward_kinematics(const Model<double>& model, Data<double>& data, const Vec& q) {
  chosen_backend().forward_kinematics(model, data, q, nullptr);
}
void forward_kinematics(const Model<double>& model, Data<double>& data, const Vec& q, const Vec& qd) {
  chosen_backend().forward_kinematics(model, data, q, &qd);
}
const Matrix6X<double>& frame_jacobian(const Model<double>& model, Data<double>& data, const Vec& q, int frame,
                                       ReferenceFrame reference) {
  return chosen_backend().frame_jacobian(model, data, q, frame, reference);
}
void rnea_batch(const Model<double>& model, BatchData<double, kDefaultBatchLanes<double>>& data,
                const ConstMatrixRef<double>& q, const ConstMatrixRef<double>& qd, const ConstMatrixRef<double>& qdd,
                MatrixRef<double> tau) {
  chosen_backend().rnea_batch(model, data, q, qd, qdd, tau);
}

}  // namespace spatial_dynamics
