// libFuzzer target: a service request decoder → every service handler. The fuzz input's first
// byte picks a service and a scene (the whole Panda, its arm as a reduced scene, the Panda
// with coupled mimic joints, or a floating Solo12 standing on its four feet); the rest decodes into
// that service's request: joint names (known, repeated or unknown), arrays of any length (up to
// thousands of entries), values that are NaN, ±Inf, huge, tiny or arbitrary bit patterns, frame
// names known to the robot, to the frame lookup, or to nobody, base poses, twists and accelerations
// (unit, non-unit or zero quaternions) and contacts (known or unknown frames and kinds, mismatched
// lengths, any friction) — or into a joint_states message merged into the cache, after which the
// scene's computed torques and centroidal state are computed. A handler must
// either answer with finite numbers or throw an error with a message; anything else (a crash, a
// non-finite answer, an empty error) is a finding.
// (ROS's own deserialiser is not the decoder here: it resizes arrays to the length a message
// claims before checking that the bytes are there, so a 20-byte message can ask for gigabytes —
// a property of roscpp, whose transport bounds a message by its frame size.)
#include <fuzzer/FuzzedDataProvider.h>
#include <sensor_msgs/JointState.h>

#include <cmath>
#include <iterator>
#include <limits>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>

#include "spatial_dynamics/reduction/couple_mimic_joints.hpp"
#include "spatial_dynamics/reduction/reduce_model.hpp"
#include "spatial_dynamics/ros/service_handlers.hpp"
#include "spatial_dynamics/urdf/model_builder.hpp"
#include "test_paths.hpp"

namespace sd = spatial_dynamics;

namespace {

/// One frame outside the robot, fixed to its root link.
class FixedFrames : public sd::FrameLookup {
 public:
  explicit FixedFrames(std::string root) : root_(std::move(root)) {}
  bool hasFrame(const std::string& frame) const override { return frame == root_ || frame == "sensor_mount"; }
  sd::PluckerTransform<double> transform(const std::string& target, const std::string& source,
                                         const ros::Time&) const override {
    const auto mount_in_root = sd::PluckerTransform<double>::FromPose(
        Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix(), Eigen::Vector3d(0.1, 0.2, 0.3));
    if (target == source) return sd::PluckerTransform<double>::Identity();
    if (target == "sensor_mount" && source == root_) return mount_in_root;  // ^mountX_root
    if (target == root_ && source == "sensor_mount") return mount_in_root.inverse();
    throw std::runtime_error("cannot transform from '" + source + "' to '" + target + "'");
  }

 private:
  std::string root_;
};

/// A floating base standing still at a pose of its own (or, when told, with no state to give).
class FixedBase : public sd::BaseStateSource {
 public:
  void state(const std::string& root_link, const ros::Time&, sd::BaseState& out) const override {
    if (missing) throw std::runtime_error("no base state yet for '" + root_link + "'");
    out.position = Eigen::Vector3d(0.1, -0.2, 0.3);
    out.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()));
    out.twist << 0.1, 0.2, -0.3, 0.4, 0.0, -0.1;
    out.world_frame = "odom";
  }
  bool missing = false;
};

struct Fixture {
  std::vector<std::shared_ptr<const sd::ServedScene>> scenes;
  std::unique_ptr<FixedFrames> frames;
  FixedBase base;
};

std::shared_ptr<const sd::ServedScene> make_scene(const std::shared_ptr<const sd::ServedRobot>& robot,
                                                  sd::Model<double> model) {
  auto scene = std::make_shared<sd::ServedScene>();
  scene->robot = robot;
  scene->model = std::make_shared<const sd::Model<double>>(std::move(model));
  scene->rigid_model = scene->model;
  scene->decoder = std::make_unique<sd::JointRequestDecoder>(*scene->model, robot->cache->jointNames());
  const sd::ContactSpec& c = robot->contacts;
  scene->contacts = sd::ContactSet<double>(*scene->model, c.frames, c.kinds, c.frictions);
  return scene;
}

std::string read_robot(const std::string& name) {
  std::ifstream file(std::string(sd_test::robots_dir()) + "/" + name + ".urdf");
  return std::string((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
}

/// Solo12 with a floating base, on its four feet (point contacts, μ = 0.7).
std::shared_ptr<const sd::ServedScene> floating_solo12() {
  sd::ModelBuildOptions options;
  options.floating_base = true;
  auto robot = std::make_shared<sd::ServedRobot>();
  robot->bare = std::make_shared<const sd::Model<double>>(sd::build_model_from_urdf_string(read_robot("solo12"), options));
  robot->full = robot->bare;
  const std::vector<std::string> names = robot->bare->velocityNames();
  robot->cache = std::make_shared<sd::JointStateCache>(std::vector<std::string>(names.begin() + 6, names.end()), 1e9);
  robot->robot_name = robot->bare->name;
  robot->root_frame = robot->bare->body_names[1];
  robot->floating_base = true;
  robot->contacts = {{"FL_FOOT", "FR_FOOT", "HL_FOOT", "HR_FOOT"}, {"point", "point", "point", "point"}, {0.7, 0.7, 0.7, 0.7}};
  return make_scene(robot, *robot->bare);
}

Fixture& fixture() {
  static Fixture f = [] {
    Fixture fx;
    const std::string urdf = read_robot("panda");
    auto robot = std::make_shared<sd::ServedRobot>();
    robot->bare = std::make_shared<const sd::Model<double>>(sd::build_model_from_urdf_string(urdf));
    robot->full = robot->bare;
    robot->cache = std::make_shared<sd::JointStateCache>(
        std::vector<std::string>(robot->bare->joint_names.begin() + 1, robot->bare->joint_names.end()), 1e9);
    robot->robot_name = robot->bare->name;
    robot->root_frame = robot->bare->body_names[0];
    const sd::Model<double>& full = *robot->bare;
    sd::Scene arm;
    for (int k = 1; k <= 7; ++k) arm.kept_joints.push_back("panda_joint" + std::to_string(k));
    fx.scenes.push_back(make_scene(robot, full));
    fx.scenes.push_back(make_scene(robot, sd::reduce_model(full, arm)));
    fx.scenes.push_back(make_scene(robot, sd::couple_mimic_joints(full)));
    fx.scenes.push_back(floating_solo12());
    fx.frames = std::make_unique<FixedFrames>(robot->root_frame);
    return fx;
  }();
  return f;
}

/// Builds requests from fuzz bytes.
class RequestDecoder {
 public:
  RequestDecoder(FuzzedDataProvider& bytes, const sd::Model<double>& model) : in_(bytes), model_(model) {}

  double value() {
    static const double special[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                                     -std::numeric_limits<double>::infinity(), 1e308, -1e308, 1e-308, 5e-324, -0.0, 0.0,
                                     1.0, -1.0, 3.141592653589793, 1e6, -1e6};
    switch (in_.ConsumeIntegralInRange<int>(0, 3)) {
      case 0: return special[in_.ConsumeIntegralInRange<std::size_t>(0, std::size(special) - 1)];
      case 1: return in_.ConsumeFloatingPoint<double>();  // any bit pattern's worth of range
      default: return in_.ConsumeFloatingPointInRange<double>(-4.0, 4.0);
    }
  }
  std::vector<double> values() {
    std::size_t n = in_.ConsumeIntegralInRange<std::size_t>(0, 12);
    if (in_.ConsumeBool() && in_.ConsumeBool()) n = in_.ConsumeIntegralInRange<std::size_t>(0, 5000);  // huge arrays
    std::vector<double> v(n);
    const double fill = value();
    for (auto& x : v) x = in_.remaining_bytes() > 0 ? value() : fill;
    return v;
  }
  std::string name(const std::vector<std::string>& known) {
    if (in_.ConsumeIntegralInRange<int>(0, 7) == 0) return in_.ConsumeRandomLengthString(24);  // unknown
    return known[in_.ConsumeIntegralInRange<std::size_t>(0, known.size() - 1)];
  }
  std::vector<std::string> joint_names() {
    std::vector<std::string> names(in_.ConsumeIntegralInRange<std::size_t>(0, 12));
    for (auto& n : names) n = name(joints_);
    return names;
  }
  std::string frame() {
    if (in_.ConsumeIntegralInRange<int>(0, 5) == 0) return in_.ConsumeBool() ? "sensor_mount" : "";
    return name(frames_);
  }
  geometry_msgs::Pose pose() {
    geometry_msgs::Pose p;
    switch (in_.ConsumeIntegralInRange<int>(0, 3)) {
      case 0: return p;  // not given
      case 1: p.orientation.w = 1.0; break;
      default:
        p.orientation.x = value(); p.orientation.y = value(); p.orientation.z = value(); p.orientation.w = value();
    }
    p.position.x = value(); p.position.y = value(); p.position.z = value();
    return p;
  }
  template <class Message>
  Message six() {
    Message m;
    if (in_.ConsumeBool()) return m;
    m.angular.x = value(); m.angular.y = value(); m.angular.z = value();
    m.linear.x = value(); m.linear.y = value(); m.linear.z = value();
    return m;
  }
  template <class Request>
  void fill_base_and_contacts(Request& r) {
    r.base_pose = pose();
    r.base_twist = six<geometry_msgs::Twist>();
    const std::size_t n = in_.ConsumeIntegralInRange<std::size_t>(0, 5);
    static const std::vector<std::string> kinds = {"point", "surface"};
    for (std::size_t k = 0; k < n; ++k) {
      r.contact_frames.push_back(frame());
      r.contact_kinds.push_back(in_.ConsumeIntegralInRange<int>(0, 7) == 0 ? in_.ConsumeRandomLengthString(8) : name(kinds));
      if (in_.ConsumeBool()) r.contact_frictions.push_back(value());
    }
    r.ignore_contacts = in_.ConsumeIntegralInRange<int>(0, 3) == 0;
  }
  geometry_msgs::WrenchStamped wrench() {
    geometry_msgs::WrenchStamped w;
    w.header.frame_id = frame();
    w.wrench.force.x = value(); w.wrench.force.y = value(); w.wrench.force.z = value();
    w.wrench.torque.x = value(); w.wrench.torque.y = value(); w.wrench.torque.z = value();
    return w;
  }
  std::vector<geometry_msgs::WrenchStamped> wrenches() {
    std::vector<geometry_msgs::WrenchStamped> w(in_.ConsumeIntegralInRange<std::size_t>(0, 3));
    for (auto& x : w) x = wrench();
    return w;
  }

  void fill(sd::InverseDynamics::Request& r) {
    r.name = joint_names(); r.position = values(); r.velocity = values(); r.acceleration = values(); r.external_wrenches = wrenches();
    fill_base_and_contacts(r);
    r.base_acceleration = six<geometry_msgs::Accel>();
  }
  void fill(sd::ForwardDynamics::Request& r) {
    r.name = joint_names(); r.position = values(); r.velocity = values(); r.effort = values(); r.external_wrenches = wrenches();
    fill_base_and_contacts(r);
  }
  void fill(sd::MassMatrix::Request& r) {
    r.name = joint_names(); r.position = values();
    fill_base_and_contacts(r);
  }
  void fill(sd::TransformWrench::Request& r) {
    r.wrench = wrench();
    r.target_frame = frame();
    r.name = joint_names();
    r.position = values();
  }
  void fill(sd::InverseDynamicsTrajectory::Request& r) {
    r.trajectory.joint_names = joint_names();
    r.trajectory.points.resize(in_.ConsumeIntegralInRange<std::size_t>(0, 6));
    if (in_.ConsumeBool() && in_.ConsumeBool()) r.trajectory.points.resize(in_.ConsumeIntegralInRange<std::size_t>(0, 600));
    double t = value();
    for (auto& p : r.trajectory.points) {
      p.positions = values();
      if (in_.ConsumeBool()) p.velocities = values();
      if (in_.ConsumeBool()) p.accelerations = values();
      // Mostly increasing times; sometimes repeated, decreasing or any value (the time is checked).
      t = in_.ConsumeBool() ? t + in_.ConsumeFloatingPointInRange<double>(0.0, 0.1) : value();
      p.time_from_start = ros::Duration(std::isfinite(t) && std::abs(t) < 1e9 ? t : 0.0);
    }
  }
  void fill(sensor_msgs::JointState& m) { m.name = joint_names(); m.position = values(); m.velocity = values(); }

  void set_names(const sd::ServedScene& scene) {
    joints_ = scene.robot->cache->jointNames();
    frames_.clear();
    for (const auto& f : model_.frames) frames_.push_back(f.name);
  }

 private:
  FuzzedDataProvider& in_;
  const sd::Model<double>& model_;
  std::vector<std::string> joints_, frames_;
};

void finding(const char* what) {
  std::fprintf(stderr, "FINDING: %s\n", what);
  std::abort();
}

template <class Vector>
void require_finite(const Vector& values, const char* what) {
  for (double v : values)
    if (!std::isfinite(v)) finding(what);
}

void require_finite(const geometry_msgs::Wrench& w, const char* what) {
  require_finite(std::vector<double>{w.force.x, w.force.y, w.force.z, w.torque.x, w.torque.y, w.torque.z}, what);
}
template <class Response>
void check_contact_answers(const Response& r) {
  for (const auto& w : r.contact_wrenches) require_finite(w.wrench, "non-finite contact wrench");
}
void check_response(const sd::InverseDynamics::Response& r) {
  require_finite(r.effort, "non-finite effort");
  require_finite(r.base_wrench, "non-finite base wrench");
  check_contact_answers(r);
}
void check_response(const sd::ForwardDynamics::Response& r) {
  require_finite(r.acceleration, "non-finite acceleration");
  const auto& a = r.base_acceleration;
  require_finite(std::vector<double>{a.angular.x, a.angular.y, a.angular.z, a.linear.x, a.linear.y, a.linear.z},
                 "non-finite base acceleration");
  check_contact_answers(r);
}
void check_response(const sd::MassMatrix::Response& r) { require_finite(r.mass_matrix, "non-finite mass matrix"); }
void check_response(const sd::InverseDynamicsTrajectory::Response& r) {
  for (const auto& p : r.points) require_finite(p.effort, "non-finite trajectory effort");
  require_finite(r.peak_effort, "non-finite peak effort");
  if (r.first_violation.size() != r.peak_effort.size()) finding("first_violation and peak_effort differ in length");
}
void check_response(const sd::TransformWrench::Response& r) {
  const auto& w = r.wrench.wrench;
  require_finite(std::vector<double>{w.force.x, w.force.y, w.force.z, w.torque.x, w.torque.y, w.torque.z},
                 "non-finite wrench");
}


template <class Request, class Response, class Handler>
void run(RequestDecoder& decoder, Handler&& handler) {
  Request request;
  decoder.fill(request);
  Response response;
  try {
    handler(request, response);
  } catch (const std::exception& e) {
    if (std::strlen(e.what()) == 0) finding("an error without a message");
    return;
  }
  check_response(response);
}

}  // namespace

// The scenes are built once, before the first input, so that their set-up never counts against an
// input's time limit.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  fixture();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  Fixture& fx = fixture();
  const std::uint8_t selector = data[0];
  const std::size_t index = (selector >> 3) % fx.scenes.size();
  const sd::ServedScene& scene = *fx.scenes[index];
  const sd::WorkspacePool::Lease workspace = scene.workspaces.acquire(*scene.model);
  sd::Workspace& ws = *workspace;
  FuzzedDataProvider bytes(data + 1, size - 1);
  RequestDecoder decoder(bytes, *scene.model);
  decoder.set_names(scene);
  switch (selector % 6) {
    case 0:
      run<sd::InverseDynamics::Request, sd::InverseDynamics::Response>(
          decoder, [&](auto& req, auto& res) { sd::compute_inverse_dynamics(scene, fx.base, ws, req, res); });
      break;
    case 1:
      run<sd::ForwardDynamics::Request, sd::ForwardDynamics::Response>(
          decoder, [&](auto& req, auto& res) { sd::compute_forward_dynamics(scene, fx.base, ws, req, res); });
      break;
    case 2:
      run<sd::MassMatrix::Request, sd::MassMatrix::Response>(
          decoder, [&](auto& req, auto& res) { sd::compute_mass_matrix(scene, fx.base, ws, req, res); });
      break;
    case 3:
      run<sd::TransformWrench::Request, sd::TransformWrench::Response>(
          decoder, [&](auto& req, auto& res) { sd::compute_transform_wrench(scene, ws, *fx.frames, req, res); });
      break;
    case 4:
      run<sd::InverseDynamicsTrajectory::Request, sd::InverseDynamicsTrajectory::Response>(
          decoder, [&](auto& req, auto& res) { sd::compute_inverse_dynamics_trajectory(scene, ws, req, res); });
      break;
    default: {  // a joint_states message from a misbehaving publisher
      sensor_msgs::JointState msg;
      decoder.fill(msg);
      scene.robot->cache->update(msg.name, msg.position, msg.velocity);
      fx.base.missing = bytes.ConsumeIntegralInRange<int>(0, 7) == 0;
      try {  // ~computed_torques, ~computed_contact_wrenches and ~centroidal_state of that state
        sensor_msgs::JointState torques;
        std::vector<geometry_msgs::WrenchStamped> wrenches;
        if (sd::compute_latest_torques(scene, fx.base, ws, ros::Time(), torques, wrenches)) {
          require_finite(torques.effort, "non-finite computed torque");
          for (const auto& w : wrenches) require_finite(w.wrench, "non-finite computed contact wrench");
        }
        sd::CentroidalState centroidal;
        if (sd::compute_centroidal_state(scene, fx.base, ws, ros::Time(), centroidal))
          require_finite(std::vector<double>{centroidal.center_of_mass.x, centroidal.linear_momentum.z,
                                             centroidal.angular_momentum.x},
                         "non-finite centroidal state");
      } catch (const std::exception& e) {
        if (std::strlen(e.what()) == 0) finding("an error without a message");
      }
      fx.base.missing = false;
    }
  }
  return 0;
}
