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

using Vec = BackendTable::Vec;
using Forces = BackendTable::Forces;

__attribute__((visibility("default"))) const BackendTable& SD_BACKEND_ENTRY() {
  static const BackendTable table{
      SD_BACKEND_NAME,
      [](const Model<double>& m, Data<double>& d, const Vec& q, const Vec& qd, const Vec& qdd,
         const Forces* f_ext) -> const VectorX<double>& {
        return f_ext ? spatial_dynamics::rnea(m, d, q, qd, qdd, *f_ext) : spatial_dynamics::rnea(m, d, q, qd, qdd);
      },
      [](const Model<double>& m, Data<double>& d, const Vec& q) -> const VectorX<double>& {
        return spatial_dynamics::gravity_torques(m, d, q);
      },
      [](const Model<double>& m, Data<double>& d, const Vec& q, const Vec& qd) -> const VectorX<double>& {
        return spatial_dynamics::nonlinear_effects(m, d, q, qd);
      },
      [](const Model<double>& m, Data<double>& d, const Vec& q, const Vec& qd, const Vec& tau,
         const Forces* f_ext) -> const VectorX<double>& {
        return f_ext ? spatial_dynamics::aba(m, d, q, qd, tau, *f_ext) : spatial_dynamics::aba(m, d, q, qd, tau);
      },
      [](const Model<double>& m, Data<double>& d, const Vec& q, const Vec& qd, const Vec& tau,
         const Forces* f_ext) -> const VectorX<double>& {
        return f_ext ? spatial_dynamics::forward_dynamics(m, d, q, qd, tau, *f_ext)
                     : spatial_dynamics::forward_dynamics(m, d, q, qd, tau);
      },
      [](const Model<double>& m, Data<double>& d, const Vec& q, const Vec& qd, const Vec& qdd,
         const Forces* f_ext) -> const VectorX<double>& {
        return f_ext ? spatial_dynamics::inverse_dynamics_actuated(m, d, q, qd, qdd, *f_ext)
                     : spatial_dynamics::inverse_dynamics_actuated(m, d, q, qd, qdd);
      },
      [](const Model<double>& m, Data<double>& d, const Vec& q, const Vec& qd, const Vec& tau,
         const Forces* f_ext) -> const VectorX<double>& {
        return f_ext ? spatial_dynamics::forward_dynamics_actuated(m, d, q, qd, tau, *f_ext)
                     : spatial_dynamics::forward_dynamics_actuated(m, d, q, qd, tau);
      },
      [](const Model<double>& m, Data<double>& d, RefinementWorkspace<double, DoubleDouble>& ws, const Vec& q,
         const Vec& qd, const Vec& tau, int max_iterations) -> const VectorX<double>& {
        return spatial_dynamics::aba_refined(m, d, ws, q, qd, tau, max_iterations);
      },
      [](const Model<double>& m, Data<double>& d, RefinementWorkspace<double, long double>& ws, const Vec& q,
         const Vec& qd, const Vec& tau, int max_iterations) -> const VectorX<double>& {
        return spatial_dynamics::aba_refined(m, d, ws, q, qd, tau, max_iterations);
      },
      [](const Model<double>& m, Data<double>& d, const Vec& q) -> const MatrixX<double>& {
        return spatial_dynamics::crba(m, d, q);
      },
      [](const Model<double>& m, Data<double>& d, const Vec& q, const Vec* qd) {
        if (qd) spatial_dynamics::forward_kinematics(m, d, q, *qd);
        else spatial_dynamics::forward_kinematics(m, d, q);
      },
      [](const Model<double>& m, Data<double>& d, const Vec& q, int frame,
         ReferenceFrame reference) -> const Matrix6X<double>& {
        return spatial_dynamics::frame_jacobian(m, d, q, frame, reference);
      },
      [](const Model<double>& m, BatchData<double, kDefaultBatchLanes<double>>& d, const ConstMatrixRef<double>& q,
         const ConstMatrixRef<double>& qd, const ConstMatrixRef<double>& qdd, MatrixRef<double> tau) {
        spatial_dynamics::rnea_batch(m, d, q, qd, qdd, tau);
      },
  };
  return table;
}

}  // namespace detail
}  // namespace spatial_dynamics
