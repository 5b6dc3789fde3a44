// The algorithms as methods of Model: arguments checked with the GIL held, then the library's
// compiled double instances run in a workspace of the model's pool with the GIL released, and
// their results are copied into new numpy arrays.
#include "algorithm_bindings.hpp"

#include <stdexcept>
#include <string>

#include "array_arguments.hpp"
#include "external_wrenches.hpp"
#include "spatial_dynamics/algorithms.hpp"
#include "spatial_dynamics/algorithms/aba_refined.hpp"

namespace spatial_dynamics {
namespace python {
namespace {

using Vec = Eigen::Map<const Eigen::VectorXd>;

py::array_t<double> rnea_method(const BoundModel& bound, const py::handle& q, const py::handle& qd,
                                const py::handle& qdd, const py::handle& external_wrenches) {
  const Model<double>& model = bound.model();
  const InputArray q_in = checked_vector("q", q, bound.positionNames());
  const InputArray qd_in = checked_vector("qd", qd, bound.velocityNames());
  const InputArray qdd_in = checked_vector("qdd", qdd, bound.velocityNames());
  BoundModel::Lease ws = bound.acquire();
  const bool with_wrenches = decode_external_wrenches(model, external_wrenches, ws->f_ext);
  py::array_t<double> out = new_vector(model.nv);
  double* result = out.mutable_data();
  const Vec q_v = view(q_in), qd_v = view(qd_in), qdd_v = view(qdd_in);
  {
    py::gil_scoped_release unlocked;
    copy_into(result, with_wrenches ? rnea(model, ws->data, q_v, qd_v, qdd_v, ws->f_ext)
                                    : rnea(model, ws->data, q_v, qd_v, qdd_v));
  }
  return out;
}

py::array_t<double> aba_method(const BoundModel& bound, const py::handle& q, const py::handle& qd,
                               const py::handle& tau) {
  const Model<double>& model = bound.model();
  const InputArray q_in = checked_vector("q", q, bound.positionNames());
  const InputArray qd_in = checked_vector("qd", qd, bound.velocityNames());
  const InputArray tau_in = checked_vector("tau", tau, bound.velocityNames());
  py::array_t<double> out = new_vector(model.nv);
  double* result = out.mutable_data();
  const Vec q_v = view(q_in), qd_v = view(qd_in), tau_v = view(tau_in);
  {
    py::gil_scoped_release unlocked;
    BoundModel::Lease ws = bound.acquire();
    copy_into(result, aba(model, ws->data, q_v, qd_v, tau_v));
  }
  return out;
}

py::array_t<double> aba_refined_method(const BoundModel& bound, const py::handle& q, const py::handle& qd,
                                       const py::handle& tau, int max_iterations) {
  const Model<double>& model = bound.model();
  const InputArray q_in = checked_vector("q", q, bound.positionNames());
  const InputArray qd_in = checked_vector("qd", qd, bound.velocityNames());
  const InputArray tau_in = checked_vector("tau", tau, bound.velocityNames());
  if (max_iterations < 0) throw std::invalid_argument("max_iterations is negative");
  py::array_t<double> out = new_vector(model.nv);
  double* result = out.mutable_data();
  const Vec q_v = view(q_in), qd_v = view(qd_in), tau_v = view(tau_in);
  {
    py::gil_scoped_release unlocked;
    BoundModel::Lease ws = bound.acquire();
    if (!ws->refinement) ws->refinement = std::make_unique<RefinementWorkspace<double>>(model);
    copy_into(result, aba_refined(model, ws->data, *ws->refinement, q_v, qd_v, tau_v, max_iterations));
  }
  return out;
}

py::array_t<double> crba_method(const BoundModel& bound, const py::handle& q) {
  const Model<double>& model = bound.model();
  const InputArray q_in = checked_vector("q", q, bound.positionNames());
  py::array_t<double> out = new_matrix(model.nv, model.nv);
  double* result = out.mutable_data();
  const Vec q_v = view(q_in);
  {
    py::gil_scoped_release unlocked;
    BoundModel::Lease ws = bound.acquire();
    copy_matrix_into(result, crba(model, ws->data, q_v));
  }
  return out;
}

py::array_t<double> gravity_torques_method(const BoundModel& bound, const py::handle& q) {
  const Model<double>& model = bound.model();
  const InputArray q_in = checked_vector("q", q, bound.positionNames());
  py::array_t<double> out = new_vector(model.nv);
  double* result = out.mutable_data();
  const Vec q_v = view(q_in);
  {
    py::gil_scoped_release unlocked;
    BoundModel::Lease ws = bound.acquire();
    copy_into(result, gravity_torques(model, ws->data, q_v));
  }
  return out;
}

py::array_t<double> nonlinear_effects_method(const BoundModel& bound, const py::handle& q, const py::handle& qd) {
  const Model<double>& model = bound.model();
  const InputArray q_in = checked_vector("q", q, bound.positionNames());
  const InputArray qd_in = checked_vector("qd", qd, bound.velocityNames());
  py::array_t<double> out = new_vector(model.nv);
  double* result = out.mutable_data();
  const Vec q_v = view(q_in), qd_v = view(qd_in);
  {
    py::gil_scoped_release unlocked;
    BoundModel::Lease ws = bound.acquire();
    copy_into(result, nonlinear_effects(model, ws->data, q_v, qd_v));
  }
  return out;
}

py::array_t<double> frame_jacobian_method(const BoundModel& bound, const std::string& frame, const py::handle& q,
                                          const std::string& reference) {
  const Model<double>& model = bound.model();
  ReferenceFrame ref;
  if (reference == "root_aligned") {
    ref = ReferenceFrame::RootAligned;
  } else if (reference == "local") {
    ref = ReferenceFrame::Local;
  } else {
    throw std::invalid_argument("unknown reference '" + reference + "'; expected 'root_aligned' or 'local'");
  }
  if (!model.hasFrame(frame)) throw std::invalid_argument("unknown frame '" + frame + "'");
  const int frame_index = model.frameIndex(frame);
  const InputArray q_in = checked_vector("q", q, bound.positionNames());
  py::array_t<double> out = new_matrix(6, model.nv);
  double* result = out.mutable_data();
  const Vec q_v = view(q_in);
  {
    py::gil_scoped_release unlocked;
    BoundModel::Lease ws = bound.acquire();
    copy_matrix_into(result, frame_jacobian(model, ws->data, q_v, frame_index, ref));
  }
  return out;
}

}  // namespace

void def_algorithms(py::class_<BoundModel, std::shared_ptr<BoundModel>>& cls) {
  cls.def("rnea", &rnea_method, py::arg("q"), py::arg("qd"), py::arg("qdd"), py::arg("external_wrenches") = py::none(),
          "Inverse dynamics: the joint forces tau (nv) that give accelerations qdd at (q, qd) under gravity.\n"
          "external_wrenches: {frame or link name: (torque x, y, z, force x, y, z)}, each in that frame's\n"
          "coordinates about its origin, acting on the robot.");
  cls.def("aba", &aba_method, py::arg("q"), py::arg("qd"), py::arg("tau"),
          "Forward dynamics by the articulated-body algorithm: the accelerations qdd (nv).");
  cls.def("aba_refined", &aba_refined_method, py::arg("q"), py::arg("qd"), py::arg("tau"),
          py::arg("max_iterations") = 8,
          "Forward dynamics with iterative refinement in double-double residuals (ill-conditioned mass matrices).");
  cls.def("crba", &crba_method, py::arg("q"), "The joint-space mass matrix M(q) (nv x nv).");
  cls.def("gravity_torques", &gravity_torques_method, py::arg("q"), "g(q) = ID(q, 0, 0).");
  cls.def("nonlinear_effects", &nonlinear_effects_method, py::arg("q"), py::arg("qd"),
          "C(q, qd) qd + g(q) = ID(q, qd, 0).");
  cls.def("frame_jacobian", &frame_jacobian_method, py::arg("frame"), py::arg("q"),
          py::arg("reference") = "root_aligned",
          "The 6 x nv Jacobian (angular rows first) of a frame's spatial velocity, about the frame's origin, in\n"
          "the root's axes ('root_aligned') or the frame's own ('local').");
}

}  // namespace python
}  // namespace spatial_dynamics
