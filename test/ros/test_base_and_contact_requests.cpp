// The requests' floating-base and contact fields without a master (base_request_decoder.hpp,
// contact_answers.hpp): a given base pose and twist land in q and q̇ as the free joint orders them,
// a left-out one comes from the base state with its note, each bad field is named, a fixed base
// refuses base fields, and contact wrenches are unstacked and judged (pull, friction cone) as
// documented.
#include <gtest/gtest.h>

#include <stdexcept>

#include "spatial_dynamics/ros/base_request_decoder.hpp"
#include "spatial_dynamics/ros/contact_answers.hpp"
#include "spatial_dynamics/urdf/model_builder.hpp"
#include "test_utils.hpp"

namespace sd = spatial_dynamics;

namespace {

class StillBase : public sd::BaseStateSource {
 public:
  void state(const std::string& root_link, const ros::Time&, sd::BaseState& out) const override {
    if (root_link != "base") throw std::runtime_error("no base state for '" + root_link + "'");
    out.position = Eigen::Vector3d(1.0, 2.0, 3.0);
    out.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()));
    out.twist << 0.1, 0.2, 0.3, 0.4, 0.5, 0.6;
    out.note = "note: from a still base";
  }
};

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(BaseRequest, AGivenPoseAndTwistLeadQAndQdot) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(9), qd = Eigen::VectorXd::Zero(8);
  geometry_msgs::Pose pose;
  pose.position.x = 0.1;
  pose.position.y = -0.2;
  pose.position.z = 0.3;
  const Eigen::Quaterniond o(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 1, 0).normalized()));
  pose.orientation.x = o.x();
  pose.orientation.y = o.y();
  pose.orientation.z = o.z();
  pose.orientation.w = o.w();
  geometry_msgs::Twist twist;
  twist.angular.z = 2.0;
  twist.linear.x = -1.0;
  std::string notes;
  sd::decode_base("base", StillBase(), pose, twist, ros::Time(), q, qd, notes);
  Eigen::Matrix<double, 7, 1> expected_q;
  expected_q << 0.1, -0.2, 0.3, o.x(), o.y(), o.z(), o.w();
  EXPECT_EQ(q.head<7>(), expected_q);
  Eigen::Matrix<double, 6, 1> expected_qd;
  expected_qd << 0, 0, 2.0, -1.0, 0, 0;
  EXPECT_EQ(qd.head<6>(), expected_qd);
  EXPECT_TRUE(notes.empty());
}

TEST(BaseRequest, ALeftOutPoseComesFromTheBaseStateWithItsNote) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(7), qd = Eigen::VectorXd::Zero(6);
  std::string notes;
  sd::decode_base("base", StillBase(), geometry_msgs::Pose(), geometry_msgs::Twist(), ros::Time(), q, qd, notes);
  EXPECT_EQ(q.head<3>(), Eigen::Vector3d(1.0, 2.0, 3.0));
  EXPECT_NEAR(q[5], std::sin(0.25), 1e-15);
  EXPECT_NEAR(q[6], std::cos(0.25), 1e-15);
  EXPECT_EQ(qd[5], 0.6);
  EXPECT_EQ(notes, "note: from a still base");
  EXPECT_EQ(error_of([&] {
              sd::decode_base("torso", StillBase(), geometry_msgs::Pose(), geometry_msgs::Twist(), ros::Time(), q, qd, notes);
            }),
            "no base state for 'torso'");
}

TEST(BaseRequest, BadFieldsAreNamed) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(7), qd = Eigen::VectorXd::Zero(6);
  std::string notes;
  geometry_msgs::Pose pose;
  pose.orientation.w = 1.5;
  EXPECT_EQ(error_of([&] { sd::decode_base("base", StillBase(), pose, geometry_msgs::Twist(), ros::Time(), q, qd, notes); }),
            "base_pose.orientation is not a unit quaternion (norm 1.5)");
  pose.orientation.w = 1.0;
  pose.position.y = std::nan("");
  EXPECT_EQ(error_of([&] { sd::decode_base("base", StillBase(), pose, geometry_msgs::Twist(), ros::Time(), q, qd, notes); }),
            "base_pose is not finite");
  pose.position.y = 0.0;
  geometry_msgs::Twist twist;
  twist.linear.z = INFINITY;
  EXPECT_EQ(error_of([&] { sd::decode_base("base", StillBase(), pose, twist, ros::Time(), q, qd, notes); }),
            "base_twist is not finite");
  // A fixed base: any base field set is refused, naming it.
  geometry_msgs::Accel acceleration;
  EXPECT_EQ(error_of([&] { sd::refuse_base_fields(geometry_msgs::Pose(), geometry_msgs::Twist(), &acceleration); }), "");
  acceleration.angular.x = 1.0;
  EXPECT_TRUE(error_of([&] { sd::refuse_base_fields(geometry_msgs::Pose(), geometry_msgs::Twist(), &acceleration); })
                  .rfind("base_acceleration is set but the robot's base is fixed", 0) == 0);
  EXPECT_TRUE(error_of([&] { sd::refuse_base_fields(pose, geometry_msgs::Twist(), nullptr); }).rfind("base_pose", 0) == 0);
  EXPECT_TRUE(error_of([&] { sd::refuse_base_fields(geometry_msgs::Pose(), twist, nullptr); }).rfind("base_twist", 0) == 0);
}

TEST(ContactAnswers, WrenchesAreUnstackedAndPullsAndSlipsNamed) {
  sd::ModelBuildOptions options;
  options.floating_base = true;
  const sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path("solo12.urdf"), options);
  const sd::ContactSet<double> contacts(model, {"FL_FOOT", "FR_FOOT", "HL_FOOT"}, {"point", "point", "surface"},
                                        {0.5, 0.0, 0.5});
  Eigen::VectorXd lambda(12);
  lambda << 0.4, 0.0, 1.0,         // FL: |f_xy| = 0.4 < 0.5 × 1: inside its cone
      5.0, 0.0, -0.1,                // FR: pulls (no cone to check)
      9.0, 9.0, 9.0, 0.6, 0.0, 1.0;  // HL (surface: moment, force): |f_xy| = 0.6 > 0.5: slips
  std::vector<geometry_msgs::WrenchStamped> wrenches;
  sd::contact_wrench_messages(model, contacts, lambda, ros::Time(3.0), wrenches);
  ASSERT_EQ(wrenches.size(), 3u);
  EXPECT_EQ(wrenches[0].header.frame_id, "FL_FOOT");
  EXPECT_EQ(wrenches[0].header.stamp, ros::Time(3.0));
  EXPECT_EQ(wrenches[0].wrench.force.x, 0.4);
  EXPECT_EQ(wrenches[0].wrench.torque.x, 0.0);
  EXPECT_EQ(wrenches[2].wrench.torque.y, 9.0);
  EXPECT_EQ(wrenches[2].wrench.force.x, 0.6);
  std::vector<std::string> violations;
  std::string message;
  sd::check_contact_wrenches(model, contacts, lambda, violations, message);
  EXPECT_EQ(violations, (std::vector<std::string>{"FR_FOOT", "HL_FOOT"}));
  EXPECT_NE(message.find("contact 'FR_FOOT' pulls (normal force -0.1 N)"), std::string::npos) << message;
  EXPECT_NE(message.find("contact 'HL_FOOT' leaves its friction cone"), std::string::npos) << message;
}
