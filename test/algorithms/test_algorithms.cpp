// Fixed-base algorithm tests on every shared robot, against identities that tie the algorithms
// to each other and to finite differences: ABA against a Cholesky solve of M q̈ = τ − h,
// ID(FD(τ)) = τ, RNEA = M q̈ + h, Jacobians against differentiated poses, external forces
// against Jᵀ f, kinetic energy against ½ q̇ᵀ M q̇, and the axis-aligned fast paths against the
// general-axis code.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cstdio>

#include "spatial_dynamics/reduction/couple_mimic_joints.hpp"
#include "test_utils.hpp"

namespace sd = spatial_dynamics;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr int kStates = 100;

class FixedBaseRobot : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override { model = sd::build_model_from_urdf_file(sd_test::robot_path(GetParam())); }
  sd::Model<double> model;
  std::mt19937 rng{7};
};

int body_frame(const sd::Model<double>& model, int body) { return model.frameIndex(model.body_names[body]); }

}  // namespace

TEST_P(FixedBaseRobot, AbaAgreesWithCholeskySolveOfMassMatrix) {
  sd::Data<double> data(model);
  double worst = 0;
  for (int s = 0; s < kStates; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const VectorXd qd = sd_test::random_vector(model.nv, rng);
    const VectorXd tau = sd_test::random_vector(model.nv, rng, 10.0);
    const MatrixXd M = sd::crba(model, data, q);
    const VectorXd h = sd::nonlinear_effects(model, data, q, qd);
    const VectorXd reference = M.llt().solve(tau - h);
    worst = std::max(worst, sd_test::relative_error(sd::aba(model, data, q, qd, tau), reference));
  }
  std::printf("[%s] ABA vs Cholesky: max relative error %.3g\n", GetParam().c_str(), worst);
  EXPECT_LE(worst, 1e-11) << GetParam();
}

TEST_P(FixedBaseRobot, InverseOfForwardDynamicsIsIdentity) {
  sd::Data<double> data(model);
  double worst = 0;
  for (int s = 0; s < kStates; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const VectorXd qd = sd_test::random_vector(model.nv, rng);
    const VectorXd tau = sd_test::random_vector(model.nv, rng, 10.0);
    const VectorXd qdd = sd::aba(model, data, q, qd, tau);
    worst = std::max(worst, sd_test::relative_error(sd::rnea(model, data, q, qd, qdd), tau));
  }
  std::printf("[%s] ID(FD(tau)) vs tau: max relative error %.3g\n", GetParam().c_str(), worst);
  EXPECT_LE(worst, 1e-12) << GetParam();
}

TEST_P(FixedBaseRobot, RneaEqualsMassMatrixTimesAccelerationPlusBias) {
  sd::Data<double> data(model);
  double worst = 0;
  for (int s = 0; s < kStates; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const VectorXd qd = sd_test::random_vector(model.nv, rng);
    const VectorXd qdd = sd_test::random_vector(model.nv, rng);
    const MatrixXd M = sd::crba(model, data, q);
    EXPECT_EQ(M, M.transpose());
    const VectorXd h = sd::nonlinear_effects(model, data, q, qd);
    worst = std::max(worst, sd_test::relative_error(VectorXd(sd::rnea(model, data, q, qd, qdd)), VectorXd(M * qdd + h)));
  }
  EXPECT_LE(worst, 1e-12) << GetParam();
}

TEST_P(FixedBaseRobot, KineticEnergyIsHalfQdMQd) {
  sd::Data<double> data(model);
  for (int s = 0; s < kStates; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const VectorXd qd = sd_test::random_vector(model.nv, rng);
    const double from_mass_matrix = 0.5 * qd.dot(sd::crba(model, data, q) * qd);
    const double from_bodies = sd::kinetic_energy(model, data, q, qd);  // Σ ½ v·I v (eq. 28)
    EXPECT_NEAR(from_bodies, from_mass_matrix, 1e-13 * from_mass_matrix) << GetParam();
  }
}

// J q̇ in the root-aligned frame is (ω, ṗ) of the frame: compare with central differences of its
// pose along q + t q̇; the local Jacobian is the same rotated into the frame's axes.
TEST_P(FixedBaseRobot, FrameJacobianMatchesDifferentiatedPose) {
  sd::Data<double> data(model);
  const double h = 1e-6;
  for (int s = 0; s < 20; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const VectorXd qd = sd_test::random_vector(model.nv, rng);
    for (int frame = 0; frame < static_cast<int>(model.frames.size()); ++frame) {
      sd::forward_kinematics(model, data, VectorXd(q + h * qd));
      const Eigen::Matrix3d R_plus = data.X_frame_base[frame].rotation();
      const Eigen::Vector3d p_plus = data.X_frame_base[frame].translation();
      sd::forward_kinematics(model, data, VectorXd(q - h * qd));
      const Eigen::Matrix3d R_minus = data.X_frame_base[frame].rotation();
      const Eigen::Vector3d p_minus = data.X_frame_base[frame].translation();
      sd::forward_kinematics(model, data, q);
      const Eigen::Matrix3d R = data.X_frame_base[frame].rotation();
      const Eigen::Matrix3d w_skew = (R_plus - R_minus) / (2 * h) * R.transpose();  // Ṙ Rᵀ = ω×
      Eigen::Matrix<double, 6, 1> numeric;
      numeric << w_skew(2, 1), w_skew(0, 2), w_skew(1, 0), (p_plus - p_minus) / (2 * h);

      const Eigen::Matrix<double, 6, 1> aligned = sd::frame_jacobian(model, data, q, frame, sd::ReferenceFrame::RootAligned) * qd;
      EXPECT_LE((aligned - numeric).norm(), 1e-7 * (1 + numeric.norm())) << GetParam() << " frame " << model.frames[frame].name;

      const Eigen::Matrix<double, 6, 1> local = sd::frame_jacobian(model, data, q, frame, sd::ReferenceFrame::Local) * qd;
      Eigen::Matrix<double, 6, 1> rotated;
      rotated << R * local.head<3>(), R * local.tail<3>();
      EXPECT_LE((rotated - aligned).norm(), 1e-13 * (1 + aligned.norm()));
      // The local Jacobian also agrees with the body velocity of forward kinematics.
      sd::forward_kinematics(model, data, q, qd);
      const auto& fr = model.frames[frame];
      EXPECT_LE((fr.X_frame_body.apply(data.v[fr.body]).toVector() - local).norm(), 1e-13 * (1 + local.norm()));
    }
  }
}

// An external force f_b on body b (body coordinates) changes the torques by −J_bᵀ f_b.
TEST_P(FixedBaseRobot, ExternalForcesEnterAsJacobianTranspose) {
  sd::Data<double> data(model);
  double worst_id = 0, worst_fd = 0;
  for (int s = 0; s < 20; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const VectorXd qd = sd_test::random_vector(model.nv, rng);
    const VectorXd qdd = sd_test::random_vector(model.nv, rng);
    std::vector<sd::ForceVector<double>> f_ext(model.nbodies(), sd::ForceVector<double>::Zero());
    VectorXd expected = sd::rnea(model, data, q, qd, qdd);
    for (int b = 1; b < model.nbodies(); ++b) {
      f_ext[b] = sd::ForceVector<double>(sd_test::random_vector(6, rng, 5.0));
      expected -= sd::frame_jacobian(model, data, q, body_frame(model, b), sd::ReferenceFrame::Local).transpose() *
                  f_ext[b].toVector();
    }
    const VectorXd tau = sd::rnea(model, data, q, qd, qdd, f_ext);
    worst_id = std::max(worst_id, sd_test::relative_error(tau, expected));
    // Forward dynamics with the same forces: ID(FD(τ, f), f) = τ.
    const VectorXd qdd_fd = sd::aba(model, data, q, qd, tau, f_ext);
    worst_fd = std::max(worst_fd, sd_test::relative_error(sd::rnea(model, data, q, qd, qdd_fd, f_ext), tau));
  }
  EXPECT_LE(worst_id, 1e-12) << GetParam();
  EXPECT_LE(worst_fd, 1e-12) << GetParam();
}

// The axis-aligned code paths give the same numbers as the general-axis path.
TEST_P(FixedBaseRobot, AxisAlignedPathsMatchGeneralAxisPath) {
  sd::Model<double> general = model;
  for (auto& joint : general.joints) joint.axis_kind = sd::AxisKind::General;
  sd::Data<double> data(model), data_general(general);
  for (int s = 0; s < 20; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const VectorXd qd = sd_test::random_vector(model.nv, rng);
    const VectorXd qdd = sd_test::random_vector(model.nv, rng);
    EXPECT_LE(sd_test::relative_error(sd::rnea(model, data, q, qd, qdd), sd::rnea(general, data_general, q, qd, qdd)), 1e-14);
    EXPECT_LE(sd_test::relative_error(sd::aba(model, data, q, qd, qdd), sd::aba(general, data_general, q, qd, qdd)), 1e-13);
    EXPECT_LE(sd_test::relative_error(sd::crba(model, data, q), sd::crba(general, data_general, q)), 1e-14);
  }
}

TEST_P(FixedBaseRobot, WrongInputLengthsAreRejectedWithTheirName) {
  sd::Data<double> data(model);
  const VectorXd q = VectorXd::Zero(model.nq), v = VectorXd::Zero(model.nv), short_v = VectorXd::Zero(model.nv - 1);
  try {
    sd::rnea(model, data, q, v, short_v);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("acceleration"), std::string::npos) << e.what();
  }
  EXPECT_THROW(sd::aba(model, data, q, short_v, v), std::invalid_argument);
  EXPECT_THROW(sd::crba(model, data, short_v), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(SharedRobots, FixedBaseRobot, ::testing::ValuesIn(sd_test::robot_files()),
                         [](const auto& info) { return info.param.substr(0, info.param.find('.')); });

// A wrist modelled with a massless dummy link between two revolute joints, ending in a massless
// leaf on its own joint: inverse dynamics works; forward dynamics fails naming the leaf joint.
TEST(MasslessLinks, LeafWithoutInertiaFailsForwardDynamicsNamingTheJoint) {
  const std::string link_with_mass =
      "<inertial><mass value='1'/><origin xyz='0.1 0 0'/><inertia ixx='0.01' ixy='0' ixz='0' iyy='0.01' iyz='0' "
      "izz='0.01'/></inertial>";
  const std::string urdf =
      "<robot name='wrist'><link name='base'/>"
      "<link name='upper'>" + link_with_mass + "</link><link name='dummy'/><link name='hand'>" + link_with_mass +
      "</link><link name='tip'/>"
      "<joint name='j1' type='continuous'><parent link='base'/><child link='upper'/><axis xyz='0 0 1'/></joint>"
      "<joint name='j2' type='continuous'><parent link='upper'/><child link='dummy'/><origin xyz='0.3 0 0'/><axis xyz='0 1 0'/></joint>"
      "<joint name='j3' type='continuous'><parent link='dummy'/><child link='hand'/><axis xyz='1 0 0'/></joint>"
      "<joint name='j4' type='continuous'><parent link='hand'/><child link='tip'/><origin xyz='0.1 0 0'/><axis xyz='0 0 1'/></joint>"
      "</robot>";
  const sd::Model<double> model = sd::build_model_from_urdf_string(urdf);
  sd::Data<double> data(model);
  const VectorXd q = VectorXd::Constant(4, 0.3), qd = VectorXd::Constant(4, 0.5), qdd = VectorXd::Constant(4, -0.2);
  const VectorXd tau = sd::rnea(model, data, q, qd, qdd);
  EXPECT_TRUE(tau.allFinite());
  EXPECT_EQ(tau[3], 0.0);  // the massless leaf needs no torque
  try {
    sd::aba(model, data, q, qd, tau);
    FAIL() << "forward dynamics of a massless leaf joint must fail";
  } catch (const std::domain_error& e) {
    EXPECT_NE(std::string(e.what()).find("'j4'"), std::string::npos) << e.what();
  }
  // Without the leaf joint the massless dummy link between j2 and j3 is fine.
  std::string without_leaf = urdf.substr(0, urdf.find("<joint name='j4'")) + "</robot>";
  without_leaf.erase(without_leaf.find("<link name='tip'/>"), std::string("<link name='tip'/>").size());
  const sd::Model<double> no_leaf = sd::build_model_from_urdf_string(without_leaf);
  sd::Data<double> data3(no_leaf);
  const VectorXd tau3 = sd::rnea(no_leaf, data3, q.head(3), qd.head(3), qdd.head(3));
  EXPECT_LE(sd_test::relative_error(sd::aba(no_leaf, data3, q.head(3), qd.head(3), tau3), VectorXd(qdd.head(3))), 1e-12);
}

// A single pendulum: analytic inverse dynamics τ = (I_c + m l²) q̈ + m g l sin q for a point at
// distance l below a horizontal axis.
TEST(AnalyticPendulum, MatchesClosedForm) {
  const double m = 2.0, l = 0.7, Ic = 0.03, g = 9.81;
  const std::string urdf =
      "<robot name='pendulum'><link name='base'/><link name='bob'><inertial><mass value='2'/>"
      "<origin xyz='0 0 -0.7'/><inertia ixx='0.03' ixy='0' ixz='0' iyy='0.03' iyz='0' izz='0.03'/></inertial></link>"
      "<joint name='swing' type='continuous'><parent link='base'/><child link='bob'/><axis xyz='1 0 0'/></joint></robot>";
  const sd::Model<double> model = sd::build_model_from_urdf_string(urdf);
  sd::Data<double> data(model);
  for (double q : {-2.0, -0.4, 0.0, 0.9, 3.0}) {
    for (double qdd : {-1.5, 0.0, 2.0}) {
      const VectorXd tau = sd::rnea(model, data, VectorXd::Constant(1, q), VectorXd::Constant(1, 1.3), VectorXd::Constant(1, qdd));
      EXPECT_NEAR(tau[0], (Ic + m * l * l) * qdd + m * g * l * std::sin(q), 1e-13);
    }
  }
}

// The joints' sin and cos, computed for all revolute joints together before the passes, against
// the C library: talos's 44 joints span several vector registers; one angle of 1e6 sends its
// register's angles to the C library; a joint coupled to another (q = k q_master + offset) takes
// the coupled angle. Then the transforms of every body against one joint at a time.
TEST(JointSinesAndCosines, EveryRevoluteJointAgainstTheCLibrary) {
  const std::string link = "<inertial><mass value='1'/><origin xyz='0.1 0.05 0'/><inertia ixx='0.01' ixy='0' ixz='0' "
                           "iyy='0.02' iyz='0' izz='0.02'/></inertial>";
  const std::string coupled_urdf =
      "<robot name='chain'><link name='base'/><link name='a'>" + link + "</link><link name='b'>" + link +
      "</link><joint name='ja' type='continuous'><parent link='base'/><child link='a'/><axis xyz='0 0 1'/></joint>"
      "<joint name='jb' type='continuous'><parent link='a'/><child link='b'/><origin xyz='0.3 0 0'/><axis xyz='0 1 0'/>"
      "<mimic joint='ja' multiplier='-2.5' offset='0.7'/></joint></robot>";
  std::mt19937 rng(31);
  for (const sd::Model<double>& model :
       {sd::build_model_from_urdf_file(sd_test::robot_path("talos.urdf")),
        sd::couple_mimic_joints(sd::build_model_from_urdf_string(coupled_urdf))}) {
    sd::Data<double> data(model);
    for (int s = 0; s < 50; ++s) {
      VectorXd q = sd_test::random_configuration(model, rng);
      if (s == 0) q[model.nq - 1] = 1e6;
      sd::forward_kinematics(model, data, q);
      int revolute = 0;
      for (int i = 1; i < model.nbodies(); ++i) {
        const auto& j = model.joints[i];
        if (j.type != sd::JointType::Revolute) continue;
        ++revolute;
        const double angle = j.coupled ? j.mimic.multiplier * q[j.idx_q] + j.mimic.offset : q[j.idx_q];
        // The library's AVX2 build may form a coupled joint's angle k q + offset with one rounding
        // (a fused multiply-add): the sine and cosine of either rounding are right.
        const double fused = j.coupled ? std::fma(j.mimic.multiplier, q[j.idx_q], j.mimic.offset) : angle;
        EXPECT_LE(std::min(std::abs(data.joint_sin[i] - std::sin(angle)), std::abs(data.joint_sin[i] - std::sin(fused))),
                  4.5e-16) << model.joint_names[i] << " at " << angle;
        EXPECT_LE(std::min(std::abs(data.joint_cos[i] - std::cos(angle)), std::abs(data.joint_cos[i] - std::cos(fused))),
                  4.5e-16) << model.joint_names[i] << " at " << angle;
        sd::PluckerTransform<double> X;
        sd::joint_up_transform(model, i, &angle, X);
        EXPECT_LE((X.E - data.X_up[i].E).eigen().cwiseAbs().maxCoeff(), 1e-15) << model.joint_names[i];
        EXPECT_EQ(X.r, data.X_up[i].r) << model.joint_names[i];
      }
      EXPECT_EQ(revolute, static_cast<int>(data.angle_bodies.size()));  // no planar joints here
      EXPECT_GE(revolute, model.nbodies() == 3 ? 2 : 30);
    }
  }
}
