// Integration test of a floating base (~root_joint floating) with contacts, the base's state from
// odometry (~base_odometry) or from tf (~world_frame), by name through the node: every service with
// and without contacts, ~computed_torques with ~computed_contact_wrenches, ~centroidal_state,
// ~set_contacts, an external wrench with the contacts, a scene (the legs) and a payload on the base,
// and each bad input named. The expected numbers are an independent float128
// solution (contact_oracle.hpp: the reference's ID, M and h, J_c by differences of frame poses,
// dense pseudo-inverses). Launched by node_floating_base.test with ~robot (talos: two surface
// soles; solo12: four point feet) and ~base_source (odometry | tf).
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <tf2_ros/transform_broadcaster.h>

#include <Eigen/LU>
#include <atomic>
#include <random>

#include "contact_oracle.hpp"
#include "exact_rotations.hpp"
#include "node_test_utils.hpp"
#include "spatial_dynamics/CentroidalState.h"
#include "spatial_dynamics/ContactWrenches.h"
#include "spatial_dynamics/InverseDynamicsTrajectory.h"
#include "spatial_dynamics/SetContacts.h"
#include "spatial_dynamics/SetPayload.h"
#include "spatial_dynamics/algorithms/centroidal.hpp"
#include "spatial_dynamics/reference/inverse_dynamics.hpp"
#include "spatial_dynamics/reference/mass_matrix.hpp"

using namespace sd_node_test;
using Eigen::VectorXd;
using sd::Quad;
using VecQ = sd::reference::VecX<Quad>;
using MatQ = sd::reference::MatX<Quad>;
namespace ref = spatial_dynamics::reference;

namespace {

constexpr double kTolerance = 1e-10;  // the node's double answers against float128

std::string private_param(const std::string& key) {
  std::string value;
  if (!ros::param::get("~" + key, value)) throw std::runtime_error("~" + key + " is not set");
  return value;
}

/// The base state the test publishes: pose in "odom", twist (ω ; v) in the root link's axes.
struct Base {
  Eigen::Vector3d position{0.1, -0.2, 0.9};
  Eigen::Quaterniond orientation{Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, -0.1, 1.0).normalized())};
  Eigen::Matrix<double, 6, 1> twist = (Eigen::Matrix<double, 6, 1>() << 0.1, -0.2, 0.05, 0.3, 0.1, -0.2).finished();

  /// The pose into a message's position (Point or Vector3) and orientation.
  template <class Position>
  void pose(Position& p, geometry_msgs::Quaternion& o) const {
    p.x = position.x();
    p.y = position.y();
    p.z = position.z();
    o.x = orientation.x();
    o.y = orientation.y();
    o.z = orientation.z();
    o.w = orientation.w();
  }
  /// The twist into a message.
  void velocity(geometry_msgs::Twist& t) const {
    t.angular.x = twist[0];
    t.angular.y = twist[1];
    t.angular.z = twist[2];
    t.linear.x = twist[3];
    t.linear.y = twist[4];
    t.linear.z = twist[5];
  }
};

class FloatingBase : public ServedNodeTest {
 protected:
  static void SetUpTestSuite() {
    ServedNodeTest::SetUpTestSuite();
    ros::NodeHandle nh;
    robot_ = private_param("robot");
    odometry_ = private_param("base_source") == "odometry";
    if (odometry_) odometry_publisher_ = nh.advertise<nav_msgs::Odometry>("/odom", 10);
    broadcaster_ = std::make_unique<tf2_ros::TransformBroadcaster>();
    timer_ = nh.createTimer(ros::Duration(0.01), [](const ros::TimerEvent&) { publishBase(); });
  }
  static void TearDownTestSuite() {
    timer_.stop();
    broadcaster_.reset();
    odometry_publisher_.shutdown();
  }

  static void publishBase() {
    if (!publishing_) return;
    const Base base;
    const ros::Time now = ros::Time::now();
    if (odometry_) {
      nav_msgs::Odometry odom;
      odom.header.stamp = now;
      odom.header.frame_id = "odom";
      odom.child_frame_id = root_link_;
      base.pose(odom.pose.pose.position, odom.pose.pose.orientation);
      base.velocity(odom.twist.twist);
      odometry_publisher_.publish(odom);
    } else {
      geometry_msgs::TransformStamped t;
      t.header.stamp = now;
      t.header.frame_id = "odom";
      t.child_frame_id = root_link_;
      base.pose(t.transform.translation, t.transform.rotation);
      broadcaster_->sendTransform(t);
    }
  }

  void SetUp() override {
    std::string urdf;
    ASSERT_TRUE(ros::param::get("robot_description", urdf));
    sd::ModelBuildOptions options;
    options.floating_base = true;
    model = sd::build_model_from_urdf_string(urdf, options);
    oracle = sd_test::with_exact_rotations(model);
    root_link_ = model.body_names[1];
    for (const std::string& name : model.velocityNames()) names.push_back(name);
    names.erase(names.begin(), names.begin() + 6);
    if (robot_ == "talos") {
      frames = {"left_sole_link", "right_sole_link"};
      kinds = {"surface", "surface"};
    } else {
      frames = {"FL_FOOT", "FR_FOOT", "HL_FOOT", "HR_FOOT"};
      kinds = {"point", "point", "point", "point"};
    }
    joint_states = nh.advertise<sensor_msgs::JointState>("/joint_states", 100);
    for (int k = 0; k < 100 && (joint_states.getNumSubscribers() == 0 || !torques.connected() || !wrenches.connected() ||
                                !centroidal.connected());
         ++k)
      ros::Duration(0.05).sleep();
  }

  /// Starts the base state and waits until the node has it.
  void startBase() {
    if (publishing_) return;
    publishing_ = true;
    for (int k = 0; k < 100; ++k) {
      if (call("inverse_dynamics", request(stance(), VectorXd::Zero(model.nv - 6), false)).response.success) return;
      ros::Duration(0.05).sleep();
    }
    FAIL() << "the node never had the base state";
  }

  /// Joints near their zero position (a standing pose), deterministic per call.
  VectorXd stance() {
    VectorXd q = VectorXd::Zero(model.nv - 6);
    std::uniform_real_distribution<double> small(-0.2, 0.2);
    for (int k = 0; k < q.size(); ++k) q[k] = small(rng);
    return q;
  }

  /// q (base pose first) of the published base and joint positions `joints`.
  VecQ configuration(const VectorXd& joints) const {
    const Base base;
    VectorXd q(model.nq);
    q << base.position, base.orientation.coeffs(), joints;
    return sd::to_quad(q);
  }

  /// An InverseDynamics request of every joint; with_base: the test's base pose and twist in it.
  sd::InverseDynamics request(const VectorXd& q, const VectorXd& qd, bool with_base) {
    sd::InverseDynamics srv;
    srv.request.name = names;
    srv.request.position = to_std(q);
    srv.request.velocity = to_std(qd);
    srv.request.acceleration.assign(names.size(), 0.0);
    if (with_base) setBase(srv.request);
    return srv;
  }

  template <class Request>
  void setBase(Request& r) const {
    const Base base;
    base.pose(r.base_pose.position, r.base_pose.orientation);
    base.velocity(r.base_twist);
  }

  /// The independent contact-consistent ID: λ = pinv(J_c,baseᵀ) ID_base, τ = ID − J_cᵀ λ, with
  /// ID = ID(q, q̇, q̈, F_ext) (F_ext: none when empty).
  void independentId(const std::vector<std::string>& contact_frames, const std::vector<std::string>& contact_kinds,
                     const VecQ& Q, const VecQ& Qd, const VecQ& Qdd, VecQ& id, VecQ& lambda, VecQ& tau,
                     const std::vector<sd::ForceVector<Quad>>& F_ext = {}) const {
    const sd::ContactSet<double> contacts(model, contact_frames, contact_kinds);
    MatQ J;
    VecQ Jdot_qd;
    sd_test::contact_jacobian_by_differences(oracle, contacts, Q, Qd, J, Jdot_qd);
    id = ref::inverse_dynamics(oracle, Q, Qd, Qdd, F_ext);
    lambda = sd_test::pseudo_inverse_solve(J.leftCols(6).transpose(), id.head(6));
    tau = id - J.transpose() * lambda;
  }

  /// A ForwardDynamics request of every joint with the test's base pose and twist.
  sd::ForwardDynamics fdRequest(const VectorXd& q, const VectorXd& qd, const VectorXd& effort) const {
    sd::ForwardDynamics fd;
    fd.request.name = names;
    fd.request.position = to_std(q);
    fd.request.velocity = to_std(qd);
    fd.request.effort = to_std(effort);
    setBase(fd.request);
    return fd;
  }

  /// The independent constrained FD with the node's contacts: (q̈ ; λ) of the dense KKT system
  /// [M −J_cᵀ; J_c 0] (q̈ ; λ) = (τ − ID(q, q̇, 0, F_ext) ; −J̇_c q̇) by its pseudo-inverse; M into `M`.
  VecQ independentFd(const VecQ& Q, const VecQ& Qd, const VectorXd& effort, MatQ& M,
                     const std::vector<sd::ForceVector<Quad>>& F_ext = {}) const {
    const int n = model.nv;
    const sd::ContactSet<double> contacts(model, frames, kinds);
    MatQ J;
    VecQ Jdot_qd;
    sd_test::contact_jacobian_by_differences(oracle, contacts, Q, Qd, J, Jdot_qd);
    M = ref::mass_matrix(oracle, Q);
    VectorXd tau_full = VectorXd::Zero(n);
    tau_full.tail(n - 6) = effort;
    const int m = contacts.rows;
    MatQ kkt = MatQ::Zero(n + m, n + m);
    kkt.topLeftCorner(n, n) = M;
    kkt.topRightCorner(n, m) = -J.transpose();
    kkt.bottomLeftCorner(m, n) = J;
    VecQ rhs(n + m);
    rhs << sd::to_quad(tau_full) - ref::inverse_dynamics(oracle, Q, Qd, VecQ(VecQ::Zero(n)), F_ext), -Jdot_qd;
    return sd_test::pseudo_inverse_solve(kkt, rhs);
  }

  /// A ForwardDynamics answer's q̈: base_acceleration, then the joints'.
  static VectorXd accelerations(const sd::ForwardDynamics& fd) {
    const geometry_msgs::Accel& a = fd.response.base_acceleration;
    VectorXd qdd(6 + fd.response.acceleration.size());
    qdd << a.angular.x, a.angular.y, a.angular.z, a.linear.x, a.linear.y, a.linear.z, to_eigen(fd.response.acceleration);
    return qdd;
  }

  /// The stacked λ of an answer's contact wrenches (point: force; surface: moment, force).
  static VectorXd stacked(const std::vector<geometry_msgs::WrenchStamped>& wrenches, const std::vector<std::string>& kinds) {
    std::vector<double> out;
    for (std::size_t k = 0; k < wrenches.size(); ++k) {
      const geometry_msgs::Wrench& w = wrenches[k].wrench;
      if (kinds[k] == "surface") out.insert(out.end(), {w.torque.x, w.torque.y, w.torque.z});
      out.insert(out.end(), {w.force.x, w.force.y, w.force.z});
    }
    return to_eigen(out);
  }

  /// The contact wrenches' sum in the world frame about the centre of mass, against the weight
  /// (−m g at c): relative error.
  double weightError(const std::vector<geometry_msgs::WrenchStamped>& wrenches, const VecQ& Q) const {
    const std::vector<sd_test::Mat6Q> X0 = sd_test::body_transforms(oracle, Q);
    const Quad mass = sd_test::total_mass(oracle);
    const sd_test::Vec3Q c = sd_test::center_of_mass(oracle, X0);
    sd_test::Vec3Q force = sd_test::Vec3Q::Zero(), moment = sd_test::Vec3Q::Zero();
    for (const geometry_msgs::WrenchStamped& w : wrenches) {
      sd_test::Mat3Q R;
      sd_test::Vec3Q p;
      sd_test::pose_of(sd_test::frame_transform(oracle, X0, model.frameIndex(w.header.frame_id)), R, p);
      const sd_test::Vec3Q f = R * sd_test::Vec3Q(Quad(w.wrench.force.x), Quad(w.wrench.force.y), Quad(w.wrench.force.z));
      const sd_test::Vec3Q n = R * sd_test::Vec3Q(Quad(w.wrench.torque.x), Quad(w.wrench.torque.y), Quad(w.wrench.torque.z));
      force += f;
      moment += n + (p - c).cross(f);
    }
    const sd_test::Vec3Q weight = -mass * oracle.gravity;
    const Quad error = (force - weight).norm() + moment.norm();
    return static_cast<double>(error / weight.norm());
  }

  /// Publishes joint positions (velocities zero) stamped now; the node's torques, contact wrenches
  /// and centroidal state for it.
  bool publishJoints(const VectorXd& q, sensor_msgs::JointState& tau, sd::ContactWrenches& w, sd::CentroidalState& c,
                     bool expect_wrenches = true) {
    sensor_msgs::JointState msg;
    msg.header.stamp = ros::Time::now();
    msg.name = names;
    msg.position = to_std(q);
    msg.velocity.assign(names.size(), 0.0);
    joint_states.publish(msg);
    const bool got = torques.waitFor(msg.header.stamp, tau) && centroidal.waitFor(msg.header.stamp, c);
    return got && (!expect_wrenches || wrenches.waitFor(msg.header.stamp, w));
  }

  static inline std::string robot_, root_link_;
  static inline bool odometry_ = false;
  static inline std::atomic<bool> publishing_{false};
  static inline ros::Publisher odometry_publisher_;
  static inline std::unique_ptr<tf2_ros::TransformBroadcaster> broadcaster_;
  static inline ros::Timer timer_;

  sd::Model<double> model;
  sd::Model<Quad> oracle;
  std::vector<std::string> names, frames, kinds;
  ros::Publisher joint_states;
  TorqueListener torques{nh};
  Collector<sd::ContactWrenches> wrenches{nh, "/dynamics/computed_contact_wrenches"};
  Collector<sd::CentroidalState> centroidal{nh, "/dynamics/centroidal_state"};
  std::mt19937 rng{7};
};

}  // namespace

// First, before any base state: refused, naming the source.
TEST_F(FloatingBase, ARequestWithoutABaseStateIsRefusedNamingTheSource) {
  const sd::InverseDynamics srv = call("inverse_dynamics", request(stance(), VectorXd::Zero(model.nv - 6), false));
  EXPECT_FALSE(srv.response.success);
  EXPECT_TRUE(contains(srv.response.message, odometry_ ? "odometry '/odom'" : "tf ('odom' to '" + root_link_ + "'"))
      << srv.response.message;
}

TEST_F(FloatingBase, StandingRobotsContactWrenchesCarryItsWeightAndTheTorquesMatch) {
  startBase();
  for (int trial = 0; trial < 3; ++trial) {
    const VectorXd q = stance();
    sensor_msgs::JointState tau;
    sd::ContactWrenches w;
    sd::CentroidalState c;
    ASSERT_TRUE(publishJoints(q, tau, w, c)) << "no computed torques, contact wrenches or centroidal state";
    const VecQ Q = configuration(q), zero = VecQ::Zero(model.nv);
    VecQ id, lambda, expected;
    independentId(frames, kinds, Q, zero, zero, id, lambda, expected);  // ID(q, 0, 0) with the base at rest
    ASSERT_EQ(tau.name, names);
    EXPECT_LT(sd::relative_error_to(to_eigen(tau.effort), VecQ(expected.tail(model.nv - 6))), kTolerance);
    ASSERT_EQ(w.wrenches.size(), frames.size());
    for (std::size_t k = 0; k < frames.size(); ++k) EXPECT_EQ(w.wrenches[k].header.frame_id, frames[k]);
    EXPECT_LT(sd::relative_error_to(stacked(w.wrenches, kinds), lambda), kTolerance);
    const double weight_error = weightError(w.wrenches, Q);
    std::printf("[%s] torques %.3g, λ %.3g, weight %.3g\n", robot_.c_str(),
                sd::relative_error_to(to_eigen(tau.effort), VecQ(expected.tail(model.nv - 6))),
                sd::relative_error_to(stacked(w.wrenches, kinds), lambda), weight_error);
    EXPECT_LT(weight_error, 1e-9);
  }
}

TEST_F(FloatingBase, SetContactsMovesTheWeightAndALeftoverBaseWrenchIsTheLeastSquaresResidual) {
  startBase();
  // Talos on one foot carries it all on that foot; Solo12 on two diagonal feet cannot balance its
  // base when the centre of mass is off their line: the wrench left over is the least-squares residual.
  const std::vector<std::string> stance_frames =
      robot_ == "talos" ? std::vector<std::string>{"left_sole_link"} : std::vector<std::string>{"FL_FOOT", "HR_FOOT"};
  const std::vector<std::string> stance_kinds(stance_frames.size(), kinds[0]);
  sd::SetContacts set;
  set.request.frames = stance_frames;
  set.request.kinds = stance_kinds;
  set = call("set_contacts", set);
  ASSERT_TRUE(set.response.success) << set.response.message;
  const VectorXd q = stance();
  sensor_msgs::JointState tau;
  sd::ContactWrenches w;
  sd::CentroidalState c;
  ASSERT_TRUE(publishJoints(q, tau, w, c));
  ASSERT_EQ(w.wrenches.size(), stance_frames.size());
  const VecQ Q = configuration(q), zero = VecQ::Zero(model.nv);
  VecQ id, lambda, expected;
  independentId(stance_frames, stance_kinds, Q, zero, zero, id, lambda, expected);
  EXPECT_LT(sd::relative_error_to(stacked(w.wrenches, stance_kinds), lambda), kTolerance);
  EXPECT_LT(sd::relative_error_to(to_eigen(tau.effort), VecQ(expected.tail(model.nv - 6))), kTolerance);
  // The same through inverse_dynamics: the base wrench left over.
  sd::InverseDynamics srv = call("inverse_dynamics", request(q, VectorXd::Zero(model.nv - 6), true));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  const Base base;
  VecQ Qd = zero;
  Qd.head(6) = sd::to_quad(VectorXd(base.twist));
  independentId(stance_frames, stance_kinds, Q, Qd, zero, id, lambda, expected);
  const geometry_msgs::Wrench& b = srv.response.base_wrench;
  VectorXd base_wrench(6);
  base_wrench << b.torque.x, b.torque.y, b.torque.z, b.force.x, b.force.y, b.force.z;
  const double residual_error =
      static_cast<double>((sd::to_quad(base_wrench) - expected.head(6)).norm() / id.head(6).norm());
  std::printf("[%s] stance %zu: base wrench %.3g (|residual| / |ID base| = %.3g)\n", robot_.c_str(), stance_frames.size(),
              residual_error, static_cast<double>(expected.head(6).norm() / id.head(6).norm()));
  EXPECT_LT(residual_error, kTolerance);
  if (robot_ == "talos") {
    EXPECT_LT(weightError(w.wrenches, Q), 1e-9);
  } else {
    EXPECT_GT(static_cast<double>(expected.head(6).norm() / id.head(6).norm()), 1e-3) << "the diagonal stance balanced";
    EXPECT_TRUE(contains(srv.response.message, "cannot balance the base")) << srv.response.message;
  }
  set.request.frames = frames;  // back to the launch file's contacts
  set.request.kinds = kinds;
  set = call("set_contacts", set);
  ASSERT_TRUE(set.response.success) << set.response.message;
}

TEST_F(FloatingBase, ServicesWithAndWithoutContactsMatchTheIndependentSolution) {
  startBase();
  const int n = model.nv, joints = n - 6;
  for (int trial = 0; trial < 2; ++trial) {
    const VectorXd q = stance(), qd = sd_test::random_vector(joints, rng), qdd = sd_test::random_vector(joints, rng);
    const VecQ Q = configuration(q);
    const Base base;
    VectorXd v(n), a(n);
    v << base.twist, qd;
    a << 0.2, -0.1, 0.3, -0.4, 0.5, 0.1, qdd;
    const VecQ Qd = sd::to_quad(v), Qdd = sd::to_quad(a);
    // Inverse dynamics, the node's contacts and none.
    sd::InverseDynamics id_srv = request(q, qd, true);
    id_srv.request.acceleration = to_std(qdd);
    id_srv.request.base_acceleration.angular.x = 0.2;
    id_srv.request.base_acceleration.angular.y = -0.1;
    id_srv.request.base_acceleration.angular.z = 0.3;
    id_srv.request.base_acceleration.linear.x = -0.4;
    id_srv.request.base_acceleration.linear.y = 0.5;
    id_srv.request.base_acceleration.linear.z = 0.1;
    const sd::InverseDynamics with = call("inverse_dynamics", id_srv);
    ASSERT_TRUE(with.response.success) << with.response.message;
    VecQ id, lambda, tau;
    independentId(frames, kinds, Q, Qd, Qdd, id, lambda, tau);
    EXPECT_LT(sd::relative_error_to(to_eigen(with.response.effort), VecQ(tau.tail(joints))), kTolerance);
    EXPECT_LT(sd::relative_error_to(stacked(with.response.contact_wrenches, kinds), lambda), kTolerance);
    const geometry_msgs::Wrench& b = with.response.base_wrench;
    EXPECT_LT(std::abs(b.force.x) + std::abs(b.force.y) + std::abs(b.force.z) + std::abs(b.torque.x) +
                  std::abs(b.torque.y) + std::abs(b.torque.z),
              kTolerance * static_cast<double>(id.head(6).norm()))
        << "the contacts balance the base";
    id_srv.request.ignore_contacts = true;
    const sd::InverseDynamics without = call("inverse_dynamics", id_srv);
    ASSERT_TRUE(without.response.success) << without.response.message;
    EXPECT_TRUE(without.response.contact_wrenches.empty());
    EXPECT_LT(sd::relative_error_to(to_eigen(without.response.effort), VecQ(id.tail(joints))), kTolerance);
    const geometry_msgs::Wrench& w = without.response.base_wrench;
    VectorXd base_wrench(6);
    base_wrench << w.torque.x, w.torque.y, w.torque.z, w.force.x, w.force.y, w.force.z;
    EXPECT_LT(sd::relative_error_to(base_wrench, VecQ(id.head(6))), kTolerance) << "the base wrench the motion needs";

    // Forward dynamics: the dense KKT system with the contacts, M⁻¹(τ − h) without.
    const VectorXd effort = sd_test::random_vector(joints, rng, 5.0);
    sd::ForwardDynamics fd = fdRequest(q, qd, effort);
    MatQ M;
    const VecQ solution = independentFd(Q, Qd, effort, M);
    const sd::ForwardDynamics fd_with = call("forward_dynamics", fd);
    ASSERT_TRUE(fd_with.response.success) << fd_with.response.message;
    EXPECT_LT(sd::relative_error_to(accelerations(fd_with), VecQ(solution.head(n))), kTolerance);
    EXPECT_LT(sd::relative_error_to(stacked(fd_with.response.contact_wrenches, kinds), VecQ(solution.tail(solution.size() - n))),
              kTolerance);
    fd.request.ignore_contacts = true;
    const sd::ForwardDynamics fd_without = call("forward_dynamics", fd);
    ASSERT_TRUE(fd_without.response.success) << fd_without.response.message;
    VectorXd tau_full = VectorXd::Zero(n);
    tau_full.tail(joints) = effort;
    const VecQ rhs_free = sd::to_quad(tau_full) - ref::nonlinear_effects(oracle, Q, Qd);
    EXPECT_LT(sd::relative_error_to(accelerations(fd_without), VecQ(M.fullPivLu().solve(rhs_free))), kTolerance);

    // The mass matrix covers the base, its six coordinates first.
    sd::MassMatrix mm;
    mm.request.name = names;
    mm.request.position = to_std(q);
    mm = call("mass_matrix", mm);
    ASSERT_TRUE(mm.response.success) << mm.response.message;
    ASSERT_EQ(mm.response.name.size(), static_cast<std::size_t>(n));
    EXPECT_EQ(mm.response.name[0], "root_joint/wx");
    EXPECT_EQ(mm.response.name[5], "root_joint/vz");
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> M_node(
        mm.response.mass_matrix.data(), n, n);
    EXPECT_LT(sd::relative_error_to(Eigen::MatrixXd(M_node), M), kTolerance);
  }
}

TEST_F(FloatingBase, TheBaseStateComesFromTheSourceWhenTheRequestLeavesItOut) {
  startBase();
  const VectorXd q = stance(), qd = sd_test::random_vector(model.nv - 6, rng);
  const sd::InverseDynamics from_source = call("inverse_dynamics", request(q, qd, false));
  ASSERT_TRUE(from_source.response.success) << from_source.response.message;
  sd::InverseDynamics given = request(q, qd, true);
  if (!odometry_) {  // tf gives the pose only: the velocity is zero, and the answer says so
    given.request.base_twist = geometry_msgs::Twist();
    EXPECT_TRUE(contains(from_source.response.message, "base velocity is taken as zero")) << from_source.response.message;
  }
  given = call("inverse_dynamics", given);
  ASSERT_TRUE(given.response.success) << given.response.message;
  EXPECT_LT(sd::relative_error_to(to_eigen(from_source.response.effort), to_eigen(given.response.effort)), 1e-12);
  EXPECT_LT(sd::relative_error_to(stacked(from_source.response.contact_wrenches, kinds),
                                  stacked(given.response.contact_wrenches, kinds)),
            1e-12);
}

TEST_F(FloatingBase, CentroidalStateIsPublishedInTheWorldFrame) {
  startBase();
  const VectorXd q = stance();
  sensor_msgs::JointState tau;
  sd::ContactWrenches w;
  sd::CentroidalState c;
  ASSERT_TRUE(publishJoints(q, tau, w, c));
  EXPECT_EQ(c.header.frame_id, "odom");
  const VecQ Q = configuration(q);
  const Quad mass = sd_test::total_mass(oracle);
  const Eigen::Vector3d com(c.center_of_mass.x, c.center_of_mass.y, c.center_of_mass.z);
  EXPECT_LT(sd::relative_error_to(com, sd_test::center_of_mass(oracle, sd_test::body_transforms(oracle, Q))), kTolerance);
  // Joint velocities zero: the momentum is the base twist's, m ċ = linear momentum.
  VectorXd v = VectorXd::Zero(model.nv);
  if (odometry_) v.head(6) = Base().twist;
  sd::Data<double> data(model);
  const VectorXd qd_double = v, q_double = Q.cast<double>();
  const Eigen::Vector3d c_dot = sd::center_of_mass_velocity(model, data, q_double, qd_double);
  const Eigen::Vector3d p(c.linear_momentum.x, c.linear_momentum.y, c.linear_momentum.z);
  const Eigen::Vector3d c_dot_node(c.center_of_mass_velocity.x, c.center_of_mass_velocity.y, c.center_of_mass_velocity.z);
  EXPECT_LT((c_dot_node - c_dot).norm(), 1e-12 * (1.0 + c_dot.norm()));
  EXPECT_LT((p - static_cast<double>(mass) * c_dot).norm(), 1e-9 * (1.0 + p.norm()));
}

// The scene "legs" (root link to the contact frames; the launch file) locks the other joints at their
// latest joint states: its answer is the whole robot's with those joints still. A payload on the root
// link adds its weight to the base wrench the robot at rest needs, in the root link's axes.
TEST_F(FloatingBase, ASceneAndAPayloadOnAFloatingBase) {
  startBase();
  const VectorXd q = stance();
  sensor_msgs::JointState tau;
  sd::ContactWrenches w;
  sd::CentroidalState c;
  ASSERT_TRUE(publishJoints(q, tau, w, c));  // the scene's locked joints follow
  sd::InverseDynamics scene;
  setBase(scene.request);
  ros::service::call(service("legs/inverse_dynamics"), scene);
  ASSERT_TRUE(scene.response.success) << scene.response.message;
  if (robot_ == "talos") {
    EXPECT_LT(scene.response.name.size(), names.size()) << "the arms, torso and head locked";
  }
  const sd::InverseDynamics full = call("inverse_dynamics", request(q, VectorXd::Zero(model.nv - 6), true));
  ASSERT_TRUE(full.response.success) << full.response.message;
  VectorXd expected(scene.response.name.size());
  for (std::size_t k = 0; k < scene.response.name.size(); ++k) {
    const auto it = std::find(full.response.name.begin(), full.response.name.end(), scene.response.name[k]);
    ASSERT_NE(it, full.response.name.end()) << scene.response.name[k];
    expected[k] = full.response.effort[it - full.response.name.begin()];
  }
  std::printf("[%s] scene of %zu joints: effort %.3g, contact wrenches %.3g\n", robot_.c_str(), scene.response.name.size(),
              sd_test::relative_error(to_eigen(scene.response.effort), expected),
              sd_test::relative_error(stacked(scene.response.contact_wrenches, kinds), stacked(full.response.contact_wrenches, kinds)));
  EXPECT_LT(sd_test::relative_error(to_eigen(scene.response.effort), expected), 1e-12);
  EXPECT_LT(sd_test::relative_error(stacked(scene.response.contact_wrenches, kinds), stacked(full.response.contact_wrenches, kinds)),
            1e-12);

  // 2 kg at the root link's origin, the base at rest and no contacts: its weight, in root link axes.
  sd::InverseDynamics at_rest = request(q, VectorXd::Zero(model.nv - 6), true);
  at_rest.request.base_twist = geometry_msgs::Twist();
  at_rest.request.ignore_contacts = true;
  const sd::InverseDynamics before = call("inverse_dynamics", at_rest);
  sd::SetPayload payload;
  payload.request.frame = root_link_;
  payload.request.inertia.m = 2.0;
  payload.request.inertia.ixx = payload.request.inertia.iyy = payload.request.inertia.izz = 0.01;
  payload = call("set_payload", payload);
  ASSERT_TRUE(payload.response.success) << payload.response.message;
  const sd::InverseDynamics after = call("inverse_dynamics", at_rest);
  payload.request.inertia.m = 0.0;
  payload = call("set_payload", payload);
  ASSERT_TRUE(after.response.success && before.response.success) << after.response.message;
  const auto wrench = [](const geometry_msgs::Wrench& b) {
    VectorXd v(6);
    v << b.torque.x, b.torque.y, b.torque.z, b.force.x, b.force.y, b.force.z;
    return v;
  };
  VectorXd weight = VectorXd::Zero(6);
  weight.tail(3) = Base().orientation.conjugate() * Eigen::Vector3d(0.0, 0.0, 2.0 * 9.81);  // −m g in root axes
  EXPECT_LT((wrench(after.response.base_wrench) - wrench(before.response.base_wrench) - weight).norm(), 1e-12 * 9.81 * 2.0);
  EXPECT_LT(sd_test::relative_error(to_eigen(after.response.effort), to_eigen(before.response.effort)), 1e-14)
      << "a payload at the root link loads no joint";
}

// An external wrench with the contacts (a humanoid pushing, a quadruped carrying a load): the contacts
// balance what the wrench leaves, ID(q, q̇, q̈, f_ext) = Sᵀ τ + J_cᵀ λ; forward dynamics solves the KKT
// system with it. The wrench acts on the last link in its own axes, about its origin; the oracle's body
// force is ^FX_Bᵀ f (the link's frame on its body).
TEST_F(FloatingBase, ExternalWrenchesWithContactsMatchTheIndependentSolution) {
  startBase();
  const int n = model.nv, joints = n - 6;
  const std::string link = model.body_names.back();
  const sd::Frame<double>& frame = model.frames[model.frameIndex(link)];
  const sd::ForceVector<double> f(Eigen::Vector3d(1.5, -2.0, 0.5), Eigen::Vector3d(10.0, -20.0, 30.0));  // (n; f)
  std::vector<sd::ForceVector<Quad>> F_ext(model.nbodies(), sd::ForceVector<Quad>::Zero());
  F_ext[frame.body] = frame.X_frame_body.applyInverse(f).cast<Quad>();
  geometry_msgs::WrenchStamped wrench;
  wrench.header.frame_id = link;
  wrench.wrench.torque.x = f.angular[0];
  wrench.wrench.torque.y = f.angular[1];
  wrench.wrench.torque.z = f.angular[2];
  wrench.wrench.force.x = f.linear[0];
  wrench.wrench.force.y = f.linear[1];
  wrench.wrench.force.z = f.linear[2];

  const VectorXd q = stance(), qd = sd_test::random_vector(joints, rng);
  const VecQ Q = configuration(q);
  const Base base;
  VectorXd v(n);
  v << base.twist, qd;
  const VecQ Qd = sd::to_quad(v), Qdd = VecQ::Zero(n);
  sd::InverseDynamics id_srv = request(q, qd, true);
  id_srv.request.external_wrenches = {wrench};
  id_srv = call("inverse_dynamics", id_srv);
  ASSERT_TRUE(id_srv.response.success) << id_srv.response.message;
  VecQ id, lambda, tau, id_free, lambda_free, tau_free;
  independentId(frames, kinds, Q, Qd, Qdd, id, lambda, tau, F_ext);
  independentId(frames, kinds, Q, Qd, Qdd, id_free, lambda_free, tau_free);
  const double tau_error = sd::relative_error_to(to_eigen(id_srv.response.effort), VecQ(tau.tail(joints)));
  const double lambda_error = sd::relative_error_to(stacked(id_srv.response.contact_wrenches, kinds), lambda);
  std::printf("[%s] a wrench on %s with the contacts: effort %.3g, contact wrenches %.3g (the wrench moves λ by %.3g)\n",
              robot_.c_str(), link.c_str(), tau_error, lambda_error,
              static_cast<double>((lambda - lambda_free).norm() / lambda_free.norm()));
  EXPECT_LT(tau_error, kTolerance);
  EXPECT_LT(lambda_error, kTolerance);
  EXPECT_GT(static_cast<double>((lambda - lambda_free).norm()), 1.0) << "the wrench must reach the contacts";

  const VectorXd effort = sd_test::random_vector(joints, rng, 5.0);
  sd::ForwardDynamics fd = fdRequest(q, qd, effort);
  fd.request.external_wrenches = {wrench};
  fd = call("forward_dynamics", fd);
  ASSERT_TRUE(fd.response.success) << fd.response.message;
  MatQ M;
  const VecQ solution = independentFd(Q, Qd, effort, M, F_ext);
  EXPECT_LT(sd::relative_error_to(accelerations(fd), VecQ(solution.head(n))), kTolerance);
  EXPECT_LT(sd::relative_error_to(stacked(fd.response.contact_wrenches, kinds), VecQ(solution.tail(solution.size() - n))),
            kTolerance);
}

TEST_F(FloatingBase, BadInputsAreNamed) {
  startBase();
  const VectorXd q = stance(), qd = VectorXd::Zero(model.nv - 6);
  auto refused = [&](sd::InverseDynamics srv, const std::string& part) {
    srv = call("inverse_dynamics", srv);
    EXPECT_FALSE(srv.response.success) << part;
    EXPECT_TRUE(contains(srv.response.message, part)) << srv.response.message;
  };
  sd::InverseDynamics srv = request(q, qd, true);
  srv.request.base_pose.orientation.w = 2.0;
  refused(srv, "base_pose.orientation is not a unit quaternion");
  srv = request(q, qd, true);
  srv.request.contact_frames = {"no_such_link"};
  srv.request.contact_kinds = {"point"};
  refused(srv, "unknown frame 'no_such_link'");
  srv.request.contact_frames = {frames[0], frames[1]};
  srv.request.contact_kinds = {"point"};
  refused(srv, "2 frames but 1 kinds");
  srv.request.contact_frames = {frames[0]};
  srv.request.contact_kinds = {"sideways"};
  refused(srv, "unknown kind 'sideways'");
  srv.request.contact_kinds = {"point"};
  srv.request.contact_frictions = {-1.0};
  refused(srv, "friction coefficient");
  // ~set_contacts: refused naming the frame; the contacts stay.
  sd::SetContacts set;
  set.request.frames = {"no_such_link"};
  set.request.kinds = {"point"};
  set = call("set_contacts", set);
  EXPECT_FALSE(set.response.success);
  EXPECT_TRUE(contains(set.response.message, "no_such_link")) << set.response.message;
  sensor_msgs::JointState tau;
  sd::ContactWrenches w;
  sd::CentroidalState c;
  ASSERT_TRUE(publishJoints(q, tau, w, c));
  EXPECT_EQ(w.wrenches.size(), frames.size());
  // The trajectory service serves fixed bases only, and says so.
  sd::InverseDynamicsTrajectory trajectory;
  trajectory.request.trajectory.joint_names = names;
  trajectory.request.trajectory.points.resize(2);
  for (auto& point : trajectory.request.trajectory.points) point.positions = to_std(q);
  trajectory.request.trajectory.points[1].time_from_start = ros::Duration(0.1);
  trajectory = call("inverse_dynamics_trajectory", trajectory);
  EXPECT_FALSE(trajectory.response.success);
  EXPECT_TRUE(contains(trajectory.response.message, "floating")) << trajectory.response.message;
}

// Last: a base state that stops is refused once older than ~max_state_age (0.5 s in the launch file).
TEST_F(FloatingBase, ZStaleBaseStateIsRefusedNamingTheSource) {
  startBase();
  publishing_ = false;
  ros::Duration(1.0).sleep();
  const sd::InverseDynamics srv = call("inverse_dynamics", request(stance(), VectorXd::Zero(model.nv - 6), false));
  EXPECT_FALSE(srv.response.success);
  EXPECT_TRUE(contains(srv.response.message, odometry_ ? "odometry '/odom'" : "tf ('odom' to '" + root_link_ + "'"))
      << srv.response.message;
  if (odometry_) {
    EXPECT_TRUE(contains(srv.response.message, "older than max_state_age")) << srv.response.message;
  }
}
