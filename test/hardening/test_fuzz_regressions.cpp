// Regression tests for what the fuzz targets (fuzz/) found: each input below once crashed the URDF
// builder, gave a model with non-finite or duplicate entries, or made an algorithm return a
// non-finite result without an error. Each must now be an exception whose message names the culprit.
#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <string>

#include "spatial_dynamics/algorithms.hpp"
#include "spatial_dynamics/reduction/couple_mimic_joints.hpp"
#include "spatial_dynamics/reduction/payload.hpp"
#include "spatial_dynamics/reduction/reduce_model.hpp"
#include "spatial_dynamics/urdf/model_builder.hpp"
#include "rejection.hpp"
#include "test_utils.hpp"

namespace {

namespace sd = spatial_dynamics;
using Eigen::VectorXd;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMax = std::numeric_limits<double>::max();

std::string link_xml(const std::string& name, const std::string& inertial_origin = "0 0 0") {
  return "<link name='" + name + "'><inertial><origin xyz='" + inertial_origin +
         "'/><mass value='1'/><inertia ixx='0.1' ixy='0' ixz='0' iyy='0.1' iyz='0' izz='0.1'/></inertial></link>";
}

std::string joint_xml(const std::string& name, const std::string& type, const std::string& parent, const std::string& child,
                  const std::string& extra = "") {
  return "<joint name='" + name + "' type='" + type + "'><parent link='" + parent + "'/><child link='" + child +
         "'/><axis xyz='0 0 1'/><limit lower='-1' upper='1' effort='1' velocity='1'/>" + extra + "</joint>";
}

std::string robot(const std::string& body) { return "<robot name='r'>" + body + "</robot>"; }

using sd_test::rejection;

/// The std::domain_error message of `call`; fails the test when it returns.
template <class F>
std::string domain_error_of(F&& call) {
  try {
    call();
  } catch (const std::domain_error& e) {
    return e.what();
  }
  ADD_FAILURE() << "a non-finite result was returned without an error";
  return "";
}

sd::Model<double> panda() { return sd::build_model_from_urdf_file(sd_test::robot_path("panda.urdf")); }

}  // namespace

// ---- URDF builder ---------------------------------------------------------------------------

TEST(FuzzRegression, JointsFormingACycleBelowTheRootAreRejectedNotFollowedForever) {
  // root → A → B → A: urdfdom accepts it (A has two parent joints); the builder recursed until
  // the stack overflowed.
  const std::string msg = rejection(robot(link_xml("root") + link_xml("A") + link_xml("B") + joint_xml("j1", "revolute", "root", "A") +
                                          joint_xml("j2", "revolute", "A", "B") + joint_xml("j3", "revolute", "B", "A")));
  EXPECT_CONTAINS(msg, "link 'A'");
  EXPECT_CONTAINS(msg, "child of two joints, 'j1' and 'j3'");
}

TEST(FuzzRegression, LinkWithTwoParentJointsIsRejectedNotDuplicated) {
  // root → A, root → B → A: A became two bodies and two frames of the same name.
  const std::string msg = rejection(robot(link_xml("root") + link_xml("A") + link_xml("B") + joint_xml("j1", "revolute", "root", "A") +
                                          joint_xml("j2", "revolute", "root", "B") + joint_xml("j3", "fixed", "B", "A")));
  EXPECT_CONTAINS(msg, "link 'A'");
  EXPECT_CONTAINS(msg, "two joints");
}

TEST(FuzzRegression, LinksOnACycleApartFromTheRootAreRejectedNotDropped) {
  // B ⇄ C beside the tree root → A: urdfdom finds the single root; B and C vanished silently.
  const std::string msg = rejection(robot(link_xml("root") + link_xml("A") + link_xml("B") + link_xml("C") +
                                          joint_xml("j1", "revolute", "root", "A") + joint_xml("j2", "revolute", "B", "C") +
                                          joint_xml("j3", "revolute", "C", "B")));
  EXPECT_CONTAINS(msg, "link 'B'");
  EXPECT_CONTAINS(msg, "not connected to the root link 'root'");
}

TEST(FuzzRegression, FloatingRootJointNameTakenByAUrdfJointIsRejected) {
  // Two joints named root_joint: looking the name up found the URDF joint, not the free root.
  sd::ModelBuildOptions floating;
  floating.floating_base = true;
  const std::string xml = robot(link_xml("base") + link_xml("l1") + joint_xml("root_joint", "revolute", "base", "l1"));
  const std::string msg = rejection(xml, floating);
  EXPECT_CONTAINS(msg, "joint 'root_joint'");
  EXPECT_CONTAINS(msg, "root_joint_name");
  EXPECT_NO_THROW(sd::build_model_from_urdf_string(xml));  // a fixed base has no root joint
  floating.root_joint_name = "free_root";
  EXPECT_NO_THROW(sd::build_model_from_urdf_string(xml, floating));
}

TEST(FuzzRegression, InertialOriginSoFarThatTheInertiaOverflowsIsRejected) {
  // m r² = 1e400: finite URDF numbers, an infinite inertia in the model.
  const std::string msg = rejection(robot(link_xml("base") + link_xml("l1", "1e200 0 0") + joint_xml("j1", "revolute", "base", "l1")));
  EXPECT_CONTAINS(msg, "link 'l1'");
  EXPECT_CONTAINS(msg, "not finite");
}

TEST(FuzzRegression, FixedJointOriginSoFarThatTheMergedInertiaOverflowsIsRejected) {
  const std::string msg = rejection(robot(link_xml("base") + link_xml("far") +
                                          "<joint name='weld' type='fixed'><parent link='base'/><child link='far'/>"
                                          "<origin xyz='0 1e200 0'/></joint>"));
  EXPECT_CONTAINS(msg, "link 'far'");
  EXPECT_CONTAINS(msg, "not finite");
}

TEST(FuzzRegression, JointOriginsAddingUpToInfinityAreRejected) {
  const std::string weld = "<origin xyz='1.5e308 0 0'/>";
  const std::string msg =
      rejection(robot(link_xml("base") + "<link name='a'/><link name='b'/>" +
                      "<joint name='w1' type='fixed'><parent link='base'/><child link='a'/>" + weld + "</joint>" +
                      "<joint name='w2' type='fixed'><parent link='a'/><child link='b'/>" + weld + "</joint>"));
  EXPECT_CONTAINS(msg, "'w2'");
  EXPECT_CONTAINS(msg, "not finite");
}

TEST(FuzzRegression, TextThatIsNotUtf8IsRejectedBeforeTheXmlParserReadsPastIt) {
  // urdfdom's XML parser (TinyXML 2.6) skips a multi-byte character's announced length without
  // looking: a lead byte at the end of the text made it read past the end (heap over-read).
  const std::string xml = robot(link_xml("base") + link_xml("l1") + joint_xml("j1", "revolute", "base", "l1"));
  std::string msg = rejection(xml + "<x \xf2");
  EXPECT_CONTAINS(msg, "malformed URDF: text that is not UTF-8 at byte " + std::to_string(xml.size() + 3));
  EXPECT_CONTAINS(rejection(xml + "\xef"), "not UTF-8");                          // cut-off 3-byte character
  EXPECT_CONTAINS(rejection(robot("<link name='\xc0\xaf'/>")), "not UTF-8");      // overlong encoding
  EXPECT_CONTAINS(rejection(std::string("<robot\0 name='r'/>", 19)), "a NUL byte at byte 6");
  EXPECT_NO_THROW(sd::build_model_from_urdf_string(  // well-formed UTF-8 is fine
      "<robot name='r\xc3\xa9'><link name='\xe2\x88\x86'/><!-- \xf0\x9f\xa4\x96 --></robot>"));
}

// ---- payloads, reduction, coupling ------------------------------------------------------------

TEST(FuzzRegression, PayloadWhoseInertiaOverflowsIsRejected) {
  const sd::Model<double> model = panda();
  sd::Payload far{1.0, Eigen::Vector3d(1e200, 0, 0), Eigen::Matrix3d::Identity()};
  try {
    sd::with_payloads(model, {{"panda_hand", far}});
    ADD_FAILURE() << "accepted";
  } catch (const sd::SceneError& e) {
    EXPECT_CONTAINS(e.what(), "'panda_hand'");
    EXPECT_CONTAINS(e.what(), "not finite");
  }
}

TEST(FuzzRegression, LockedPositionSoLargeThatTheReducedInertiaOverflowsIsRejected) {
  const sd::Model<double> model = sd::build_model_from_urdf_string(
      robot(link_xml("base") + link_xml("slide") + link_xml("arm") + joint_xml("lift", "prismatic", "base", "slide") +
            joint_xml("turn", "revolute", "slide", "arm")));
  sd::Scene scene{{"turn"}, {{"lift", kMax}}};
  try {
    sd::reduce_model(model, scene);
    ADD_FAILURE() << "accepted";
  } catch (const sd::SceneError& e) {
    EXPECT_CONTAINS(e.what(), "not finite");
    EXPECT_CONTAINS(e.what(), "locked position");
  }
  scene.locked_positions["lift"] = 0.5;  // an ordinary one still works
  EXPECT_EQ(sd::reduce_model(model, scene).nv, 1);
}

TEST(FuzzRegression, MimicChainWhoseMultiplierOverflowsIsRejected) {
  const sd::Model<double> model = sd::build_model_from_urdf_string(
      robot(link_xml("base") + link_xml("a") + link_xml("b") + link_xml("c") + joint_xml("j1", "revolute", "base", "a") +
            joint_xml("j2", "revolute", "a", "b", "<mimic joint='j1' multiplier='1e200'/>") +
            joint_xml("j3", "revolute", "b", "c", "<mimic joint='j2' multiplier='1e200'/>")));
  try {
    sd::couple_mimic_joints(model);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_CONTAINS(e.what(), "joint 'j3'");
    EXPECT_CONTAINS(e.what(), "not finite");
  }
}

// ---- algorithms: a non-finite result is an error naming the coordinate ------------------------

TEST(FuzzRegression, NonFiniteInputsGiveErrorsNotNonFiniteResults) {
  const sd::Model<double> model = panda();
  sd::Data<double> data(model);
  const VectorXd zero = VectorXd::Zero(model.nv);
  VectorXd q = VectorXd::Zero(model.nq);
  q[model.joints[model.jointBody("panda_joint3")].idx_q] = kNaN;
  EXPECT_CONTAINS(domain_error_of([&] { sd::rnea(model, data, q, zero, zero); }), "inverse dynamics");
  EXPECT_CONTAINS(domain_error_of([&] { sd::aba(model, data, q, zero, zero); }), "forward dynamics");
  EXPECT_CONTAINS(domain_error_of([&] { sd::crba(model, data, q); }), "mass matrix");
  EXPECT_CONTAINS(domain_error_of([&] { sd::forward_kinematics(model, data, q); }), "panda_link3");
  EXPECT_CONTAINS(domain_error_of([&] { sd::kinetic_energy(model, data, q, zero); }), "forward kinematics");
  EXPECT_CONTAINS(domain_error_of([&] { sd::frame_jacobian(model, data, q, model.frameIndex("panda_hand"),
                                                           sd::ReferenceFrame::Local); }),
                  "forward kinematics");
  const VectorXd q0 = VectorXd::Zero(model.nq);
  VectorXd tau = zero;
  tau[model.joints[model.jointBody("panda_joint5")].idx_v] = kNaN;
  const std::string msg = domain_error_of([&] { sd::aba(model, data, q0, zero, tau); });
  EXPECT_CONTAINS(msg, "forward dynamics: the acceleration for 'panda_joint");
  EXPECT_CONTAINS(msg, "not finite");
  const sd::Model<double> coupled = sd::couple_mimic_joints(model);  // forward dynamics through the CRBA
  sd::Data<double> coupled_data(coupled);
  VectorXd tau_c = VectorXd::Zero(coupled.nv);
  tau_c[0] = kNaN;
  EXPECT_CONTAINS(domain_error_of([&] {
                    sd::forward_dynamics(coupled, coupled_data, VectorXd::Zero(coupled.nq), VectorXd::Zero(coupled.nv),
                                         tau_c);
                  }),
                  "forward dynamics");
}

TEST(FuzzRegression, OverflowingResultsAreErrorsNamingTheJoint) {
  // A payload of the largest finite mass on the hand: its weight overflows every torque upstream.
  const sd::Model<double> loaded =
      sd::with_payloads(panda(), {{"panda_hand", sd::Payload{kMax, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()}}});
  sd::Data<double> data(loaded);
  const VectorXd q = VectorXd::Zero(loaded.nq), zero = VectorXd::Zero(loaded.nv);
  const std::string msg = domain_error_of([&] { sd::gravity_torques(loaded, data, q); });
  EXPECT_CONTAINS(msg, "inverse dynamics: the joint force for 'panda_joint");
  EXPECT_CONTAINS(msg, "overflows");
  // Finite but absurd velocities overflow v ×* I v on an ordinary model.
  const sd::Model<double> model = panda();
  sd::Data<double> d(model);
  const VectorXd fast = VectorXd::Constant(model.nv, 1e200);
  EXPECT_CONTAINS(domain_error_of([&] { sd::nonlinear_effects(model, d, q, fast); }), "inverse dynamics");
  EXPECT_CONTAINS(domain_error_of([&] { sd::kinetic_energy(model, d, q, fast); }), "kinetic energy");
  // Ordinary inputs are unaffected.
  EXPECT_NO_THROW(sd::rnea(model, d, q, zero, zero));
  EXPECT_NO_THROW(sd::aba(model, d, q, zero, zero));
}
