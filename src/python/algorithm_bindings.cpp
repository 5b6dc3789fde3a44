// The algorithms as methods of Model: arguments checked with the GIL held, then the library's
// compiled double instances run in a workspace of the model's pool with the GIL released, and
// their results are copied into new numpy arrays.
#include "algorithm_bindings.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "array_arguments.hpp"
#include "external_wrenches.hpp"
#include "spatial_dynamics/algorithms.hpp"
#include "spatial_dynamics/algorithms/aba_refined.hpp"

namespace spatial_dynamics {
namespace python {
namespace {

using Vec = Eigen::Map<const Eigen::VectorXd>;

/// A call of the shape f(model, data, q, qd, x[, f_ext]) → nv-vector (rnea and the actuated
/// inverse and forward dynamics): x named `x_name`, external wrenches as rnea's.
template <class Call>
py::array_t<double> state_call(const BoundModel& bound, const py::handle& q, const py::handle& qd, const py::handle& x,
                               const char* x_name, const py::handle& external_wrenches, Call call) {
  const Model<double>& model = bound.model();
  const InputArray q_in = checked_vector("q", q, bound.positionNames());
  const InputArray qd_in = checked_vector("qd", qd, bound.velocityNames());
  const InputArray x_in = checked_vector(x_name, x, bound.velocityNames());
  BoundModel::Lease ws = bound.acquire();
  const bool with_wrenches = decode_external_wrenches(model, external_wrenches, ws->f_ext);
  py::array_t<double> out = new_vector(model.nv);
  double* result = out.mutable_data();
  const Vec q_v = view(q_in), qd_v = view(qd_in), x_v = view(x_in);
  {
    py::gil_scoped_release unlocked;
    copy_into(result, call(model, ws->data, q_v, qd_v, x_v, with_wrenches ? &ws->f_ext : nullptr));
  }
  return out;
}

using Wrenches = const std::vector<ForceVector<double>>*;

py::array_t<double> rnea_method(const BoundModel& bound, const py::handle& q, const py::handle& qd,
                                const py::handle& qdd, const py::handle& external_wrenches) {
  return state_call(bound, q, qd, qdd, "qdd", external_wrenches,
                    [](const Model<double>& m, Data<double>& d, const Vec& q, const Vec& qd, const Vec& qdd,
                       Wrenches f) -> const Eigen::VectorXd& { return f ? rnea(m, d, q, qd, qdd, *f) : rnea(m, d, q, qd, qdd); });
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

py::array_t<double> inverse_dynamics_actuated_method(const BoundModel& bound, const py::handle& q, const py::handle& qd,
                                                     const py::handle& qdd, const py::handle& external_wrenches) {
  return state_call(bound, q, qd, qdd, "qdd", external_wrenches,
                    [](const Model<double>& m, Data<double>& d, const Vec& q, const Vec& qd, const Vec& qdd,
                       Wrenches f) -> const Eigen::VectorXd& {
                      return f ? inverse_dynamics_actuated(m, d, q, qd, qdd, *f) : inverse_dynamics_actuated(m, d, q, qd, qdd);
                    });
}

py::array_t<double> forward_dynamics_actuated_method(const BoundModel& bound, const py::handle& q, const py::handle& qd,
                                                     const py::handle& tau, const py::handle& external_wrenches) {
  return state_call(bound, q, qd, tau, "tau", external_wrenches,
                    [](const Model<double>& m, Data<double>& d, const Vec& q, const Vec& qd, const Vec& tau,
                       Wrenches f) -> const Eigen::VectorXd& {
                      return f ? forward_dynamics_actuated(m, d, q, qd, tau, *f) : forward_dynamics_actuated(m, d, q, qd, tau);
                    });
}

py::array_t<double> actuator_forces_method(const BoundModel& bound, const py::handle& qd) {
  const Model<double>& model = bound.model();
  const InputArray qd_in = checked_vector("qd", qd, bound.velocityNames());
  py::array_t<double> out = new_vector(model.nv);
  double* result = out.mutable_data();
  const Vec qd_v = view(qd_in);
  BoundModel::Lease ws = bound.acquire();
  copy_into(result, actuator_forces(model, ws->data, qd_v));
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
  cls.def("inverse_dynamics_actuated", &inverse_dynamics_actuated_method, py::arg("q"), py::arg("qd"), py::arg("qdd"),
          py::arg("external_wrenches") = py::none(),
          "rnea plus the actuators' damping and friction forces (armature is in rnea already): what the\n"
          "actuators must produce.");
  cls.def("forward_dynamics_actuated", &forward_dynamics_actuated_method, py::arg("q"), py::arg("qd"), py::arg("tau"),
          py::arg("external_wrenches") = py::none(),
          "qdd from (M + diag(armature)) qdd = tau - h - actuator_forces(qd).");
  cls.def("actuator_forces", &actuator_forces_method, py::arg("qd"),
          "damping * qd + friction * clip(qd / friction_velocity, -1, 1), per velocity coordinate.");
  cls.def("frame_jacobian", &frame_jacobian_method, py::arg("frame"), py::arg("q"),
          py::arg("reference") = "root_aligned",
          "The 6 x nv Jacobian (angular rows first) of a frame's spatial velocity, about the frame's origin, in\n"
          "the root's axes ('root_aligned') or the frame's own ('local').");
}

}  // namespace python
}  // namespace spatial_dynamics
