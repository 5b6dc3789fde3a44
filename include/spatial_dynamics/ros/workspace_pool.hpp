// The buffers a service call or a joint state works in, pooled per scene: a served scene owns its
// pool, a call leases one workspace for its duration, and as many exist as calls ever ran at once
// (one per serving thread). A workspace is allocated the first time the pool is short of one,
// never per call; it dies with its scene, so a rebuilt scene starts a pool of its own.
#pragma once

#include <memory>
#include <mutex>
#include <vector>

#include "spatial_dynamics/model/batch_data.hpp"
#include "spatial_dynamics/model/contact_data.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/ros/joint_state_cache.hpp"

namespace spatial_dynamics {

/// One call's buffers for one scene's model (Data is allocated once per model).
struct Workspace {
  explicit Workspace(const Model<double>& model)
      : data(model), batch(model), f_ext(model.nbodies(), ForceVector<double>::Zero()) {}

  Data<double> data;
  BatchData<double> batch;  // trajectories: several states per RNEA pass
  JointStateCache::Snapshot state;
  std::vector<int> indices;
  Eigen::VectorXd q, qd, x;
  Eigen::VectorXd joint_values;                     // one request array, before it goes into q, q̇ or x
  ContactSet<double> request_contacts;              // a request's own contacts (contact_frames)
  std::unique_ptr<ContactData<double>> contact_data;  // for contact_data_set (its frames and kinds)
  ContactSet<double> contact_data_set;
  std::vector<ForceVector<double>> f_ext;
  Eigen::MatrixXd trajectory_q, trajectory_qd, trajectory_qdd, trajectory_tau;  // one column per point

  /// The contact work space for `contacts` on `model` (ContactData is laid out for its set's frames
  /// and kinds): reallocated only when they change.
  ContactData<double>& contactData(const Model<double>& model, const ContactSet<double>& contacts) {
    bool same = contact_data && contact_data->J.cols() == model.nv && contact_data_set.size() == contacts.size();
    for (std::size_t k = 0; same && k < contacts.size(); ++k)
      same = contact_data_set.contacts[k].frame == contacts.contacts[k].frame &&
             contact_data_set.contacts[k].kind == contacts.contacts[k].kind;
    if (!same) {
      contact_data = std::make_unique<ContactData<double>>(model, contacts);
      contact_data_set = contacts;
    }
    return *contact_data;
  }
};

class WorkspacePool {
 public:
  /// A workspace held for one call; back to the pool when the lease ends.
  class Lease {
   public:
    Lease(const WorkspacePool& pool, std::unique_ptr<Workspace> workspace)
        : pool_(&pool), workspace_(std::move(workspace)) {}
    Lease(Lease&&) = default;
    Lease& operator=(Lease&&) = delete;
    ~Lease() {
      if (workspace_) pool_->release(std::move(workspace_));
    }
    Workspace& operator*() const { return *workspace_; }
    Workspace* operator->() const { return workspace_.get(); }

   private:
    const WorkspacePool* pool_;
    std::unique_ptr<Workspace> workspace_;
  };

  /// A free workspace, or a new one for `model` (the scene's) when every one is leased.
  Lease acquire(const Model<double>& model) const {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!free_.empty()) {
        std::unique_ptr<Workspace> workspace = std::move(free_.back());
        free_.pop_back();
        return Lease(*this, std::move(workspace));
      }
    }
    return Lease(*this, std::make_unique<Workspace>(model));
  }

  /// How many workspaces exist and are not leased (for tests).
  std::size_t freeCount() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return free_.size();
  }

 private:
  void release(std::unique_ptr<Workspace> workspace) const {
    std::lock_guard<std::mutex> lock(mutex_);
    free_.push_back(std::move(workspace));
  }

  mutable std::mutex mutex_;
  mutable std::vector<std::unique_ptr<Workspace>> free_;
};

}  // namespace spatial_dynamics
