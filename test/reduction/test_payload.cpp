// Payloads against an extra fixed link in the URDF, and against the 3-D weight of a held-still
// payload.
#include <gtest/gtest.h>

#include <fstream>

#include "spatial_dynamics/reduction/payload.hpp"
#include "test_utils.hpp"

namespace sd = spatial_dynamics;
using Eigen::VectorXd;

namespace {

std::string read(const std::string& path) {
  std::ifstream file(path);
  return std::string((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
}

const sd::Payload kBox{2.0, Eigen::Vector3d(0.01, -0.02, 0.08),
                       (Eigen::Matrix3d() << 0.012, 0.001, -0.002, 0.001, 0.015, 0.0005, -0.002, 0.0005, 0.009).finished()};

}  // namespace

TEST(Payload, EqualsAnExtraFixedLink) {
  const std::string urdf = read(sd_test::robot_path("panda.urdf"));
  const std::string extra =
      "<link name='box'><inertial><origin xyz='0.01 -0.02 0.08'/><mass value='2'/>"
      "<inertia ixx='0.012' ixy='0.001' ixz='-0.002' iyy='0.015' iyz='0.0005' izz='0.009'/></inertial></link>"
      "<joint name='box_mount' type='fixed'><parent link='panda_hand'/><child link='box'/></joint></robot>";
  const sd::Model<double> with_link = sd::build_model_from_urdf_string(urdf.substr(0, urdf.rfind("</robot>")) + extra);
  const sd::Model<double> bare = sd::build_model_from_urdf_string(urdf);
  const sd::Model<double> loaded = sd::with_payloads(bare, {{"panda_hand", kBox}});
  sd::Data<double> d1(with_link), d2(loaded);
  std::mt19937 rng(8);
  for (int s = 0; s < 50; ++s) {
    const VectorXd q = sd_test::random_configuration(bare, rng);
    const VectorXd qd = sd_test::random_vector(bare.nv, rng), qdd = sd_test::random_vector(bare.nv, rng);
    EXPECT_LE(sd_test::relative_error(sd::rnea(loaded, d2, q, qd, qdd), sd::rnea(with_link, d1, q, qd, qdd)), 1e-12);
    EXPECT_LE(sd_test::relative_error(sd::crba(loaded, d2, q), sd::crba(with_link, d1, q)), 1e-12);
  }
}

// Held still, the payload adds its weight: Δg = −Jᵀ w, w = (c × m g ; m g) at the frame origin in
// base-aligned axes, c the centre of mass relative to that origin.
TEST(Payload, WeightAppearsInGravityTorques) {
  const sd::Model<double> bare = sd::build_model_from_urdf_file(sd_test::robot_path("panda.urdf"));
  const sd::Model<double> loaded = sd::with_payloads(bare, {{"panda_hand", kBox}});
  sd::Data<double> d1(bare), d2(loaded);
  std::mt19937 rng(9);
  const int frame = bare.frameIndex("panda_hand");
  for (int s = 0; s < 20; ++s) {
    const VectorXd q = sd_test::random_configuration(bare, rng);
    const VectorXd delta = sd::gravity_torques(loaded, d2, q) - sd::gravity_torques(bare, d1, q);
    const Eigen::MatrixXd J = sd::frame_jacobian(bare, d1, q, frame, sd::ReferenceFrame::RootAligned);
    const Eigen::Vector3d c = d1.X_frame_base[frame].rotation() * kBox.center_of_mass;
    const Eigen::Vector3d weight = kBox.mass * bare.gravity;
    Eigen::Matrix<double, 6, 1> w;
    w << c.cross(weight), weight;
    EXPECT_LE(sd_test::relative_error(delta, VectorXd(-J.transpose() * w)), 1e-12);
  }
}

TEST(Payload, BadPayloadsAreRejectedNamingTheFrame) {
  const sd::Model<double> bare = sd::build_model_from_urdf_file(sd_test::robot_path("panda.urdf"));
  try {
    sd::with_payloads(bare, {{"no_such_frame", kBox}});
    FAIL();
  } catch (const sd::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("'no_such_frame'"), std::string::npos) << e.what();
  }
  sd::Payload negative = kBox;
  negative.mass = -1;
  try {
    sd::with_payloads(bare, {{"panda_hand", negative}});
    FAIL();
  } catch (const sd::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("'panda_hand'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("negative"), std::string::npos) << e.what();
  }
}
