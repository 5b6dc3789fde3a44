#include "model_bindings.hpp"

#include <pybind11/stl.h>

#include <fstream>
#include <map>
#include <set>
#include <algorithm>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "array_arguments.hpp"
#include "spatial_dynamics/reduction/reduce_model.hpp"
#include "spatial_dynamics/urdf/model_builder.hpp"

namespace spatial_dynamics {
namespace python {
namespace {

namespace py = pybind11;

bool is_readable_file(const std::string& path) {
  if (path.empty() || path.find('<') != std::string::npos) return false;  // URDF text, not a path
  std::ifstream file(path);
  return file.good();
}

std::shared_ptr<BoundModel> from_urdf(const std::string& path_or_text, bool floating_base) {
  ModelBuildOptions options;
  options.floating_base = floating_base;
  py::gil_scoped_release unlocked;
  return std::make_shared<BoundModel>(is_readable_file(path_or_text)
                                          ? build_model_from_urdf_file(path_or_text, options)
                                          : build_model_from_urdf_string(path_or_text, options));
}

/// {joint name: position} from a dict (or, for lock, a list of names, each held at 0).
std::map<std::string, double> positions_of(const py::handle& value, const char* what) {
  std::map<std::string, double> positions;
  if (value.is_none()) return positions;
  if (py::isinstance<py::dict>(value)) {
    for (const auto& item : py::reinterpret_borrow<py::dict>(value)) {
      if (!py::isinstance<py::str>(item.first))
        throw std::invalid_argument(std::string(what) + ": the keys must be joint names (str)");
      const std::string name = item.first.cast<std::string>();
      try {
        positions[name] = item.second.cast<double>();
      } catch (const py::cast_error&) {
        throw std::invalid_argument(std::string(what) + ": the position of joint '" + name + "' is not a number");
      }
    }
    return positions;
  }
  if (py::isinstance<py::str>(value)) throw std::invalid_argument(std::string(what) + ": expected joint names, not a str");
  for (const auto& name : value) {
    if (!py::isinstance<py::str>(name)) throw std::invalid_argument(std::string(what) + ": expected joint names (str)");
    positions[name.cast<std::string>()] = 0.0;
  }
  return positions;
}

std::vector<std::string> names_of(const py::handle& value, const char* what) {
  if (py::isinstance<py::str>(value)) throw std::invalid_argument(std::string(what) + ": expected a list of joint names, not a str");
  std::vector<std::string> names;
  for (const auto& name : value) {
    if (!py::isinstance<py::str>(name)) throw std::invalid_argument(std::string(what) + ": expected joint names (str)");
    names.push_back(name.cast<std::string>());
  }
  return names;
}

std::shared_ptr<BoundModel> reduced(const BoundModel& bound, const Scene& scene) {
  py::gil_scoped_release unlocked;
  return std::make_shared<BoundModel>(reduce_model(bound.model(), scene));
}

/// Keeps `joints`; every other 1-DoF joint is locked, at `positions` where given, else at 0.
std::shared_ptr<BoundModel> reduce_method(const BoundModel& bound, const py::handle& joints,
                                          const py::handle& positions) {
  Scene scene;
  scene.kept_joints = names_of(joints, "joints");
  scene.locked_positions = positions_of(positions, "positions");
  return reduced(bound, scene);
}

/// Locks `joints` ({name: position}, or names held at 0); every other joint is kept.
std::shared_ptr<BoundModel> lock_method(const BoundModel& bound, const py::handle& joints) {
  const Model<double>& model = bound.model();
  Scene scene;
  scene.locked_positions = positions_of(joints, "joints");
  for (int i = 1; i < model.nbodies(); ++i)
    if (!scene.locked_positions.count(model.joint_names[i])) scene.kept_joints.push_back(model.joint_names[i]);
  return reduced(bound, scene);
}

/// The model with some actuator terms replaced: each argument None (kept), a dict {joint name:
/// value} (each of the joint's coordinates), or one value per velocity coordinate.
std::shared_ptr<BoundModel> with_actuators_method(const BoundModel& bound, const py::handle& armature,
                                                  const py::handle& damping, const py::handle& friction,
                                                  const py::handle& friction_velocity) {
  Model<double> model = bound.model();
  const std::tuple<const char*, const py::handle*, std::vector<double>*> terms[] = {
      {"armature", &armature, &model.armature},
      {"damping", &damping, &model.damping},
      {"friction", &friction, &model.friction},
      {"friction_velocity", &friction_velocity, &model.friction_velocity}};
  for (const auto& [term, value, values] : terms) {
    if (value->is_none()) continue;
    if (py::isinstance<py::dict>(*value)) {
      for (const auto& item : py::reinterpret_borrow<py::dict>(*value)) {
        if (!py::isinstance<py::str>(item.first))
          throw std::invalid_argument(std::string(term) + ": the keys must be joint names (str)");
        const std::string name = item.first.cast<std::string>();
        if (!model.hasJoint(name)) throw std::invalid_argument(std::string(term) + ": unknown joint '" + name + "'");
        double x;
        try {
          x = item.second.cast<double>();
        } catch (const py::cast_error&) {
          throw std::invalid_argument(std::string(term) + " of joint '" + name + "' is not a number");
        }
        const Joint<double>& j = model.joints[model.jointBody(name)];
        std::fill_n(values->begin() + j.idx_v, j.nv, x);
      }
    } else {
      const InputArray array = checked_vector(term, *value, bound.velocityNames());
      values->assign(array.data(), array.data() + array.shape(0));
    }
  }
  model.finalize();  // a negative or non-finite term: std::invalid_argument naming the coordinate
  py::gil_scoped_release unlocked;
  return std::make_shared<BoundModel>(std::move(model));
}

std::vector<std::string> frame_names(const BoundModel& bound) {
  std::vector<std::string> names;
  for (const Frame<double>& frame : bound.model().frames) names.push_back(frame.name);
  return names;
}

}  // namespace

void def_model(py::class_<BoundModel, std::shared_ptr<BoundModel>>& cls) {
  cls.def_static("from_urdf", &from_urdf, py::arg("path_or_text"), py::arg("floating_base") = false,
                 "A model from a URDF file (when path_or_text names an existing file) or URDF text. With\n"
                 "floating_base, a free root joint comes first: q = (x y z qx qy qz qw ...), qd = (w; v ...).");
  cls.def_property_readonly("name", [](const BoundModel& b) { return b.model().name; });
  cls.def_property_readonly("nq", [](const BoundModel& b) { return b.model().nq; });
  cls.def_property_readonly("nv", [](const BoundModel& b) { return b.model().nv; });
  cls.def_property_readonly("floating_base", [](const BoundModel& b) { return b.model().floating_base; });
  cls.def_property_readonly("joint_names", &BoundModel::velocityNames,
                            "The names of the velocity coordinates, in the model's order (one per entry of qd, tau).");
  cls.def_property_readonly("position_names", &BoundModel::positionNames, "One name per entry of q.");
  cls.def_property_readonly("frame_names", &frame_names, "Every link of the URDF, a frame of the model.");
  cls.def("reduce", &reduce_method, py::arg("joints"), py::arg("positions") = py::none(),
          "A new model keeping `joints`; every other joint is locked at positions[name] (default 0).");
  cls.def("with_actuators", &with_actuators_method, py::arg("armature") = py::none(), py::arg("damping") = py::none(),
          py::arg("friction") = py::none(), py::arg("friction_velocity") = py::none(),
          "A new model with actuator terms: each None (kept), {joint name: value} (each of the joint's\n"
          "coordinates) or one value per velocity coordinate. armature (kg m^2 or kg) is part of M in every\n"
          "algorithm; damping and Coulomb friction enter inverse_dynamics_actuated and forward_dynamics_actuated.");
  using Term = std::vector<double> Model<double>::*;
  for (const auto& [name, term] : {std::pair<const char*, Term>{"armature", &Model<double>::armature},
                                   {"damping", &Model<double>::damping},
                                   {"friction", &Model<double>::friction},
                                   {"friction_velocity", &Model<double>::friction_velocity}})
    cls.def_property_readonly(name, [term = term](const BoundModel& b) {
      const std::vector<double>& v = b.model().*term;
      return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
    });
  cls.def("lock", &lock_method, py::arg("joints"),
          "A new model with `joints` locked ({name: position}, or names locked at 0); the others are kept.");
  cls.def("__repr__", [](const BoundModel& b) {
    return "<spatial_dynamics.dynamics.Model '" + b.model().name + "' nq=" + std::to_string(b.model().nq) +
           " nv=" + std::to_string(b.model().nv) + ">";
  });
}

}  // namespace python
}  // namespace spatial_dynamics
