// Reduced models against the full model with the locked joints held still (q̇ = q̈ = 0):
// torques, mass matrix and forward dynamics of the kept joints agree to 1e-12 relative.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include "spatial_dynamics/reduction/reduce_model.hpp"
#include "synthetic_robots.hpp"
#include "test_utils.hpp"

namespace sd = spatial_dynamics;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr double kTolerance = 1e-12;

/// Random locked positions for every joint the scene does not keep.
sd::Scene with_random_locks(const sd::Model<double>& full, sd::Scene scene, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (int i = 1; i < full.nbodies(); ++i) {
    const std::string& name = full.joint_names[i];
    if (full.joints[i].type == sd::JointType::Free) continue;
    if (std::find(scene.kept_joints.begin(), scene.kept_joints.end(), name) == scene.kept_joints.end())
      scene.locked_positions[name] = u(rng);
  }
  return scene;
}

struct Worst {
  double tau = 0, mass = 0, fd = 0;
};

/// Compares reduced and full model at random states of the kept joints.
Worst compare(const sd::Model<double>& full, const sd::Model<double>& reduced, const sd::Scene& scene,
              std::mt19937& rng, int states = 50) {
  sd::Data<double> full_data(full), reduced_data(reduced);
  // Velocity-coordinate map reduced → full, by coordinate name.
  const std::vector<std::string> full_names = full.velocityNames(), reduced_names = reduced.velocityNames();
  std::vector<int> kept_v;
  for (const std::string& name : reduced_names)
    kept_v.push_back(static_cast<int>(std::find(full_names.begin(), full_names.end(), name) - full_names.begin()));
  Worst worst;
  for (int s = 0; s < states; ++s) {
    // Full state: locked joints at their positions and still; kept joints random.
    VectorXd q = sd_test::random_configuration(full, rng);
    VectorXd qd = VectorXd::Zero(full.nv), qdd = VectorXd::Zero(full.nv);
    for (int i = 1; i < full.nbodies(); ++i) {
      const auto it = scene.locked_positions.find(full.joint_names[i]);
      if (it != scene.locked_positions.end()) q[full.joints[i].idx_q] = it->second;
      else if (full.joints[i].nv == 1 && !reduced.hasJoint(full.joint_names[i])) q[full.joints[i].idx_q] = 0.0;
    }
    VectorXd q_red(reduced.nq), qd_red(reduced.nv), qdd_red(reduced.nv), tau_red(reduced.nv);
    for (int i = 1; i < reduced.nbodies(); ++i) {
      const auto& jr = reduced.joints[i];
      const auto& jf = full.joints[full.jointBody(reduced.joint_names[i])];
      q_red.segment(jr.idx_q, jr.nq) = q.segment(jf.idx_q, jf.nq);
    }
    for (int k = 0; k < reduced.nv; ++k) {
      qd[kept_v[k]] = qd_red[k] = std::uniform_real_distribution<double>(-1, 1)(rng);
      qdd[kept_v[k]] = qdd_red[k] = std::uniform_real_distribution<double>(-1, 1)(rng);
    }
    const VectorXd tau_full = sd::rnea(full, full_data, q, qd, qdd);
    for (int k = 0; k < reduced.nv; ++k) tau_red[k] = tau_full[kept_v[k]];
    worst.tau = std::max(worst.tau, sd_test::relative_error(sd::rnea(reduced, reduced_data, q_red, qd_red, qdd_red), tau_red));

    const MatrixXd M_full = sd::crba(full, full_data, q);
    MatrixXd M_kept(reduced.nv, reduced.nv);
    for (int a = 0; a < reduced.nv; ++a)
      for (int b = 0; b < reduced.nv; ++b) M_kept(a, b) = M_full(kept_v[a], kept_v[b]);
    worst.mass = std::max(worst.mass, sd_test::relative_error(sd::crba(reduced, reduced_data, q_red), M_kept));

    // Forward dynamics of the constrained full system: M_kk q̈_k = τ_k − h_k.
    const VectorXd h_full = sd::nonlinear_effects(full, full_data, q, qd);
    VectorXd rhs(reduced.nv);
    for (int k = 0; k < reduced.nv; ++k) rhs[k] = tau_red[k] - h_full[kept_v[k]];
    worst.fd = std::max(worst.fd, sd_test::relative_error(sd::aba(reduced, reduced_data, q_red, qd_red, tau_red),
                                                          VectorXd(M_kept.llt().solve(rhs))));
  }
  return worst;
}

void expect_exact(const Worst& worst, const std::string& what) {
  std::printf("[reduction] %-40s tau %.2e  M %.2e  FD %.2e\n", what.c_str(), worst.tau, worst.mass, worst.fd);
  EXPECT_LE(worst.tau, kTolerance) << what;
  EXPECT_LE(worst.mass, kTolerance) << what;
  EXPECT_LE(worst.fd, kTolerance) << what;
}

sd::Scene arm(const std::string& prefix) {
  sd::Scene scene;
  for (int k = 1; k <= 7; ++k) scene.kept_joints.push_back(prefix + std::to_string(k) + "_joint");
  return scene;
}

}  // namespace

TEST(Reduction, HumanoidOneArm) {
  const sd::Model<double> full = sd::build_model_from_urdf_file(sd_test::robot_path("talos.urdf"));
  std::mt19937 rng(1);
  for (int trial = 0; trial < 5; ++trial) {
    const sd::Scene scene = with_random_locks(full, arm("arm_left_"), rng);
    const sd::Model<double> reduced = sd::reduce_model(full, scene);
    EXPECT_EQ(reduced.nv, 7);
    EXPECT_EQ(reduced.frames.size(), full.frames.size());  // every link stays addressable
    expect_exact(compare(full, reduced, scene, rng), "talos, left arm");
  }
}

TEST(Reduction, HumanoidFloatingBaseOneArm) {
  sd::ModelBuildOptions options;
  options.floating_base = true;
  const sd::Model<double> full = sd::build_model_from_urdf_file(sd_test::robot_path("talos.urdf"), options);
  std::mt19937 rng(2);
  const sd::Scene scene = with_random_locks(full, arm("arm_right_"), rng);
  const sd::Model<double> reduced = sd::reduce_model(full, scene);
  EXPECT_EQ(reduced.nv, 13);  // free root (kept) + 7
  expect_exact(compare(full, reduced, scene, rng), "talos floating, right arm");
}

TEST(Reduction, HumanoidRootAndTips) {
  const sd::Model<double> full = sd::build_model_from_urdf_file(sd_test::robot_path("talos.urdf"));
  std::mt19937 rng(3);
  sd::Scene scene = sd::scene_from_root_and_tips(full, sd::RootTipScene{"torso_2_link", {"arm_left_7_link"}, {}});
  EXPECT_EQ(scene.kept_joints.size(), 7u);
  scene = with_random_locks(full, scene, rng);
  expect_exact(compare(full, sd::reduce_model(full, scene), scene, rng), "talos, torso_2_link -> arm_left_7_link");

  sd::Scene both = sd::scene_from_root_and_tips(full, sd::RootTipScene{"base_link", {"arm_left_7_link", "arm_right_7_link"}, {}});
  EXPECT_EQ(both.kept_joints.size(), 16u);  // torso 2 + arms 2 × 7
  both = with_random_locks(full, both, rng);
  expect_exact(compare(full, sd::reduce_model(full, both), both, rng), "talos, base_link -> both hands");
}

TEST(Reduction, MobileManipulator) {
  const sd::Model<double> full = sd::build_model_from_urdf_string(sd_test::mobile_manipulator_urdf(7));
  EXPECT_EQ(full.nv, 2 + 2 + 14 + 4);
  EXPECT_EQ(full.frames.size(), 1u + 2 + 2 + 14 + 2 + 4 + 20);
  std::mt19937 rng(4);
  for (int trial = 0; trial < 5; ++trial) {
    const sd::Scene scene = with_random_locks(full, arm("arm_left_"), rng);
    const sd::Model<double> reduced = sd::reduce_model(full, scene);
    EXPECT_EQ(reduced.nbodies(), 8);
    expect_exact(compare(full, reduced, scene, rng), "mobile manipulator, left arm");
  }
  sd::Scene tips = sd::scene_from_root_and_tips(full, sd::RootTipScene{"torso_link", {"gripper_right_link"}, {}});
  EXPECT_EQ(tips.kept_joints.size(), 7u);
  tips = with_random_locks(full, tips, rng);
  expect_exact(compare(full, sd::reduce_model(full, tips), tips, rng), "mobile manipulator, torso -> right gripper");
  // A root below the tip's branch point: the path climbs from the root and descends to the tip.
  sd::Scene across = sd::scene_from_root_and_tips(full, sd::RootTipScene{"arm_left_3_link", {"arm_right_2_link"}, {}});
  EXPECT_EQ(across.kept_joints.size(), 5u);  // arm_left_3..1, arm_right_1..2
  across = with_random_locks(full, across, rng);
  expect_exact(compare(full, sd::reduce_model(full, across), across, rng), "mobile manipulator, left arm 3 -> right arm 2");
}

TEST(Reduction, FramesFollowTheirLinks) {
  const sd::Model<double> full = sd::build_model_from_urdf_string(sd_test::mobile_manipulator_urdf(7));
  std::mt19937 rng(5);
  const sd::Scene scene = with_random_locks(full, arm("arm_right_"), rng);
  const sd::Model<double> reduced = sd::reduce_model(full, scene);
  sd::Data<double> full_data(full), reduced_data(reduced);
  VectorXd q = VectorXd::Zero(full.nq);
  for (const auto& [name, position] : scene.locked_positions) q[full.joints[full.jointBody(name)].idx_q] = position;
  VectorXd q_red(reduced.nq);
  for (int i = 1; i < reduced.nbodies(); ++i) {
    const double value = 0.3 * i;
    q_red[reduced.joints[i].idx_q] = value;
    q[full.joints[full.jointBody(reduced.joint_names[i])].idx_q] = value;
  }
  sd::forward_kinematics(full, full_data, q);
  sd::forward_kinematics(reduced, reduced_data, q_red);
  for (const auto& frame : full.frames) {
    const auto& a = full_data.X_frame_base[full.frameIndex(frame.name)];
    const auto& b = reduced_data.X_frame_base[reduced.frameIndex(frame.name)];
    EXPECT_LE((a.E - b.E).norm() + (a.r - b.r).norm(), 1e-13) << frame.name;
  }
}

TEST(Reduction, UnknownNamesAreRejectedNamingThem) {
  const sd::Model<double> full = sd::build_model_from_urdf_file(sd_test::robot_path("talos.urdf"));
  auto expect_message = [](auto&& make, const std::string& part) {
    try {
      make();
      ADD_FAILURE() << "no error for " << part;
    } catch (const sd::SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  expect_message([&] { sd::reduce_model(full, sd::Scene{{"arm_left_9_joint"}, {}}); }, "'arm_left_9_joint'");
  expect_message([&] { sd::reduce_model(full, sd::Scene{{"arm_left_1_joint"}, {{"knee_of_nobody", 0.1}}}); },
                 "'knee_of_nobody'");
  expect_message([&] { sd::scene_from_root_and_tips(full, sd::RootTipScene{"torso_9_link", {"arm_left_7_link"}, {}}); },
                 "'torso_9_link'");
  expect_message([&] { sd::scene_from_root_and_tips(full, sd::RootTipScene{"base_link", {"hand_of_nobody"}, {}}); },
                 "'hand_of_nobody'");
}
