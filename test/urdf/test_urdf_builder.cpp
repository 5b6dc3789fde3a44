// URDF → Model: rejections with messages naming the culprit, accepted corner cases, exact
// inertia handling (inertial origin, fixed-joint merge, root inertia), mimic joints, limits,
// and every robot of the shared set checked against its URDF.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include <Eigen/Geometry>
#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>

#include "rejection.hpp"
#include "test_utils.hpp"

namespace {

namespace sd = spatial_dynamics;
using sd_test::robot_files;
using sd_test::robot_path;

constexpr double kInf = std::numeric_limits<double>::infinity();

// ---- small URDF builder -------------------------------------------------------------------

std::string robot(const std::string& body) {
  return "<?xml version=\"1.0\"?>\n<robot name=\"test_robot\">\n" + body + "</robot>\n";
}

std::string origin(const std::string& xyz, const std::string& rpy) {
  return "<origin xyz=\"" + xyz + "\" rpy=\"" + rpy + "\"/>";
}

/// <inertial> with the tensor given as "ixx ixy ixz iyy iyz izz".
std::string inertial(const std::string& mass, const std::string& tensor = "0.1 0 0 0.1 0 0.1",
                     const std::string& origin_tag = "") {
  std::istringstream in(tensor);
  std::string c[6];
  for (auto& x : c) in >> x;
  return "<inertial>" + origin_tag + "<mass value=\"" + mass + "\"/><inertia ixx=\"" + c[0] + "\" ixy=\"" + c[1] +
         "\" ixz=\"" + c[2] + "\" iyy=\"" + c[3] + "\" iyz=\"" + c[4] + "\" izz=\"" + c[5] + "\"/></inertial>";
}

std::string link(const std::string& name, const std::string& inertial_tag = inertial("1")) {
  return "<link name=\"" + name + "\">" + inertial_tag + "</link>\n";
}

/// A joint; revolute and prismatic joints get a default <limit> (urdfdom requires one).
std::string joint(const std::string& name, const std::string& type, const std::string& parent,
                  const std::string& child, const std::string& extra = "") {
  std::string limit;
  if ((type == "revolute" || type == "prismatic") && extra.find("<limit") == std::string::npos)
    limit = "<limit lower=\"-1\" upper=\"1\" velocity=\"1\" effort=\"1\"/>";
  return "<joint name=\"" + name + "\" type=\"" + type + "\"><parent link=\"" + parent + "\"/><child link=\"" + child +
         "\"/>" + extra + limit + "</joint>\n";
}

/// base —j1 (revolute)→ l1, with `l1_inertial` as l1's <inertial> and `j1_extra` inside j1.
std::string two_link(const std::string& l1_inertial, const std::string& j1_extra = "<axis xyz=\"0 0 1\"/>") {
  return robot(link("base") + link("l1", l1_inertial) + joint("j1", "revolute", "base", "l1", j1_extra));
}

using sd_test::rejection;

// ---- independent reference computations ---------------------------------------------------

/// Rotation of a URDF rpy: Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Matrix3d rpy_rotation(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Matrix3d tensor(double ixx, double ixy, double ixz, double iyy, double iyz, double izz) {
  Eigen::Matrix3d I;
  I << ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz;
  return I;
}

/// Mass, first moment and inertia about the origin of a point body with centroidal tensor I_c
/// (already in the target axes) at centre of mass c: Ī_O = Ī_c + m (cᵀc 1 − c cᵀ).
struct Reference {
  double mass = 0;
  Eigen::Vector3d h = Eigen::Vector3d::Zero();
  Eigen::Matrix3d I_O = Eigen::Matrix3d::Zero();

  void add(double m, const Eigen::Vector3d& c, const Eigen::Matrix3d& I_c) {
    mass += m;
    h += m * c;
    I_O += I_c + m * (c.dot(c) * Eigen::Matrix3d::Identity() - c * c.transpose());
  }
};

double rel(double x, double ref) { return std::abs(x - ref) / std::max(std::abs(ref), 1e-300); }

void expect_inertia_matches(const sd::RigidInertia<double>& got, const Reference& ref, double tol) {
  EXPECT_LE(rel(got.mass, ref.mass), tol) << got.mass << " vs " << ref.mass;
  EXPECT_LE(sd_test::relative_error(got.first_moment, ref.h), tol) << got.first_moment.transpose() << " vs "
                                                                    << ref.h.transpose();
  EXPECT_LE(sd_test::relative_error(got.rotational_inertia, ref.I_O), tol) << got.rotational_inertia << "\nvs\n"
                                                                          << ref.I_O;
}

// ==== 1. rejections ==========================================================================

TEST(UrdfRejection, NegativeMass) {
  const std::string msg = rejection(two_link(inertial("-0.5")));
  EXPECT_CONTAINS(msg, "l1");
  EXPECT_CONTAINS(msg, "negative");
  EXPECT_CONTAINS(msg, "-0.5");
}

TEST(UrdfRejection, NanMass) {
  // urdfdom does not read "nan" as a double: its logged error must reach our message.
  const std::string msg = rejection(two_link(inertial("nan")));
  EXPECT_CONTAINS(msg, "l1");
  EXPECT_CONTAINS(msg, "mass");
  EXPECT_CONTAINS(msg, "nan");
}

TEST(UrdfRejection, InfMass) {
  const std::string msg = rejection(two_link(inertial("inf")));
  EXPECT_CONTAINS(msg, "l1");
  EXPECT_CONTAINS(msg, "mass");
  EXPECT_CONTAINS(msg, "inf");
}

TEST(UrdfRejection, InertiaEntryNotANumber) {
  // urdfdom logs the error but still returns the model, with this link's tensor zeroed.
  const std::string msg = rejection(two_link(inertial("1", "0.1 0 0 abc 0 0.1")));
  EXPECT_CONTAINS(msg, "l1");
  EXPECT_CONTAINS(msg, "iyy");
  EXPECT_CONTAINS(msg, "not a valid");
}

TEST(UrdfRejection, NonFiniteMassInParsedModel) {
  // The builder's own check, reached through an already parsed model.
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), kInf, -kInf}) {
    urdf::ModelInterfaceSharedPtr parsed = urdf::parseURDF(two_link(inertial("1")));
    ASSERT_TRUE(parsed);
    parsed->links_.at("l1")->inertial->mass = bad;
    try {
      sd::build_model(*parsed);
      ADD_FAILURE() << "mass " << bad << " accepted";
    } catch (const sd::ModelError& e) {
      EXPECT_CONTAINS(e.what(), "'l1'");
      EXPECT_CONTAINS(e.what(), "not finite");
    }
  }
}

TEST(UrdfRejection, NonFiniteInertiaInParsedModel) {
  urdf::ModelInterfaceSharedPtr parsed = urdf::parseURDF(two_link(inertial("1")));
  ASSERT_TRUE(parsed);
  parsed->links_.at("l1")->inertial->iyz = std::numeric_limits<double>::quiet_NaN();
  try {
    sd::build_model(*parsed);
    ADD_FAILURE() << "NaN inertia accepted";
  } catch (const sd::ModelError& e) {
    EXPECT_CONTAINS(e.what(), "'l1'");
    EXPECT_CONTAINS(e.what(), "non-finite");
  }
}

TEST(UrdfRejection, InertiaNotPositiveSemiDefinite) {
  const std::string msg = rejection(two_link(inertial("1", "-1 0 0 1 0 1")));
  EXPECT_CONTAINS(msg, "l1");
  EXPECT_CONTAINS(msg, "positive semi-definite");
}

TEST(UrdfRejection, InertiaViolatesTriangleInequality) {
  const std::string msg = rejection(two_link(inertial("1", "1 0 0 1 0 3")));
  EXPECT_CONTAINS(msg, "l1");
  EXPECT_CONTAINS(msg, "triangle inequality");
}

TEST(UrdfRejection, RotatedInertiaViolatesTriangleInequality) {
  // diag(1, 1, 3) seen in rotated axes: every diagonal entry alone looks plausible.
  // Principal axis of the 3 along (1, 1, 1)/√3: I = 1 + 2 n nᵀ, diagonal 5/3, off-diagonal 2/3.
  const Eigen::Matrix3d R =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), Eigen::Vector3d(1, 1, 1)).toRotationMatrix();
  const Eigen::Matrix3d I = R * Eigen::Vector3d(1, 1, 3).asDiagonal() * R.transpose();
  ASSERT_GT(std::abs(I(0, 1)), 0.1);
  ASSERT_LE(I(2, 2), I(0, 0) + I(1, 1));  // the diagonal alone passes the triangle test
  std::ostringstream t;
  t.precision(17);
  t << I(0, 0) << ' ' << I(0, 1) << ' ' << I(0, 2) << ' ' << I(1, 1) << ' ' << I(1, 2) << ' ' << I(2, 2);
  const std::string msg = rejection(two_link(inertial("1", t.str())));
  EXPECT_CONTAINS(msg, "l1");
  EXPECT_CONTAINS(msg, "triangle inequality");
}

TEST(UrdfRejection, ZeroJointAxis) {
  const std::string msg = rejection(two_link(inertial("1"), "<axis xyz=\"0 0 0\"/>"));
  EXPECT_CONTAINS(msg, "'j1'");
  EXPECT_CONTAINS(msg, "axis is zero");
}

TEST(UrdfBuilder, FloatingJointInsideTreeIsAFreeJointWithTheRootsCoordinateNames) {
  const std::string xml = robot(link("base") + link("l1", inertial("1")) + link("l2", inertial("2")) +
                                joint("j1", "revolute", "base", "l1", "<axis xyz=\"1 0 0\"/>") +
                                joint("float_j", "floating", "l1", "l2"));
  const sd::Model<double> model = sd::build_model_from_urdf_string(xml);
  ASSERT_EQ(model.nbodies(), 3);
  EXPECT_EQ(model.joints[2].type, sd::JointType::Free);
  EXPECT_EQ(model.parent[2], 1);
  EXPECT_EQ(model.nq, 8);
  EXPECT_EQ(model.nv, 7);
  EXPECT_TRUE(model.has_multi_dof_tree_joints);
  const std::vector<std::string> velocities = model.velocityNames();
  EXPECT_EQ(velocities, (std::vector<std::string>{"j1", "float_j/wx", "float_j/wy", "float_j/wz", "float_j/vx",
                                                  "float_j/vy", "float_j/vz"}));
  EXPECT_EQ(model.positionNames().back(), "float_j/qw");
}

TEST(UrdfBuilder, PlanarJointHasThreeCoordinatesAndInPlaneAxesPerpendicularToTheNormal) {
  for (const char* normal : {"0 0 1", "1 0 0", "0 1 0", "0.3 -0.4 0.5"}) {
    const std::string xml = robot(link("base") + link("l1", inertial("1")) +
                                  joint("plane_j", "planar", "base", "l1", std::string("<axis xyz=\"") + normal + "\"/>"));
    const sd::Model<double> model = sd::build_model_from_urdf_string(xml);
    const sd::Joint<double>& j = model.joints[1];
    EXPECT_EQ(j.type, sd::JointType::Planar);
    EXPECT_EQ(model.nq, 3);
    EXPECT_EQ(model.nv, 3);
    EXPECT_EQ(model.velocityNames(), (std::vector<std::string>{"plane_j/x", "plane_j/y", "plane_j/yaw"}));
    EXPECT_NEAR(j.axis.norm(), 1.0, 1e-15) << normal;
    EXPECT_NEAR(j.plane_x.norm(), 1.0, 1e-15) << normal;
    EXPECT_NEAR(j.plane_x.dot(j.axis), 0.0, 1e-15) << normal;
    EXPECT_LT((j.plane_y - j.axis.cross(j.plane_x)).norm(), 1e-15) << normal;
  }
  const sd::Model<double> z = sd::build_model_from_urdf_string(
      robot(link("base") + link("l1", inertial("1")) + joint("plane_j", "planar", "base", "l1", "<axis xyz=\"0 0 1\"/>")));
  EXPECT_EQ(z.joints[1].plane_x, Eigen::Vector3d::UnitX());  // the joint frame's own x and y
  EXPECT_EQ(z.joints[1].plane_y, Eigen::Vector3d::UnitY());
}

TEST(UrdfRejection, PlanarJointWithZeroAxisOrMimic) {
  std::string msg = rejection(robot(link("base") + link("l1", inertial("1")) +
                                    joint("plane_j", "planar", "base", "l1", "<axis xyz=\"0 0 0\"/>")));
  EXPECT_CONTAINS(msg, "'plane_j'");
  EXPECT_CONTAINS(msg, "axis is zero");
  msg = rejection(robot(link("base") + link("l1", inertial("1")) + link("l2", inertial("1")) +
                        joint("j1", "revolute", "base", "l1", "<axis xyz=\"1 0 0\"/>") +
                        joint("plane_j", "planar", "l1", "l2", "<axis xyz=\"0 0 1\"/><mimic joint=\"j1\"/>")));
  EXPECT_CONTAINS(msg, "'plane_j'");
  EXPECT_CONTAINS(msg, "cannot mimic");
}

TEST(UrdfBuilder, FloatingJointInsideTreeWithFloatingBaseOption) {
  sd::ModelBuildOptions options;
  options.floating_base = true;
  const sd::Model<double> model = sd::build_model_from_urdf_string(
      robot(link("base", inertial("1")) + link("l1", inertial("1")) + joint("float_j", "floating", "base", "l1")), options);
  ASSERT_EQ(model.nbodies(), 3);
  EXPECT_EQ(model.joints[1].type, sd::JointType::Free);  // the root
  EXPECT_EQ(model.joints[2].type, sd::JointType::Free);
  EXPECT_EQ(model.nv, 12);
  EXPECT_TRUE(model.has_multi_dof_tree_joints);
}

TEST(UrdfRejection, MalformedXml) {
  const std::string full = two_link(inertial("1"));
  const std::string truncated = full.substr(0, full.find("<joint") + 20);
  const std::string msg = rejection(truncated);
  EXPECT_EQ(msg.rfind("malformed URDF", 0), 0u) << msg;
  EXPECT_GT(msg.size(), std::string("malformed URDF: ").size());
}

TEST(UrdfRejection, NotXmlAtAll) {
  const std::string msg = rejection("this is not a robot");
  EXPECT_EQ(msg.rfind("malformed URDF", 0), 0u) << msg;
}

TEST(UrdfRejection, MissingFile) {
  try {
    sd::build_model_from_urdf_file("/nonexistent/dir/robot.urdf");
    ADD_FAILURE() << "missing file accepted";
  } catch (const sd::ModelError& e) {
    EXPECT_CONTAINS(e.what(), "/nonexistent/dir/robot.urdf");
    EXPECT_CONTAINS(e.what(), "cannot read");
  }
}

TEST(UrdfRejection, MimicOfUnknownJoint) {
  const std::string xml = robot(link("base") + link("l1") + link("l2") +
                                joint("j1", "revolute", "base", "l1", "<axis xyz=\"0 0 1\"/>") +
                                joint("j2", "revolute", "l1", "l2", "<axis xyz=\"0 0 1\"/><mimic joint=\"ghost\"/>"));
  const std::string msg = rejection(xml);
  EXPECT_CONTAINS(msg, "'j2'");
  EXPECT_CONTAINS(msg, "'ghost'");
  EXPECT_CONTAINS(msg, "mimics");
}

TEST(UrdfRejection, MimicOfFixedJoint) {
  const std::string xml = robot(link("base") + link("l1") + link("l2") + joint("weld", "fixed", "base", "l1") +
                                joint("j2", "revolute", "l1", "l2", "<axis xyz=\"0 0 1\"/><mimic joint=\"weld\"/>"));
  const std::string msg = rejection(xml);
  EXPECT_CONTAINS(msg, "'j2'");
  EXPECT_CONTAINS(msg, "'weld'");
  EXPECT_CONTAINS(msg, "not a revolute, continuous or prismatic");
}

// ==== 2. acceptances ========================================================================

TEST(UrdfAcceptance, MasslessIntermediateLink) {
  const std::string xml = robot(link("base") + link("mid", "") + link("tip", inertial("2")) +
                                joint("j1", "revolute", "base", "mid", "<axis xyz=\"0 0 1\"/>") +
                                joint("j2", "revolute", "mid", "tip", "<axis xyz=\"0 1 0\"/>"));
  const auto model = sd::build_model_from_urdf_string(xml);
  ASSERT_EQ(model.nbodies(), 3);
  EXPECT_EQ(model.nv, 2);
  const int mid = model.jointBody("j1");
  EXPECT_EQ(model.body_names[mid], "mid");
  EXPECT_EQ(model.inertia[mid].mass, 0.0);
  EXPECT_EQ(model.inertia[mid].rotational_inertia.norm(), 0.0);
  EXPECT_EQ(model.inertia[model.jointBody("j2")].mass, 2.0);
}

TEST(UrdfAcceptance, LeafLinkWithoutInertial) {
  const std::string xml = robot(link("base") + link("l1", inertial("1.5")) + link("leaf", "") +
                                joint("j1", "revolute", "base", "l1", "<axis xyz=\"1 0 0\"/>") +
                                joint("j2", "prismatic", "l1", "leaf", "<axis xyz=\"0 0 1\"/>"));
  const auto model = sd::build_model_from_urdf_string(xml);
  ASSERT_EQ(model.nbodies(), 3);
  const int leaf = model.jointBody("j2");
  EXPECT_EQ(model.body_names[leaf], "leaf");
  EXPECT_EQ(model.joints[leaf].type, sd::JointType::Prismatic);
  EXPECT_EQ(model.inertia[leaf].mass, 0.0);
  EXPECT_EQ(model.inertia[leaf].first_moment.norm(), 0.0);
  EXPECT_EQ(model.inertia[model.jointBody("j1")].mass, 1.5);
}

TEST(UrdfAcceptance, NonUnitAxisIsNormalised) {
  const auto model = sd::build_model_from_urdf_string(two_link(inertial("1"), "<axis xyz=\"0 0 2\"/>"));
  const auto& j = model.joints[model.jointBody("j1")];
  EXPECT_EQ(j.axis, Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(j.axis_kind, sd::AxisKind::Z);
}

TEST(UrdfAcceptance, GeneralNonUnitAxisIsNormalised) {
  const auto model = sd::build_model_from_urdf_string(two_link(inertial("1"), "<axis xyz=\"3 0 4\"/>"));
  const auto& j = model.joints[model.jointBody("j1")];
  EXPECT_NEAR(j.axis.norm(), 1.0, 1e-15);
  EXPECT_LE((j.axis - Eigen::Vector3d(0.6, 0, 0.8)).norm(), 1e-15);
  EXPECT_EQ(j.axis_kind, sd::AxisKind::General);
}

TEST(UrdfAcceptance, NegativeAxisIsGeneral) {
  const auto model = sd::build_model_from_urdf_string(two_link(inertial("1"), "<axis xyz=\"0 -1 0\"/>"));
  const auto& j = model.joints[model.jointBody("j1")];
  EXPECT_EQ(j.axis, Eigen::Vector3d(0, -1, 0));
  EXPECT_EQ(j.axis_kind, sd::AxisKind::General);
}

TEST(UrdfAcceptance, AxisKindsAndDefaultAxis) {
  // urdfdom's default axis is (1, 0, 0).
  const std::string xml = robot(link("base") + link("a") + link("b") + link("c") + link("d") +
                                joint("jx", "revolute", "base", "a", "<axis xyz=\"1 0 0\"/>") +
                                joint("jy", "continuous", "a", "b", "<axis xyz=\"0 1 0\"/>") +
                                joint("jz", "prismatic", "b", "c", "<axis xyz=\"0 0 1\"/>") +
                                joint("jdefault", "revolute", "c", "d"));
  const auto model = sd::build_model_from_urdf_string(xml);
  EXPECT_EQ(model.joints[model.jointBody("jx")].axis_kind, sd::AxisKind::X);
  EXPECT_EQ(model.joints[model.jointBody("jy")].axis_kind, sd::AxisKind::Y);
  EXPECT_EQ(model.joints[model.jointBody("jy")].type, sd::JointType::Revolute);
  EXPECT_EQ(model.joints[model.jointBody("jz")].axis_kind, sd::AxisKind::Z);
  EXPECT_EQ(model.joints[model.jointBody("jz")].type, sd::JointType::Prismatic);
  EXPECT_EQ(model.joints[model.jointBody("jdefault")].axis, Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(model.joints[model.jointBody("jdefault")].axis_kind, sd::AxisKind::X);
  // Index bookkeeping of a chain: body i has q/v coordinate i−1 and parent i−1.
  for (int i = 1; i < model.nbodies(); ++i) {
    EXPECT_EQ(model.parent[i], i - 1);
    EXPECT_EQ(model.joints[i].idx_q, i - 1);
    EXPECT_EQ(model.joints[i].idx_v, i - 1);
  }
}

TEST(UrdfAcceptance, PointMassAndZeroMassAccepted) {
  // A point mass (zero tensor) and a zero mass are physical; borderline triangle equality too.
  const std::string xml = robot(link("base") + link("l1", inertial("0.7", "0 0 0 0 0 0")) +
                                link("l2", inertial("0", "0 0 0 0 0 0")) + link("l3", inertial("1", "1 0 0 1 0 2")) +
                                joint("j1", "revolute", "base", "l1", "<axis xyz=\"0 0 1\"/>") +
                                joint("j2", "revolute", "l1", "l2", "<axis xyz=\"0 0 1\"/>") +
                                joint("j3", "revolute", "l2", "l3", "<axis xyz=\"0 0 1\"/>"));
  const auto model = sd::build_model_from_urdf_string(xml);
  EXPECT_EQ(model.inertia[model.jointBody("j1")].mass, 0.7);
  EXPECT_EQ(model.inertia[model.jointBody("j2")].mass, 0.0);
  EXPECT_EQ(model.inertia[model.jointBody("j3")].rotational_inertia(2, 2), 2.0);
}

// ==== 3. exact inertia of a link with a rotated, offset inertial frame =======================

TEST(UrdfInertia, InertialOriginAndFullTensor) {
  const double m = 2.75;
  const Eigen::Vector3d c(0.12, -0.31, 0.07);
  const double roll = 0.4, pitch = -1.1, yaw = 2.3;
  const Eigen::Matrix3d I = tensor(0.31, -0.021, 0.013, 0.27, 0.034, 0.19);
  const std::string xml = robot(
      link("base") +
      link("arm", inertial("2.75", "0.31 -0.021 0.013 0.27 0.034 0.19", origin("0.12 -0.31 0.07", "0.4 -1.1 2.3"))) +
      joint("j1", "revolute", "base", "arm", origin("0.5 -0.2 1.3", "0.3 0.2 -0.9") + "<axis xyz=\"0 0 1\"/>"));
  const auto model = sd::build_model_from_urdf_string(xml);
  const int body = model.jointBody("j1");
  ASSERT_EQ(model.body_names[body], "arm");

  const Eigen::Matrix3d R = rpy_rotation(roll, pitch, yaw);
  Reference ref;
  ref.add(m, c, R * I * R.transpose());
  expect_inertia_matches(model.inertia[body], ref, 1e-14);
  EXPECT_EQ(model.inertia[body].mass, m);
  EXPECT_LE(sd_test::relative_error(model.inertia[body].centerOfMass(), c), 1e-14);
  EXPECT_LE(sd_test::relative_error(model.inertia[body].inertiaAboutCenterOfMass(), R * I * R.transpose()), 1e-13);

  // The joint origin sits in X_tree only: ^{J}X_{parent} has the joint frame's pose in the parent.
  const Eigen::Matrix3d Rj = rpy_rotation(0.3, 0.2, -0.9);
  EXPECT_LE((model.X_tree[body].rotation() - Rj).norm(), 1e-15);
  EXPECT_LE((model.X_tree[body].translation() - Eigen::Vector3d(0.5, -0.2, 1.3)).norm(), 1e-15);
  // Base link carries the default inertial of link(): 1 kg, 0.1·1 at its origin.
  EXPECT_EQ(model.inertia[0].mass, 1.0);
  EXPECT_EQ(model.inertia[0].rotational_inertia, 0.1 * Eigen::Matrix3d::Identity());
}

// ==== 4. fixed-joint merge ====================================================================

TEST(UrdfInertia, FixedJointMergeAndFrames) {
  // base —j1 (revolute)→ P —weld1 (fixed)→ C —weld2 (fixed)→ D: P, C and D form one body.
  const std::string xml = robot(
      link("base") +
      link("P", inertial("1.3", "0.05 0.002 -0.001 0.04 0.003 0.03", origin("0.01 0.02 -0.03", "0.1 0.2 0.3"))) +
      link("C", inertial("0.8", "0.02 -0.001 0.0005 0.025 0.0015 0.018", origin("-0.05 0.04 0.02", "-0.6 0.5 1.2"))) +
      link("D", inertial("0.35", "0.004 0 0 0.005 0 0.006", origin("0.0 0.0 0.1", "0 0 0"))) +
      joint("j1", "revolute", "base", "P", origin("0 0 0.4", "0 0 0") + "<axis xyz=\"0 1 0\"/>") +
      joint("weld1", "fixed", "P", "C", origin("0.2 -0.1 0.3", "0.7 -0.4 1.9")) +
      joint("weld2", "fixed", "C", "D", origin("0.05 0.15 -0.2", "-1.2 0.3 0.25")));
  const auto model = sd::build_model_from_urdf_string(xml);
  ASSERT_EQ(model.nbodies(), 2);
  EXPECT_EQ(model.nv, 1);
  EXPECT_FALSE(model.hasJoint("weld1"));
  EXPECT_FALSE(model.hasJoint("weld2"));
  const int body = model.jointBody("j1");
  ASSERT_EQ(body, 1);
  EXPECT_EQ(model.body_names[body], "P");

  // Poses in body (P) coordinates.
  const Eigen::Matrix3d R_C = rpy_rotation(0.7, -0.4, 1.9);
  const Eigen::Vector3d p_C(0.2, -0.1, 0.3);
  const Eigen::Matrix3d R_D = R_C * rpy_rotation(-1.2, 0.3, 0.25);
  const Eigen::Vector3d p_D = p_C + R_C * Eigen::Vector3d(0.05, 0.15, -0.2);

  Reference ref;
  {
    const Eigen::Matrix3d R = rpy_rotation(0.1, 0.2, 0.3);
    ref.add(1.3, Eigen::Vector3d(0.01, 0.02, -0.03), R * tensor(0.05, 0.002, -0.001, 0.04, 0.003, 0.03) * R.transpose());
  }
  {
    const Eigen::Matrix3d R = R_C * rpy_rotation(-0.6, 0.5, 1.2);
    ref.add(0.8, p_C + R_C * Eigen::Vector3d(-0.05, 0.04, 0.02),
            R * tensor(0.02, -0.001, 0.0005, 0.025, 0.0015, 0.018) * R.transpose());
  }
  ref.add(0.35, p_D + R_D * Eigen::Vector3d(0, 0, 0.1), R_D * tensor(0.004, 0, 0, 0.005, 0, 0.006) * R_D.transpose());
  expect_inertia_matches(model.inertia[body], ref, 1e-14);
  EXPECT_NEAR(model.inertia[body].mass, 2.45, 1e-15);

  // Every link is a frame; merged links sit on the body at the fixed joints' poses.
  ASSERT_EQ(model.frames.size(), 4u);
  const auto& fP = model.frames[model.frameIndex("P")];
  EXPECT_EQ(fP.body, body);
  EXPECT_LE((fP.X_frame_body.rotation() - Eigen::Matrix3d::Identity()).norm(), 0.0);
  EXPECT_LE(fP.X_frame_body.translation().norm(), 0.0);
  const auto& fC = model.frames[model.frameIndex("C")];
  EXPECT_EQ(fC.body, body);
  EXPECT_LE((fC.X_frame_body.rotation() - R_C).norm(), 1e-15);
  EXPECT_LE((fC.X_frame_body.translation() - p_C).norm(), 1e-15);
  const auto& fD = model.frames[model.frameIndex("D")];
  EXPECT_EQ(fD.body, body);
  EXPECT_LE((fD.X_frame_body.rotation() - R_D).norm(), 1e-14);
  EXPECT_LE((fD.X_frame_body.translation() - p_D).norm(), 1e-15);
  // A point given in D coordinates maps to body coordinates through the frame's pose.
  const Eigen::Vector3d x_D(0.3, -0.2, 0.9);
  const auto X_body_D = fD.X_frame_body.inverse();  // ^BX_D
  EXPECT_LE((X_body_D.rotation().transpose() * (x_D - X_body_D.translation()) - (p_D + R_D * x_D)).norm(), 1e-14);
  const auto& fbase = model.frames[model.frameIndex("base")];
  EXPECT_EQ(fbase.body, 0);
  EXPECT_THROW(model.frameIndex("weld1"), std::out_of_range);
}

TEST(UrdfInertia, MovableJointBelowMergedLinkUsesComposedTreeTransform) {
  // base —weld (fixed, offset)→ C —j (revolute, offset)→ E: X_tree of j composes both origins.
  const std::string xml = robot(link("base") + link("C") + link("E") +
                                joint("weld", "fixed", "base", "C", origin("0.1 0.2 0.3", "0.5 0 0")) +
                                joint("j", "revolute", "C", "E", origin("0.4 0 -0.1", "0 0.3 0") +
                                                                     "<axis xyz=\"0 0 1\"/>"));
  const auto model = sd::build_model_from_urdf_string(xml);
  ASSERT_EQ(model.nbodies(), 2);
  const Eigen::Matrix3d R_C = rpy_rotation(0.5, 0, 0);
  const Eigen::Matrix3d R_E = R_C * rpy_rotation(0, 0.3, 0);
  const Eigen::Vector3d p_E = Eigen::Vector3d(0.1, 0.2, 0.3) + R_C * Eigen::Vector3d(0.4, 0, -0.1);
  EXPECT_LE((model.X_tree[1].rotation() - R_E).norm(), 1e-15);
  EXPECT_LE((model.X_tree[1].translation() - p_E).norm(), 1e-15);
  EXPECT_EQ(model.frames[model.frameIndex("C")].body, 0);
  EXPECT_EQ(model.frames[model.frameIndex("E")].body, 1);
  // Body 0 has the root and C merged: 2 kg of default inertials.
  EXPECT_EQ(model.inertia[0].mass, 2.0);
}

// ==== 5. root inertia =========================================================================

std::string root_model() {
  return robot(link("root", inertial("2", "0.2 0 0 0.3 0 0.4", origin("0.1 0 0", "0 0 0"))) +
               link("root_attachment", inertial("0.5", "0.01 0 0 0.01 0 0.01", origin("0 0 0.05", "0 0 0"))) +
               link("l1", inertial("1")) + link("l2", inertial("0.25")) +
               joint("weld", "fixed", "root", "root_attachment", origin("0 0.3 0", "0 0 1.5707963267948966")) +
               joint("j1", "revolute", "root", "l1", "<axis xyz=\"0 0 1\"/>") +
               joint("j2", "prismatic", "l1", "l2", "<axis xyz=\"1 0 0\"/>"));
}

TEST(UrdfRootInertia, FixedBaseKeepsRootMass) {
  const auto model = sd::build_model_from_urdf_string(root_model());
  EXPECT_FALSE(model.floating_base);
  ASSERT_EQ(model.nbodies(), 3);
  EXPECT_EQ(model.nq, 2);
  EXPECT_EQ(model.nv, 2);
  EXPECT_EQ(model.body_names[0], "root");
  EXPECT_NEAR(model.inertia[0].mass, 2.5, 1e-15);
  // root c = (0.1,0,0); attachment c = (0,0.3,0) + Rz(π/2)(0,0,0.05) = (0,0.3,0.05).
  EXPECT_LE((model.inertia[0].first_moment - Eigen::Vector3d(0.2, 0.15, 0.025)).norm(), 1e-15);
}

TEST(UrdfRootInertia, FloatingBaseKeepsRootMass) {
  const auto fixed = sd::build_model_from_urdf_string(root_model());
  sd::ModelBuildOptions options;
  options.floating_base = true;
  options.gravity = Eigen::Vector3d(0.5, -1.0, -3.7);
  const auto model = sd::build_model_from_urdf_string(root_model(), options);
  EXPECT_TRUE(model.floating_base);
  EXPECT_EQ(model.gravity, Eigen::Vector3d(0.5, -1.0, -3.7));
  const int n = fixed.nv;
  ASSERT_EQ(model.nbodies(), fixed.nbodies() + 1);
  EXPECT_EQ(model.nq, n + 7);
  EXPECT_EQ(model.nv, n + 6);
  EXPECT_EQ(model.body_names[0], "universe");
  EXPECT_EQ(model.body_names[1], "root");
  EXPECT_EQ(model.joint_names[1], "root_joint");
  EXPECT_EQ(model.jointBody("root_joint"), 1);
  EXPECT_EQ(model.joints[1].type, sd::JointType::Free);
  EXPECT_EQ(model.joints[1].nq, 7);
  EXPECT_EQ(model.joints[1].nv, 6);
  EXPECT_EQ(model.joints[1].idx_q, 0);
  EXPECT_EQ(model.joints[1].idx_v, 0);
  EXPECT_EQ(model.parent[1], 0);
  EXPECT_EQ(model.inertia[0].mass, 0.0);
  EXPECT_NEAR(model.inertia[1].mass, 2.5, 1e-15);
  EXPECT_EQ(model.inertia[1].mass, fixed.inertia[0].mass);
  EXPECT_EQ(model.inertia[1].first_moment, fixed.inertia[0].first_moment);
  EXPECT_EQ(model.inertia[1].rotational_inertia, fixed.inertia[0].rotational_inertia);
  // The movable joints follow the free one in q and q̇.
  EXPECT_EQ(model.joints[model.jointBody("j1")].idx_q, 7);
  EXPECT_EQ(model.joints[model.jointBody("j1")].idx_v, 6);
  EXPECT_EQ(model.joints[model.jointBody("j2")].idx_q, 8);
  EXPECT_EQ(model.joints[model.jointBody("j2")].idx_v, 7);
  EXPECT_EQ(model.frames.size(), 4u);  // links only: "universe" is not a URDF link
  EXPECT_FALSE(model.hasFrame("universe"));
  EXPECT_EQ(model.frames[model.frameIndex("root_attachment")].body, 1);
  const auto names = model.velocityNames();
  ASSERT_EQ(names.size(), 8u);
  EXPECT_EQ(names[0], "root_joint/wx");
  EXPECT_EQ(names[6], "j1");
}

TEST(UrdfRootInertia, CustomRootJointName) {
  sd::ModelBuildOptions options;
  options.floating_base = true;
  options.root_joint_name = "free_flyer";
  const auto model = sd::build_model_from_urdf_string(root_model(), options);
  EXPECT_EQ(model.jointBody("free_flyer"), 1);
  EXPECT_FALSE(model.hasJoint("root_joint"));
}

// ==== 6. mimic ================================================================================

TEST(UrdfMimic, PandaFingers) {
  const auto model = sd::build_model_from_urdf_file(robot_path("panda.urdf"));
  EXPECT_EQ(model.nv, 9);
  EXPECT_EQ(model.nq, 9);
  const int master = model.jointBody("panda_finger_joint1");
  const int slave = model.jointBody("panda_finger_joint2");
  const auto& mimic = model.joints[slave].mimic;
  EXPECT_TRUE(mimic.active());
  EXPECT_EQ(mimic.master_body, master);
  EXPECT_EQ(mimic.multiplier, 1.0);
  EXPECT_EQ(mimic.offset, 0.0);
  EXPECT_FALSE(model.joints[master].mimic.active());
  int active = 0;
  for (const auto& j : model.joints) active += j.mimic.active();
  EXPECT_EQ(active, 1);
  EXPECT_EQ(model.joints[slave].type, sd::JointType::Prismatic);
}

TEST(UrdfMimic, TalosGrippers) {
  const auto model = sd::build_model_from_urdf_file(robot_path("talos.urdf"));
  EXPECT_EQ(model.nv, 44);
  int active = 0;
  for (int i = 1; i < model.nbodies(); ++i) {
    const auto& m = model.joints[i].mimic;
    if (!m.active()) continue;
    ++active;
    ASSERT_GT(m.master_body, 0);
    ASSERT_LT(m.master_body, model.nbodies());
    EXPECT_FALSE(model.joints[m.master_body].mimic.active()) << model.joint_names[i];
    EXPECT_TRUE(std::isfinite(m.multiplier));
    EXPECT_NE(m.multiplier, 0.0) << model.joint_names[i];
  }
  EXPECT_EQ(active, 12);
}

TEST(UrdfMimic, MultiplierOffsetAndForwardReference) {
  // The mimic joint comes before its master in the tree: resolution happens after the walk.
  const std::string xml = robot(link("base") + link("a") + link("b") +
                                joint("follower", "revolute", "base", "a",
                                      "<axis xyz=\"0 0 1\"/><mimic joint=\"leader\" multiplier=\"-2.5\" offset=\"0.25\"/>") +
                                joint("leader", "revolute", "a", "b", "<axis xyz=\"0 0 1\"/>"));
  const auto model = sd::build_model_from_urdf_string(xml);
  const auto& mimic = model.joints[model.jointBody("follower")].mimic;
  EXPECT_EQ(mimic.master_body, model.jointBody("leader"));
  EXPECT_EQ(mimic.multiplier, -2.5);
  EXPECT_EQ(mimic.offset, 0.25);
}

// ==== 7. every robot of the shared set ========================================================

struct UrdfFacts {
  double total_mass = 0;
  std::set<std::string> links;
  std::set<std::string> movable_joints;
  std::map<std::string, std::string> child_joint;  // link → joint above it
  std::string root;
};

UrdfFacts urdf_facts(const std::string& path) {
  UrdfFacts facts;
  const urdf::ModelInterfaceSharedPtr parsed = urdf::parseURDFFile(path);
  if (!parsed) {
    ADD_FAILURE() << "urdfdom cannot parse " << path;
    return facts;
  }
  facts.root = parsed->getRoot()->name;
  for (const auto& [name, link] : parsed->links_) {
    facts.links.insert(name);
    if (link->inertial) facts.total_mass += link->inertial->mass;
  }
  for (const auto& [name, joint] : parsed->joints_) {
    facts.child_joint[joint->child_link_name] = name;
    if (joint->type != urdf::Joint::FIXED) facts.movable_joints.insert(name);
  }
  return facts;
}

double total_mass(const sd::Model<double>& model) {
  double m = 0;
  for (const auto& in : model.inertia) m += in.mass;
  return m;
}

void check_against_urdf(const std::string& file, const sd::Model<double>& model, const UrdfFacts& facts) {
  SCOPED_TRACE(file + (model.floating_base ? " (floating)" : " (fixed)"));
  const int extra = model.floating_base ? 1 : 0;
  EXPECT_LE(rel(total_mass(model), facts.total_mass), 1e-12) << total_mass(model) << " vs " << facts.total_mass;
  EXPECT_EQ(model.frames.size(), facts.links.size());
  for (const auto& name : facts.links) EXPECT_TRUE(model.hasFrame(name)) << name;
  EXPECT_EQ(model.nbodies() - 1, static_cast<int>(facts.movable_joints.size()) + extra);
  EXPECT_EQ(model.nv, static_cast<int>(facts.movable_joints.size()) + 6 * extra);
  EXPECT_EQ(model.nq, static_cast<int>(facts.movable_joints.size()) + 7 * extra);
  for (const auto& name : facts.movable_joints) {
    ASSERT_TRUE(model.hasJoint(name)) << name;
  }
  // Each body is defined by one URDF link whose frame is the body frame itself; a link below a
  // movable joint is the body of that joint.
  for (int i = 0; i < model.nbodies(); ++i) {
    if (model.floating_base && i == 0) continue;
    const std::string& name = model.body_names[i];
    ASSERT_TRUE(model.hasFrame(name)) << name;
    const auto& f = model.frames[model.frameIndex(name)];
    EXPECT_EQ(f.body, i) << name;
    EXPECT_EQ(f.X_frame_body.rotation(), Eigen::Matrix3d::Identity()) << name;
    EXPECT_EQ(f.X_frame_body.translation(), Eigen::Vector3d::Zero()) << name;
    if (i > 0 && !(model.floating_base && i == 1)) {
      EXPECT_EQ(facts.child_joint.at(name), model.joint_names[i]);
      EXPECT_LT(model.parent[i], i);
    }
  }
  EXPECT_EQ(model.body_names[model.floating_base ? 1 : 0], facts.root);
  // q and q̇ indices tile [0, nq) and [0, nv).
  int q = 0, v = 0;
  for (int i = 1; i < model.nbodies(); ++i) {
    EXPECT_EQ(model.joints[i].idx_q, q);
    EXPECT_EQ(model.joints[i].idx_v, v);
    q += model.joints[i].nq;
    v += model.joints[i].nv;
    EXPECT_NEAR(model.joints[i].axis.norm(), model.joints[i].type == sd::JointType::Free ? 0.0 : 1.0, 1e-15);
  }
  EXPECT_EQ(q, model.nq);
  EXPECT_EQ(v, model.nv);
}

TEST(UrdfRobots, FixedAndFloatingMatchTheUrdf) {
  for (const auto& file : robot_files()) {
    const UrdfFacts facts = urdf_facts(robot_path(file));
    ASSERT_FALSE(facts.links.empty()) << file;
    const auto fixed = sd::build_model_from_urdf_file(robot_path(file));
    check_against_urdf(file, fixed, facts);
    sd::ModelBuildOptions options;
    options.floating_base = true;
    const auto floating = sd::build_model_from_urdf_file(robot_path(file), options);
    check_against_urdf(file, floating, facts);
    EXPECT_EQ(floating.inertia[1].mass, fixed.inertia[0].mass) << file;
    EXPECT_EQ(floating.inertia[1].rotational_inertia, fixed.inertia[0].rotational_inertia) << file;
  }
}

TEST(UrdfRobots, CountsFromTheRobotSetReadme) {
  // Link count, DoF and total mass [kg] as tabulated in the robot set's README (4 decimals).
  struct Row {
    const char* file;
    std::size_t links;
    int dof;
    double mass;
  };
  const Row rows[] = {{"panda.urdf", 13, 9, 17.4519},
                      {"ur5.urdf", 11, 6, 20.9939},
                      {"talos.urdf", 60, 44, 93.3357},
                      {"solo12.urdf", 17, 12, 2.5000},
                      {"double_pendulum.urdf", 3, 2, 0.7010}};
  for (const Row& row : rows) {
    SCOPED_TRACE(row.file);
    const auto model = sd::build_model_from_urdf_file(robot_path(row.file));
    EXPECT_EQ(model.frames.size(), row.links);
    EXPECT_EQ(model.nv, row.dof);
    EXPECT_EQ(model.nbodies() - 1, row.dof);
    EXPECT_NEAR(total_mass(model), row.mass, 5.1e-5);
  }
}

TEST(UrdfRobots, RootLinkMasses) {
  const auto panda = sd::build_model_from_urdf_file(robot_path("panda.urdf"));
  EXPECT_EQ(panda.body_names[0], "panda_link0");
  EXPECT_NEAR(panda.inertia[0].mass, 0.629769, 1e-12);
  sd::ModelBuildOptions options;
  options.floating_base = true;
  const auto talos = sd::build_model_from_urdf_file(robot_path("talos.urdf"), options);
  EXPECT_EQ(talos.body_names[1], "base_link");
  EXPECT_EQ(talos.nq, 51);
  EXPECT_EQ(talos.nv, 50);
  EXPECT_GE(talos.inertia[1].mass, 15.3628 - 1e-4);  // base_link plus whatever is welded to it
  const auto solo = sd::build_model_from_urdf_file(robot_path("solo12.urdf"), options);
  EXPECT_EQ(solo.nq, 19);
  EXPECT_EQ(solo.nv, 18);
  EXPECT_GE(solo.inertia[1].mass, 1.16115 - 1e-5);
}

TEST(UrdfRobots, Ur5WorldRoot) {
  const auto model = sd::build_model_from_urdf_file(robot_path("ur5.urdf"));
  EXPECT_TRUE(model.hasFrame("world"));
  EXPECT_EQ(model.body_names[0], "world");
  EXPECT_EQ(model.frames[model.frameIndex("world")].body, 0);
  EXPECT_EQ(model.frames[model.frameIndex("base_link")].body, 0);  // fixed to world
  EXPECT_GT(model.inertia[0].mass, 0.0);  // base_link's mass, merged into the massless world
  sd::ModelBuildOptions options;
  options.floating_base = true;
  const auto floating = sd::build_model_from_urdf_file(robot_path("ur5.urdf"), options);
  EXPECT_EQ(floating.body_names[0], "universe");
  EXPECT_EQ(floating.body_names[1], "world");
  EXPECT_EQ(floating.frames[floating.frameIndex("world")].body, 1);
}

// ==== 8. limits ===============================================================================

TEST(UrdfLimits, RevoluteContinuousPrismatic) {
  const std::string xml = robot(
      link("base") + link("a") + link("b") + link("c") + link("d") +
      joint("rev", "revolute", "base", "a",
            "<axis xyz=\"0 0 1\"/><limit lower=\"-1.25\" upper=\"2.5\" velocity=\"3.5\" effort=\"87\"/>") +
      joint("cont", "continuous", "a", "b", "<axis xyz=\"0 1 0\"/><limit velocity=\"5.5\" effort=\"12\"/>") +
      joint("pris", "prismatic", "b", "c",
            "<axis xyz=\"1 0 0\"/><limit lower=\"0\" upper=\"0.04\" velocity=\"0.2\" effort=\"20\"/>") +
      joint("cont_free", "continuous", "c", "d", "<axis xyz=\"0 0 1\"/>"));
  const auto model = sd::build_model_from_urdf_string(xml);
  const auto& rev = model.joints[model.jointBody("rev")].limits;
  EXPECT_EQ(rev.position_lower, -1.25);
  EXPECT_EQ(rev.position_upper, 2.5);
  EXPECT_EQ(rev.velocity, 3.5);
  EXPECT_EQ(rev.effort, 87.0);
  const auto& cont = model.joints[model.jointBody("cont")].limits;
  EXPECT_EQ(cont.position_lower, -kInf);
  EXPECT_EQ(cont.position_upper, kInf);
  EXPECT_EQ(cont.velocity, 5.5);
  EXPECT_EQ(cont.effort, 12.0);
  const auto& pris = model.joints[model.jointBody("pris")].limits;
  EXPECT_EQ(pris.position_lower, 0.0);
  EXPECT_EQ(pris.position_upper, 0.04);
  EXPECT_EQ(pris.velocity, 0.2);
  EXPECT_EQ(pris.effort, 20.0);
  const auto& none = model.joints[model.jointBody("cont_free")].limits;
  EXPECT_EQ(none.position_lower, -kInf);
  EXPECT_EQ(none.position_upper, kInf);
  EXPECT_EQ(none.velocity, kInf);
  EXPECT_EQ(none.effort, kInf);
}

TEST(UrdfLimits, PandaJoint4) {
  // panda_joint4: lower −3.0718, upper −0.0698, velocity 2.1750, effort 87 in the URDF.
  const auto model = sd::build_model_from_urdf_file(robot_path("panda.urdf"));
  const auto& l = model.joints[model.jointBody("panda_joint4")].limits;
  EXPECT_EQ(l.position_lower, -3.0718);
  EXPECT_EQ(l.position_upper, -0.0698);
  EXPECT_EQ(l.velocity, 2.1750);
  EXPECT_EQ(l.effort, 87.0);
}

}  // namespace
