// No algorithm call allocates: global operator new is counted while the algorithms run.
#include <gtest/gtest.h>

#include "allocation_counter.hpp"
#include "spatial_dynamics/algorithms/aba_refined.hpp"
#include "spatial_dynamics/algorithms/centroidal.hpp"
#include "spatial_dynamics/algorithms/contact_dynamics.hpp"
#include "spatial_dynamics/algorithms/regressor.hpp"
#include "spatial_dynamics/estimation/external_wrench.hpp"
#include "spatial_dynamics/estimation/momentum_observer.hpp"
#include "spatial_dynamics/reference/high_precision.hpp"
#include "test_utils.hpp"

namespace sd = spatial_dynamics;

class NoAllocation : public ::testing::TestWithParam<bool> {};

TEST_P(NoAllocation, AlgorithmCallsDoNotAllocate) {
  for (const std::string& file : sd_test::robot_files()) {
    sd::ModelBuildOptions options;
    options.floating_base = GetParam();
    const sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path(file), options);
    sd::Data<double> data(model);
    sd::RefinementWorkspace<double, long double> refinement(model);
    sd::RefinementWorkspace<double, sd::DoubleDouble> refinement_double_double(model);
    std::mt19937 rng(3);
    const Eigen::VectorXd q = sd_test::random_configuration(model, rng);
    const Eigen::VectorXd qd = sd_test::random_vector(model.nv, rng);
    const Eigen::VectorXd qdd = sd_test::random_vector(model.nv, rng);
    const std::vector<sd::ForceVector<double>> f_ext(model.nbodies(), sd::ForceVector<double>(Eigen::Matrix<double, 6, 1>::Ones()));
    const int frame = static_cast<int>(model.frames.size()) - 1;
    const std::string& frame_name = model.frames[frame].name;
    sd::MomentumObserver<double> observer(model, Eigen::VectorXd::Constant(model.nv, 50.0));
    const sd::ContactSet<double> contacts(model, {model.frames[1].name, frame_name}, {"surface", "point"});
    sd::ContactData<double> contact_data(model, contacts);
    // Sets that take the decompositions instead of the small Cholesky factors: three rows cannot
    // balance a floating base; two surfaces hold more rows than a fixed arm has joints (K singular).
    const sd::ContactSet<double> one_point(model, {frame_name}, {"point"});
    sd::ContactData<double> one_point_data(model, one_point);
    const sd::ContactSet<double> two_surfaces(model, {model.frames[1].name, frame_name}, {"surface", "surface"});
    sd::ContactData<double> two_surfaces_data(model, two_surfaces);

    // The counter itself works: a direct call of operator new is counted (and cannot be elided).
    const long before_sanity = bench::allocation_count();
    ::operator delete(::operator new(64));
    EXPECT_EQ(bench::allocation_count() - before_sanity, 1);

    const long before = bench::allocation_count();
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
    sd::aba_refined(model, data, refinement_double_double, q, qd, qdd);
    sd::coriolis_matrix(model, data, q, qd);
    sd::generalized_momentum(model, data, q, qd);
    sd::external_wrench(model, data, q, frame, qdd);
    sd::joint_torque_regressor(model, data, q, qd, qdd);
    sd::payload_regressor(model, data, q, qd, qdd, frame_name);
    sd::contact_jacobian(model, data, contacts, contact_data, q, qd);
    sd::inverse_dynamics_with_contacts(model, data, contacts, contact_data, q, qd, qdd);
    sd::forward_dynamics_with_contacts(model, data, contacts, contact_data, q, qd, qdd);
    sd::inverse_dynamics_with_contacts(model, data, one_point, one_point_data, q, qd, qdd);
    sd::forward_dynamics_with_contacts(model, data, one_point, one_point_data, q, qd, qdd);
    sd::inverse_dynamics_with_contacts(model, data, two_surfaces, two_surfaces_data, q, qd, qdd);
    sd::forward_dynamics_with_contacts(model, data, two_surfaces, two_surfaces_data, q, qd, qdd);
    sd::inverse_dynamics_with_contacts(model, data, contacts, contact_data, q, qd, qdd, f_ext);
    sd::forward_dynamics_with_contacts(model, data, contacts, contact_data, q, qd, qdd, f_ext);
    sd::center_of_mass(model, data, q);
    sd::center_of_mass_velocity(model, data, q, qd);
    sd::center_of_mass_jacobian(model, data, q);
    sd::centroidal_momentum(model, data, q, qd);
    observer.update(q, qd, qdd, 1e-3);  // the first update after construction, then a second
    observer.update(q, qd, qdd, 1e-3);
    observer.tare();
    EXPECT_EQ(bench::allocation_count() - before, 0) << file << (GetParam() ? " (floating base)" : " (fixed base)");
  }
}

INSTANTIATE_TEST_SUITE_P(Base, NoAllocation, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? std::string("Floating") : std::string("Fixed"); });

template <class W>
void expect_escalation_without_allocation(double qdd_scale) {
  // q̈ much smaller than the forces (1e-4 for the long double residual, 1e-8 for the finer
  // double-double one): the wide residual cannot resolve the result, so the call goes on with
  // float128 residuals (checked through fine.iterations).
  const sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path("double_pendulum.urdf"));
  sd::Data<double> data(model);
  sd::RefinementWorkspace<double, W> ws(model);
  sd::RefinementWorkspace<double, sd::Quad> fine(model);
  std::mt19937 rng(5);
  const Eigen::VectorXd q = sd_test::random_configuration(model, rng);
  const Eigen::VectorXd qd = sd_test::random_vector(model.nv, rng);
  const Eigen::VectorXd tau = sd::rnea(model, data, q, qd, sd_test::random_vector(model.nv, rng, qdd_scale));
  const long before = bench::allocation_count();
  sd::aba_refined(model, data, ws, fine, q, qd, tau);
  EXPECT_EQ(bench::allocation_count() - before, 0);
  EXPECT_GE(fine.iterations, 1);
}

TEST(NoAllocation, RefinementWithFloat128ResidualsDoesNotAllocate) {
  expect_escalation_without_allocation<long double>(1e-4);
  expect_escalation_without_allocation<sd::DoubleDouble>(1e-8);
}
