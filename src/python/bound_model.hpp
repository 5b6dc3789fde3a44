// The model the Python module hands out: an immutable Model<double> shared by every copy of the
// Python object, the names of its coordinates, and a pool of workspaces (Data and the refinement
// buffers), one taken by each call for its duration, so that calls from several threads never
// share one. The pool grows to the number of threads that ever called at once.
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "spatial_dynamics/algorithms/aba_refined.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"

namespace spatial_dynamics {
namespace python {

/// What one call computes in: allocated once per model and thread count, reused.
struct Workspace {
  explicit Workspace(const Model<double>& model) : data(model), f_ext(model.nbodies(), ForceVector<double>::Zero()) {}
  Data<double> data;
  std::vector<ForceVector<double>> f_ext;                      // body forces of external wrenches
  std::unique_ptr<RefinementWorkspace<double>> refinement;     // aba_refined's, made at its first use
};

class BoundModel {
 public:
  explicit BoundModel(Model<double> model);

  const Model<double>& model() const { return model_; }
  /// One name per entry of q: a joint's name, "<root>/x" ... "<root>/qw" for a free root.
  const std::vector<std::string>& positionNames() const { return position_names_; }
  /// One name per entry of q̇ (Model::velocityNames()).
  const std::vector<std::string>& velocityNames() const { return velocity_names_; }

  /// A workspace of this model for one call; it goes back to the pool when the handle is destroyed.
  class Lease {
   public:
    Lease(const BoundModel& owner, std::unique_ptr<Workspace> ws) : owner_(owner), ws_(std::move(ws)) {}
    Lease(const Lease&) = delete;
    Lease& operator=(const Lease&) = delete;
    ~Lease() { owner_.release(std::move(ws_)); }
    Workspace& operator*() const { return *ws_; }
    Workspace* operator->() const { return ws_.get(); }

   private:
    const BoundModel& owner_;
    std::unique_ptr<Workspace> ws_;
  };
  Lease acquire() const;

 private:
  void release(std::unique_ptr<Workspace> ws) const;

  const Model<double> model_;
  std::vector<std::string> position_names_, velocity_names_;
  mutable std::mutex pool_mutex_;
  mutable std::vector<std::unique_ptr<Workspace>> pool_;
};

}  // namespace python
}  // namespace spatial_dynamics
