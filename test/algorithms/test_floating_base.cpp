// Floating-base tests on the humanoid (talos) and the quadruped (solo12) with a free root:
// q = (x y z qx qy qz qw, joints), q̇ = (ω, v of the root in its own frame, joints).
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cstdio>

#include "test_utils.hpp"

namespace sd = spatial_dynamics;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr int kStates = 100;

class FloatingBaseRobot : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    sd::ModelBuildOptions options;
    options.floating_base = true;
    model = sd::build_model_from_urdf_file(sd_test::robot_path(GetParam()), options);
  }
  sd::Model<double> model;
  std::mt19937 rng{11};
};

}  // namespace

TEST_P(FloatingBaseRobot, CoordinatesAreDocumentedSizes) {
  const int joints = model.nbodies() - 2;  // minus the fixed base and the free root body
  EXPECT_EQ(model.nq, joints + 7);
  EXPECT_EQ(model.nv, joints + 6);
  EXPECT_EQ(model.joints[1].type, sd::JointType::Free);
  EXPECT_EQ(model.joints[1].idx_q, 0);
  EXPECT_EQ(model.joints[1].idx_v, 0);
}

TEST_P(FloatingBaseRobot, InverseOfForwardDynamicsIsIdentity) {
  sd::Data<double> data(model);
  double worst = 0, worst_cholesky = 0;
  for (int s = 0; s < kStates; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const VectorXd qd = sd_test::random_vector(model.nv, rng);
    const VectorXd tau = sd_test::random_vector(model.nv, rng, 10.0);
    const VectorXd qdd = sd::aba(model, data, q, qd, tau);
    worst = std::max(worst, sd_test::relative_error(sd::rnea(model, data, q, qd, qdd), tau));
    const MatrixXd M = sd::crba(model, data, q);
    const VectorXd h = sd::nonlinear_effects(model, data, q, qd);
    worst_cholesky = std::max(worst_cholesky, sd_test::relative_error(qdd, VectorXd(M.llt().solve(tau - h))));
  }
  std::printf("[%s floating] ID(FD(tau)): %.3g, ABA vs Cholesky: %.3g\n", GetParam().c_str(), worst, worst_cholesky);
  EXPECT_LE(worst, 1e-12) << GetParam();
  EXPECT_LE(worst_cholesky, 1e-11) << GetParam();
}

TEST_P(FloatingBaseRobot, MassMatrixIsSymmetricPositiveDefinite) {
  sd::Data<double> data(model);
  for (int s = 0; s < kStates; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const MatrixXd M = sd::crba(model, data, q);
    EXPECT_EQ(M, M.transpose());
    const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(M, Eigen::EigenvaluesOnly);
    EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0) << GetParam();
    // The root block is the composite inertia of the whole robot: its mass is the total mass.
    double total_mass = 0;
    for (const auto& inertia : model.inertia) total_mass += inertia.mass;
    EXPECT_NEAR(M(3, 3), total_mass, 1e-12 * total_mass);
    // Columns of M are ID(q, 0, e_i) − ID(q, 0, 0) with gravity off.
    sd::Model<double> no_gravity = model;
    no_gravity.gravity.setZero();
    sd::Data<double> d0(no_gravity);
    MatrixXd columns(model.nv, model.nv);
    const VectorXd zero = VectorXd::Zero(model.nv);
    for (int i = 0; i < model.nv; ++i) columns.col(i) = sd::rnea(no_gravity, d0, q, zero, VectorXd(VectorXd::Unit(model.nv, i)));
    EXPECT_LE(sd_test::relative_error(M, columns), 1e-13) << GetParam();
  }
}

// The first six rows of M q̇ are the system's momentum in root-body coordinates; the sum of
// the bodies' momenta (eq. 23) moved to the base gives the same physical quantity.
TEST_P(FloatingBaseRobot, TotalMomentumIsTheSumOfBodyMomenta) {
  sd::Data<double> data(model);
  double worst = 0;
  for (int s = 0; s < kStates; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const VectorXd qd = sd_test::random_vector(model.nv, rng);
    const sd::ForceVector<double> h_base = sd::total_momentum(model, data, q, qd);
    const Eigen::Matrix<double, 6, 1> from_bodies = data.X_base[1].apply(h_base).toVector();  // into root-body coordinates
    const Eigen::Matrix<double, 6, 1> from_mass_matrix = (sd::crba(model, data, q) * qd).head<6>();
    worst = std::max(worst, sd_test::relative_error(from_bodies, from_mass_matrix));
    const double T = 0.5 * qd.dot(data.M * qd);
    EXPECT_NEAR(sd::kinetic_energy(model, data, q, qd), T, 1e-13 * T);
  }
  EXPECT_LE(worst, 1e-12) << GetParam();
}

// With no joint torques, zero velocity and nothing else acting, every body falls freely: the
// joints do not accelerate, the root does not rotate, and its linear acceleration is g.
TEST_P(FloatingBaseRobot, FreeFallAcceleratesEveryBodyWithGravity) {
  sd::Data<double> data(model);
  for (int s = 0; s < 10; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const VectorXd qdd = sd::aba(model, data, q, VectorXd::Zero(model.nv), VectorXd::Zero(model.nv));
    sd::forward_kinematics(model, data, q);
    const Eigen::Vector3d g_in_root = data.X_base[1].E.eigen() * model.gravity;
    EXPECT_LE(qdd.head<3>().norm(), 1e-12);
    EXPECT_LE((qdd.segment<3>(3) - g_in_root).norm(), 1e-12);
    EXPECT_LE(qdd.tail(model.nv - 6).norm(), 1e-11) << GetParam();
  }
}

TEST_P(FloatingBaseRobot, NonUnitQuaternionIsRejectedNamingTheRootJoint) {
  sd::Data<double> data(model);
  VectorXd q = sd_test::random_configuration(model, rng);
  q.segment<4>(3) *= 1.1;
  try {
    sd::rnea(model, data, q, VectorXd::Zero(model.nv), VectorXd::Zero(model.nv));
    FAIL() << "a non-unit quaternion must be rejected";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("root_joint"), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(SharedRobots, FloatingBaseRobot, ::testing::Values("talos.urdf", "solo12.urdf"),
                         [](const auto& info) { return std::string(info.param).substr(0, std::string(info.param).find('.')); });
