// WorkspacePool without a master: a lease is one workspace for one call, returned when the lease
// ends and handed to the next call (no allocation per call), and concurrent calls never share one;
// as many workspaces exist as leases were ever held at once.
#include <gtest/gtest.h>

#include <atomic>
#include <set>
#include <thread>
#include <vector>

#include "spatial_dynamics/algorithms.hpp"
#include "spatial_dynamics/ros/workspace_pool.hpp"
#include "spatial_dynamics/urdf/model_builder.hpp"
#include "test_utils.hpp"

namespace sd = spatial_dynamics;

TEST(WorkspacePool, ALeaseEndedIsTheNextCallsWorkspace) {
  const sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path("panda.urdf"));
  const sd::WorkspacePool pool;
  const sd::Workspace* first = nullptr;
  {
    const sd::WorkspacePool::Lease lease = pool.acquire(model);
    first = &*lease;
    EXPECT_EQ(lease->data.tau.size(), model.nv);
    EXPECT_EQ(static_cast<int>(lease->f_ext.size()), model.nbodies());
    EXPECT_EQ(pool.freeCount(), 0u);
  }
  EXPECT_EQ(pool.freeCount(), 1u);
  for (int call = 0; call < 5; ++call) {
    const sd::WorkspacePool::Lease lease = pool.acquire(model);
    EXPECT_EQ(&*lease, first) << "call " << call << " was given a new workspace";
  }
  {  // two leases at once: two workspaces, then both kept
    const sd::WorkspacePool::Lease a = pool.acquire(model), b = pool.acquire(model);
    EXPECT_NE(&*a, &*b);
  }
  EXPECT_EQ(pool.freeCount(), 2u);
}

TEST(WorkspacePool, ConcurrentCallsNeverShareAWorkspace) {
  const sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path("panda.urdf"));
  const sd::WorkspacePool pool;
  constexpr int kThreads = 4, kCalls = 2000;
  std::atomic<int> shared{0};
  std::vector<std::thread> threads;
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(model.nq, -1.0, 1.0), zero = Eigen::VectorXd::Zero(model.nv);
  sd::Data<double> reference_data(model);
  const Eigen::VectorXd expected = sd::gravity_torques(model, reference_data, q);
  std::atomic<int> wrong{0};
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&] {
      for (int call = 0; call < kCalls; ++call) {
        const sd::WorkspacePool::Lease lease = pool.acquire(model);
        // A workspace held by another call at the same time would see this mark changed.
        lease->indices.assign(1, call);
        const Eigen::VectorXd& tau = sd::gravity_torques(model, lease->data, q);
        if (!(tau == expected)) ++wrong;
        if (lease->indices.size() != 1 || lease->indices[0] != call) ++shared;
      }
    });
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(shared.load(), 0);
  EXPECT_EQ(wrong.load(), 0);
  EXPECT_GE(pool.freeCount(), 1u);
  EXPECT_LE(pool.freeCount(), static_cast<std::size_t>(kThreads));
}
