#include "bound_model.hpp"

namespace spatial_dynamics {
namespace python {

BoundModel::BoundModel(Model<double> model)
    : model_(std::move(model)), position_names_(model_.positionNames()), velocity_names_(model_.velocityNames()) {}

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
