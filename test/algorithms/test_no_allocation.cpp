// No algorithm call allocates: global operator new is counted while the algorithms run.
#include <gtest/gtest.h>

// The replacement operators below pair malloc/aligned_alloc with free by design.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

#include <atomic>
#include <cstdlib>
#include <new>

#include "spatial_dynamics/algorithms/aba_refined.hpp"
#include "spatial_dynamics/reference/high_precision.hpp"
#include "test_utils.hpp"

namespace {
std::atomic<long> g_allocations{0};
}

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void* operator new(std::size_t size, std::align_val_t alignment) {
  ++g_allocations;
  const std::size_t a = static_cast<std::size_t>(alignment);
  if (void* p = std::aligned_alloc(a, (size + a - 1) / a * a)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size, std::align_val_t alignment) { return operator new(size, alignment); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace sd = spatial_dynamics;

class NoAllocation : public ::testing::TestWithParam<bool> {};

TEST_P(NoAllocation, AlgorithmCallsDoNotAllocate) {
  for (const std::string& file : sd_test::robot_files()) {
    sd::ModelBuildOptions options;
    options.floating_base = GetParam();
    const sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path(file), options);
    sd::Data<double> data(model);
    sd::RefinementWorkspace<double> refinement(model);
    std::mt19937 rng(3);
    const Eigen::VectorXd q = sd_test::random_configuration(model, rng);
    const Eigen::VectorXd qd = sd_test::random_vector(model.nv, rng);
    const Eigen::VectorXd qdd = sd_test::random_vector(model.nv, rng);
    const std::vector<sd::ForceVector<double>> f_ext(model.nbodies(), sd::ForceVector<double>(Eigen::Matrix<double, 6, 1>::Ones()));
    const int frame = static_cast<int>(model.frames.size()) - 1;

    // The counter itself works: a direct call of operator new is counted (and cannot be elided).
    const long before_sanity = g_allocations;
    ::operator delete(::operator new(64));
    EXPECT_EQ(g_allocations - before_sanity, 1);

    const long before = g_allocations;
    sd::rnea(model, data, q, qd, qdd);
    sd::rnea(model, data, q, qd, qdd, f_ext);
    sd::aba(model, data, q, qd, qdd);
    sd::aba(model, data, q, qd, qdd, f_ext);
    sd::crba(model, data, q);
    sd::gravity_torques(model, data, q);
    sd::nonlinear_effects(model, data, q, qd);
    sd::forward_kinematics(model, data, q, qd);
    sd::frame_jacobian(model, data, q, frame, sd::ReferenceFrame::RootAligned);
    sd::kinetic_energy(model, data, q, qd);
    sd::total_momentum(model, data, q, qd);
    sd::aba_refined(model, data, refinement, q, qd, qdd);
    EXPECT_EQ(g_allocations - before, 0) << file << (GetParam() ? " (floating base)" : " (fixed base)");
  }
}

INSTANTIATE_TEST_SUITE_P(Base, NoAllocation, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? std::string("Floating") : std::string("Fixed"); });

TEST(NoAllocation, RefinementWithFloat128ResidualsDoesNotAllocate) {
  // q̈ a thousand times smaller than the forces: the long double residual cannot resolve the
  // result, so the call goes on with float128 residuals (checked through fine.iterations).
  const sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path("double_pendulum.urdf"));
  sd::Data<double> data(model);
  sd::RefinementWorkspace<double> ws(model);
  sd::RefinementWorkspace<double, sd::Quad> fine(model);
  std::mt19937 rng(5);
  const Eigen::VectorXd q = sd_test::random_configuration(model, rng);
  const Eigen::VectorXd qd = sd_test::random_vector(model.nv, rng);
  const Eigen::VectorXd tau = sd::rnea(model, data, q, qd, sd_test::random_vector(model.nv, rng, 1e-4));
  const long before = g_allocations;
  sd::aba_refined(model, data, ws, fine, q, qd, tau);
  EXPECT_EQ(g_allocations - before, 0);
  EXPECT_GE(fine.iterations, 1);
}
