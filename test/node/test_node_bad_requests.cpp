// Integration test: every kind of bad request gets success = false and a message naming the
// culprit, and a good request right after is answered correctly.
#include <sensor_msgs/JointState.h>

#include <cmath>
#include <limits>

#include "node_test_utils.hpp"

using namespace sd_node_test;
using Eigen::VectorXd;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

class BadRequests : public ServedNodeTest {
 protected:
  void SetUp() override {
    model = model_from_parameter();
    for (int i = 1; i < model.nbodies(); ++i) names.push_back(model.joint_names[i]);
  }

  /// A full, valid inverse-dynamics request at a random state.
  spatial_dynamics::InverseDynamics good_request() {
    spatial_dynamics::InverseDynamics id;
    id.request.position = to_std(sd_test::random_configuration(model, rng));
    id.request.velocity = to_std(sd_test::random_vector(model.nv, rng));
    id.request.acceleration = to_std(sd_test::random_vector(model.nv, rng));
    return id;
  }

  /// The node still answers a good request, correctly.
  void expect_good_request_works() {
    spatial_dynamics::InverseDynamics id = call("inverse_dynamics", good_request());
    ASSERT_TRUE(id.response.success) << id.response.message;
    sd::Data<double> data(model);
    const VectorXd tau = sd::rnea(model, data, to_eigen(id.request.position), to_eigen(id.request.velocity),
                                  to_eigen(id.request.acceleration));
    EXPECT_LE(sd_test::relative_error(to_eigen(id.response.effort), tau), 1e-12);
  }

  template <class Srv>
  void expect_rejected(const std::string& service_name, Srv srv, const std::vector<std::string>& parts) {
    srv = call(service_name, srv);
    EXPECT_FALSE(srv.response.success) << service_name << " accepted a bad request";
    for (const std::string& part : parts)
      EXPECT_TRUE(contains(srv.response.message, part)) << "message '" << srv.response.message << "' lacks '" << part << "'";
    expect_good_request_works();
  }

  sd::Model<double> model;
  std::vector<std::string> names;
  std::mt19937 rng{5};
};

}  // namespace

// Runs first: no joint_states have been published yet in this test's world.
TEST_F(BadRequests, AMissingJointStateIsNamed) {
  spatial_dynamics::InverseDynamics id;  // everything left out
  expect_rejected("inverse_dynamics", id, {"no joint state yet", "'" + names[0] + "'"});
  spatial_dynamics::MassMatrix mm;
  mm.request.name = {names[0]};
  mm.request.position = {0.1};
  expect_rejected("mass_matrix", mm, {"no joint state yet", "'" + names[1] + "'"});
}

TEST_F(BadRequests, UnknownAndRepeatedJointNames) {
  auto id = good_request();
  id.request.name = names;
  id.request.name[2] = "no_such_joint";
  expect_rejected("inverse_dynamics", id, {"unknown joint", "'no_such_joint'"});
  id = good_request();
  id.request.name = names;
  id.request.name[3] = names[1];
  expect_rejected("inverse_dynamics", id, {"'" + names[1] + "'", "twice"});
  spatial_dynamics::MassMatrix mm;
  mm.request.name = {"elbow_of_nobody"};
  mm.request.position = {0.0};
  expect_rejected("mass_matrix", mm, {"unknown joint", "'elbow_of_nobody'"});
}

TEST_F(BadRequests, LengthMismatches) {
  auto id = good_request();
  id.request.velocity.pop_back();
  expect_rejected("inverse_dynamics", id, {"velocity", std::to_string(model.nv - 1), std::to_string(model.nv)});
  id = good_request();
  id.request.name = {names[0], names[1]};
  id.request.position = {0.1, 0.2, 0.3};
  id.request.velocity.clear();
  id.request.acceleration.clear();
  expect_rejected("inverse_dynamics", id, {"position has 3 entries", "name has 2"});
  spatial_dynamics::ForwardDynamics fd;
  fd.request.position = std::vector<double>(model.nv, 0.0);
  fd.request.velocity = std::vector<double>(model.nv, 0.0);
  fd.request.effort = std::vector<double>(model.nv + 2, 0.0);
  expect_rejected("forward_dynamics", fd, {"effort", std::to_string(model.nv + 2)});
}

TEST_F(BadRequests, NonFiniteValuesNameFieldAndJoint) {
  auto id = good_request();
  id.request.position[2] = kNaN;
  expect_rejected("inverse_dynamics", id, {"position", "'" + names[2] + "'", "not finite"});
  id = good_request();
  id.request.velocity[0] = kInf;
  expect_rejected("inverse_dynamics", id, {"velocity", "'" + names[0] + "'", "not finite"});
  id = good_request();
  id.request.acceleration[model.nv - 1] = -kInf;
  expect_rejected("inverse_dynamics", id, {"acceleration", "'" + names[model.nv - 1] + "'", "not finite"});
  spatial_dynamics::ForwardDynamics fd;
  fd.request.position = std::vector<double>(model.nv, 0.0);
  fd.request.velocity = std::vector<double>(model.nv, 0.0);
  fd.request.effort = std::vector<double>(model.nv, 0.0);
  fd.request.effort[1] = kNaN;
  expect_rejected("forward_dynamics", fd, {"effort", "'" + names[1] + "'", "not finite"});
}

TEST_F(BadRequests, UnknownFramesAndBadWrenches) {
  auto id = good_request();
  geometry_msgs::WrenchStamped w;
  w.header.frame_id = "nowhere_link";
  id.request.external_wrenches.push_back(w);
  expect_rejected("inverse_dynamics", id, {"external_wrenches[0]", "unknown frame", "'nowhere_link'"});
  id = good_request();
  w.header.frame_id = model.frames.back().name;
  w.wrench.force.y = kNaN;
  id.request.external_wrenches.push_back(w);
  expect_rejected("inverse_dynamics", id, {"external_wrenches[0]", "'" + model.frames.back().name + "'", "not finite"});

  spatial_dynamics::TransformWrench tw;
  tw.request.wrench.header.frame_id = model.frames.back().name;
  tw.request.target_frame = "frame_known_to_nobody";
  tw.request.position = std::vector<double>(model.nv, 0.0);
  expect_rejected("transform_wrench", tw, {"'frame_known_to_nobody'", "neither"});
  tw.request.target_frame.clear();
  expect_rejected("transform_wrench", tw, {"target_frame", "empty"});
}

TEST_F(BadRequests, PositionOutsideLimitsIsAnsweredWithAWarning) {
  int limited = -1;
  for (int i = 1; i < model.nbodies() && limited < 0; ++i)
    if (model.joints[i].limits.position_upper > model.joints[i].limits.position_lower) limited = i;
  ASSERT_GT(limited, 0) << "the test robot needs a joint with limits";
  auto id = good_request();
  const int v = model.joints[limited].idx_v;
  id.request.position[v] = model.joints[limited].limits.position_upper + 0.5;
  id = call("inverse_dynamics", id);
  EXPECT_TRUE(id.response.success) << id.response.message;
  EXPECT_TRUE(contains(id.response.message, "'" + model.joint_names[limited] + "'")) << id.response.message;
  EXPECT_TRUE(contains(id.response.message, "outside its limits")) << id.response.message;
  sd::Data<double> data(model);
  EXPECT_LE(sd_test::relative_error(to_eigen(id.response.effort),
                                    sd::rnea(model, data, to_eigen(id.request.position), to_eigen(id.request.velocity),
                                             to_eigen(id.request.acceleration))),
            1e-12);
}
