#include "bound_model.hpp"

namespace spatial_dynamics {
namespace python {

BoundModel::BoundModel(Model<double> model) : model_(std::move(model)), velocity_names_(model_.velocityNames()) {
  position_names_.assign(model_.nq, std::string());
  for (int i = 1; i < model_.nbodies(); ++i) {
    const Joint<double>& j = model_.joints[i];
    if (j.coupled) continue;  // shares its master's coordinate
    if (j.type == JointType::Free) {
      const char* parts[] = {"x", "y", "z", "qx", "qy", "qz", "qw"};
      for (int k = 0; k < 7; ++k) position_names_[j.idx_q + k] = model_.joint_names[i] + "/" + parts[k];
    } else {
      position_names_[j.idx_q] = model_.joint_names[i];
    }
  }
}

BoundModel::Lease BoundModel::acquire() const {
  {
    std::lock_guard<std::mutex> lock(pool_mutex_);
    if (!pool_.empty()) {
      std::unique_ptr<Workspace> ws = std::move(pool_.back());
      pool_.pop_back();
      return Lease(*this, std::move(ws));
    }
  }
  return Lease(*this, std::make_unique<Workspace>(model_));  // allocated outside the lock
}

void BoundModel::release(std::unique_ptr<Workspace> ws) const {
  std::lock_guard<std::mutex> lock(pool_mutex_);
  pool_.push_back(std::move(ws));
}

}  // namespace python
}  // namespace spatial_dynamics
