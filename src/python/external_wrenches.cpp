#include "external_wrenches.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "array_arguments.hpp"

namespace spatial_dynamics {
namespace python {

bool decode_external_wrenches(const Model<double>& model, const py::handle& wrenches,
                              std::vector<ForceVector<double>>& f_ext) {
  std::fill(f_ext.begin(), f_ext.end(), ForceVector<double>::Zero());
  if (wrenches.is_none()) return false;
  if (!py::isinstance<py::dict>(wrenches))
    throw std::invalid_argument("external_wrenches must be a dict {frame name: (torque; force) 6-vector}");
  static const std::vector<std::string> components = {"torque x", "torque y", "torque z",
                                                      "force x",  "force y",  "force z"};
  bool any = false;
  for (const auto& item : py::reinterpret_borrow<py::dict>(wrenches)) {
    if (!py::isinstance<py::str>(item.first))
      throw std::invalid_argument("external_wrenches: the keys must be frame names (str)");
    const std::string frame_name = item.first.cast<std::string>();
    if (!model.hasFrame(frame_name))
      throw std::invalid_argument("external_wrenches: unknown frame '" + frame_name + "' (not a link of the model)");
    const std::string field = "external_wrenches['" + frame_name + "']";
    const InputArray w = checked_vector(field.c_str(), item.second, components);
    const ForceVector<double> f(Eigen::Vector3d(w.data()[0], w.data()[1], w.data()[2]),
                                Eigen::Vector3d(w.data()[3], w.data()[4], w.data()[5]));
    const Frame<double>& frame = model.frames[model.frameIndex(frame_name)];
    f_ext[frame.body] += frame.X_frame_body.applyInverse(f);  // f_B = ^FX_Bᵀ f_F, as the node
    any = true;
  }
  return any;
}

}  // namespace python
}  // namespace spatial_dynamics
