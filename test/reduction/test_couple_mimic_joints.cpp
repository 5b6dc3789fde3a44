// Coupled mimic joints against the independent model projected through the coupling:
// q̇ = G q̇_c ⇒ τ_c = Gᵀ τ, M_c = Gᵀ M G, J_c = J G, and FD solves M_c q̈_c = τ_c − h_c.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include "spatial_dynamics/reduction/couple_mimic_joints.hpp"
#include "synthetic_robots.hpp"
#include "test_utils.hpp"

namespace sd = spatial_dynamics;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

struct Coupling {
  MatrixXd G;  // independent velocity coordinates = G · coupled ones
};

/// Follows a joint's mimic chain to the joint with a coordinate of its own: q = k q_master + offset.
void resolve(const sd::Model<double>& independent, int body, double& k, double& offset, int& master) {
  k = 1;
  offset = 0;
  master = body;
  while (independent.joints[master].mimic.active()) {
    const auto& m = independent.joints[master].mimic;
    offset = k * m.offset + offset;
    k *= m.multiplier;
    master = m.master_body;
  }
}

/// Independent positions from coupled ones: q = k q_master + offset per joint; a free root copied.
VectorXd independent_positions(const sd::Model<double>& independent, const sd::Model<double>& coupled,
                               const VectorXd& qc) {
  VectorXd q(independent.nq);
  for (int i = 1; i < independent.nbodies(); ++i) {
    double k, offset;
    int master;
    resolve(independent, i, k, offset, master);
    const auto& j = independent.joints[i];
    const auto& jc = coupled.joints[coupled.jointBody(independent.joint_names[master])];
    if (j.nv == 1) q[j.idx_q] = k * qc[jc.idx_q] + offset;
    else q.segment(j.idx_q, j.nq) = qc.segment(jc.idx_q, jc.nq);
  }
  return q;
}

/// Built from the URDF mimic records of the independent model, independently of couple_mimic_joints.
Coupling coupling_of(const sd::Model<double>& independent, const sd::Model<double>& coupled) {
  Coupling c{MatrixXd::Zero(independent.nv, coupled.nv)};
  for (int i = 1; i < independent.nbodies(); ++i) {
    double k, offset;
    int master;
    resolve(independent, i, k, offset, master);
    const auto& j = independent.joints[i];
    const auto& jc = coupled.joints[coupled.jointBody(independent.joint_names[master])];
    for (int l = 0; l < j.nv; ++l) c.G(j.idx_v + l, jc.idx_v + l) = k;
  }
  return c;
}

void check(const std::string& label, const sd::Model<double>& independent, int expected_coupled) {
  const sd::Model<double> coupled = sd::couple_mimic_joints(independent);
  EXPECT_TRUE(coupled.has_coupled_joints);
  EXPECT_EQ(independent.nv - coupled.nv, expected_coupled) << label;
  EXPECT_EQ(static_cast<int>(coupled.velocityNames().size()), coupled.nv);
  const Coupling c = coupling_of(independent, coupled);
  sd::Data<double> di(independent), dc(coupled);
  std::mt19937 rng(17);
  double worst_tau = 0, worst_M = 0, worst_fd = 0, worst_idfd = 0, worst_J = 0;
  const int frame = static_cast<int>(independent.frames.size()) - 1;
  for (int s = 0; s < 50; ++s) {
    const VectorXd qc = sd_test::random_configuration(coupled, rng);
    const VectorXd qdc = sd_test::random_vector(coupled.nv, rng), qddc = sd_test::random_vector(coupled.nv, rng);
    const VectorXd qd = c.G * qdc, qdd = c.G * qddc;
    const VectorXd q = independent_positions(independent, coupled, qc);
    worst_tau = std::max(worst_tau, sd_test::relative_error(sd::rnea(coupled, dc, qc, qdc, qddc),
                                                            VectorXd(c.G.transpose() * sd::rnea(independent, di, q, qd, qdd))));
    const MatrixXd M = c.G.transpose() * sd::crba(independent, di, q) * c.G;
    const MatrixXd Mc = sd::crba(coupled, dc, qc);
    EXPECT_EQ(Mc, Mc.transpose());
    worst_M = std::max(worst_M, sd_test::relative_error(Mc, M));
    const VectorXd tau_c = sd_test::random_vector(coupled.nv, rng, 5.0);
    const VectorXd h = c.G.transpose() * sd::nonlinear_effects(independent, di, q, qd);
    const VectorXd qdd_c = sd::forward_dynamics(coupled, dc, qc, qdc, tau_c);
    worst_fd = std::max(worst_fd, sd_test::relative_error(qdd_c, VectorXd(M.llt().solve(tau_c - h))));
    worst_idfd = std::max(worst_idfd, sd_test::relative_error(sd::rnea(coupled, dc, qc, qdc, qdd_c), tau_c));
    const MatrixXd J = sd::frame_jacobian(independent, di, q, frame, sd::ReferenceFrame::Local) * c.G;
    worst_J = std::max(worst_J, sd_test::relative_error(sd::frame_jacobian(coupled, dc, qc, frame, sd::ReferenceFrame::Local), J));
  }
  std::printf("[coupled mimic] %-22s tau %.2e  M %.2e  FD %.2e  ID(FD) %.2e  J %.2e\n", label.c_str(), worst_tau,
              worst_M, worst_fd, worst_idfd, worst_J);
  EXPECT_LE(worst_tau, 1e-12) << label;
  EXPECT_LE(worst_M, 1e-12) << label;
  EXPECT_LE(worst_fd, 1e-12) << label;
  EXPECT_LE(worst_idfd, 1e-12) << label;
  EXPECT_LE(worst_J, 1e-12) << label;
  EXPECT_THROW(sd::aba(coupled, dc, VectorXd::Zero(coupled.nq), VectorXd::Zero(coupled.nv), VectorXd::Zero(coupled.nv)),
               std::invalid_argument);
}

}  // namespace

TEST(CoupledMimicJoints, Panda) {
  check("panda", sd::build_model_from_urdf_file(sd_test::robot_path("panda.urdf")), 1);
}

TEST(CoupledMimicJoints, Humanoid) {
  check("talos", sd::build_model_from_urdf_file(sd_test::robot_path("talos.urdf")), 12);
}

TEST(CoupledMimicJoints, HumanoidFloatingBase) {
  sd::ModelBuildOptions options;
  options.floating_base = true;
  check("talos floating", sd::build_model_from_urdf_file(sd_test::robot_path("talos.urdf"), options), 12);
}

TEST(CoupledMimicJoints, MobileManipulatorWithNegativeMultiplier) {
  check("mobile manipulator", sd::build_model_from_urdf_string(sd_test::mobile_manipulator_urdf(3)), 2);
}

TEST(CoupledMimicJoints, MimicOfAMimicFollowsTheChain) {
  const std::string link = "<inertial><mass value='1'/><origin xyz='0.1 0.05 0'/><inertia ixx='0.01' ixy='0' ixz='0' "
                           "iyy='0.02' iyz='0' izz='0.02'/></inertial>";
  const std::string urdf =
      "<robot name='chain'><link name='base'/><link name='a'>" + link + "</link><link name='b'>" + link +
      "</link><link name='c'>" + link +
      "</link>"
      "<joint name='ja' type='continuous'><parent link='base'/><child link='a'/><axis xyz='0 0 1'/></joint>"
      "<joint name='jb' type='continuous'><parent link='a'/><child link='b'/><origin xyz='0.3 0 0'/><axis xyz='0 1 0'/>"
      "<mimic joint='ja' multiplier='2' offset='0.1'/></joint>"
      "<joint name='jc' type='continuous'><parent link='b'/><child link='c'/><origin xyz='0.3 0 0'/><axis xyz='1 0 0'/>"
      "<mimic joint='jb' multiplier='-0.5' offset='0.3'/></joint></robot>";
  const sd::Model<double> independent = sd::build_model_from_urdf_string(urdf);
  const sd::Model<double> coupled = sd::couple_mimic_joints(independent);
  EXPECT_EQ(coupled.nv, 1);
  const auto& jc = coupled.joints[coupled.jointBody("jc")];
  EXPECT_EQ(jc.mimic.master_body, coupled.jointBody("ja"));
  EXPECT_DOUBLE_EQ(jc.mimic.multiplier, -1.0);        // −0.5 · 2
  EXPECT_DOUBLE_EQ(jc.mimic.offset, -0.5 * 0.1 + 0.3);
  check("mimic chain", independent, 2);
}
