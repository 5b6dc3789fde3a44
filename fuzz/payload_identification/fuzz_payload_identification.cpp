// libFuzzer target: ~identify_payload's and ~excitation_trajectory's handlers
// (ros/payload_identification_handlers.hpp) on the Panda, independent or with coupled mimic joints
// (the first byte picks the service and the model). The rest decodes into a request: joint names
// (known, repeated, mimic or unknown), points with arrays of any length, values that are NaN, ±Inf,
// huge, tiny or arbitrary, times that increase, repeat or go back, frames known or not, a prior
// payload; durations up to 60 s (the trajectory's longer durations only add points), scales and
// accelerations of any value. A handler must answer with a physical body and finite numbers (a
// standard deviation may be NaN only where a parameter is held at the prior), or a trajectory
// within the limits at rest at both ends — or throw an error with a message.
#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>

#include "spatial_dynamics/reduction/couple_mimic_joints.hpp"
#include "spatial_dynamics/ros/payload_identification_handlers.hpp"
#include "spatial_dynamics/urdf/model_builder.hpp"
#include "test_paths.hpp"

namespace sd = spatial_dynamics;

namespace {

struct Robot {
  sd::Model<double> model;
  std::unique_ptr<sd::JointStateCache> cache;
  std::unique_ptr<sd::JointRequestDecoder> decoder;
  std::vector<std::string> joints, frames;
};

std::vector<Robot>& robots() {
  static std::vector<Robot> all = [] {
    std::ifstream file(std::string(sd_test::robots_dir()) + "/panda.urdf");
    const std::string urdf((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    const sd::Model<double> bare = sd::build_model_from_urdf_string(urdf);
    std::vector<Robot> out(2);
    out[0].model = bare;
    out[1].model = sd::couple_mimic_joints(bare);
    for (Robot& r : out) {
      const std::vector<std::string> names = bare.velocityNames();
      r.cache = std::make_unique<sd::JointStateCache>(names, 1e9);
      r.cache->update(names, std::vector<double>(names.size(), 0.1), std::vector<double>(names.size(), 0.0));
      r.decoder = std::make_unique<sd::JointRequestDecoder>(r.model, names);
      r.joints = names;
      for (const auto& f : r.model.frames) r.frames.push_back(f.name);
    }
    return out;
  }();
  return all;
}

class Decoder {
 public:
  Decoder(FuzzedDataProvider& in, const Robot& robot) : in_(in), robot_(robot) {}
  double value() {
    static const double special[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                                     -std::numeric_limits<double>::infinity(), 1e308, -1e308, 1e-308, -0.0, 0.0, 1.0, -1.0,
                                     0.5, 600.0, 601.0, 1e6};
    switch (in_.ConsumeIntegralInRange<int>(0, 3)) {
      case 0: return special[in_.ConsumeIntegralInRange<std::size_t>(0, std::size(special) - 1)];
      case 1: return in_.ConsumeFloatingPoint<double>();
      default: return in_.ConsumeFloatingPointInRange<double>(-3.0, 3.0);
    }
  }
  std::vector<double> values(std::size_t usual) {
    std::size_t n = in_.ConsumeBool() ? usual : in_.ConsumeIntegralInRange<std::size_t>(0, 12);
    std::vector<double> v(n);
    for (auto& x : v) x = value();
    return v;
  }
  std::string name(const std::vector<std::string>& known) {
    if (in_.ConsumeIntegralInRange<int>(0, 7) == 0) return in_.ConsumeRandomLengthString(16);
    return known[in_.ConsumeIntegralInRange<std::size_t>(0, known.size() - 1)];
  }
  std::vector<std::string> joint_names() {
    if (in_.ConsumeBool()) return {robot_.joints.begin(), robot_.joints.begin() + 7};  // the arm
    std::vector<std::string> names(in_.ConsumeIntegralInRange<std::size_t>(0, 10));
    for (auto& n : names) n = name(robot_.joints);
    return names;
  }
  void fill(sd::IdentifyPayload::Request& r) {
    r.frame = name(robot_.frames);
    r.samples.joint_names = joint_names();
    const std::size_t width = r.samples.joint_names.empty() ? robot_.model.nv : r.samples.joint_names.size();
    r.samples.points.resize(in_.ConsumeIntegralInRange<std::size_t>(0, 40));
    double t = 0;
    const bool accelerations = in_.ConsumeBool();
    for (auto& p : r.samples.points) {
      p.positions = values(width);
      p.velocities = values(width);
      if (accelerations || in_.ConsumeIntegralInRange<int>(0, 15) == 0) p.accelerations = values(width);
      p.effort = values(width);
      t = in_.ConsumeIntegralInRange<int>(0, 7) ? t + in_.ConsumeFloatingPointInRange<double>(0.001, 0.1) : value();
      p.time_from_start = ros::Duration(std::isfinite(t) && std::abs(t) < 1e9 ? t : 0.0);
    }
    r.identify_friction = in_.ConsumeBool();
  }
  void fill(sd::ExcitationTrajectory::Request& r) {
    r.joints = joint_names();
    const double duration = value();
    r.duration = std::isfinite(duration) && duration > 60 ? 60 : duration;
    r.speed_scale = value();
    r.max_acceleration = value();
  }
  sd::Payload prior() {
    sd::Payload p;
    if (in_.ConsumeBool()) return p;
    p.mass = std::abs(in_.ConsumeFloatingPointInRange<double>(0.0, 5.0));
    p.center_of_mass = Eigen::Vector3d(value(), value(), value()).cwiseMin(1.0).cwiseMax(-1.0);
    p.inertia = Eigen::Vector3d(0.01, 0.02, 0.025).asDiagonal();
    if (!p.center_of_mass.allFinite()) p.center_of_mass.setZero();
    return p;
  }

 private:
  FuzzedDataProvider& in_;
  const Robot& robot_;
};

void finding(const std::string& what) {
  std::fprintf(stderr, "FINDING: %s\n", what.c_str());
  std::abort();
}

void check(const sd::IdentifyPayload::Response& r) {
  const geometry_msgs::Inertia& m = r.inertia;
  Eigen::Matrix3d I;
  I << m.ixx, m.ixy, m.ixz, m.ixy, m.iyy, m.iyz, m.ixz, m.iyz, m.izz;
  const std::string problem = sd::inertia_problem(m.m, Eigen::Vector3d(m.com.x, m.com.y, m.com.z), I);
  if (!problem.empty()) finding("an identified payload that is not a body: " + problem);
  if (!(m.m > 0)) finding("an identified payload without mass");
  for (double x : r.residual_rms) if (!std::isfinite(x)) finding("a non-finite residual");
  for (double x : r.damping) if (!std::isfinite(x)) finding("a non-finite damping");
  for (double x : r.friction) if (!std::isfinite(x)) finding("a non-finite friction");
  if (r.name.size() != r.residual_rms.size()) finding("name and residual_rms differ in length");
  const double s[] = {r.stddev.m, r.stddev.com.x, r.stddev.ixx, r.stddev.izz};
  for (double x : s)
    if (std::isnan(x) && r.unidentifiable.empty()) finding("a NaN standard deviation with every parameter identified");
}

void check(const sd::ExcitationTrajectory::Response& r, const Robot& robot) {
  const auto& t = r.trajectory;
  if (t.points.size() < 2) finding("a trajectory of fewer than two points");
  for (std::size_t j = 0; j < t.joint_names.size(); ++j) {
    const sd::JointLimits<double>& limits = robot.model.joints[robot.model.jointBody(t.joint_names[j])].limits;
    for (const auto& p : t.points) {
      if (!std::isfinite(p.positions[j]) || !std::isfinite(p.velocities[j]) || !std::isfinite(p.accelerations[j]))
        finding("a non-finite trajectory point");
      if (std::abs(p.velocities[j]) > limits.velocity * (1 + 1e-9)) finding("a velocity above the limit");
      if (p.positions[j] < limits.position_lower - 1e-9 || p.positions[j] > limits.position_upper + 1e-9)
        finding("a position outside the limits");
    }
    if (std::abs(t.points.front().velocities[j]) > 1e-9 || std::abs(t.points.back().velocities[j]) > 1e-9)
      finding("a trajectory not at rest at its ends");
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  robots();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const Robot& robot = robots()[(data[0] >> 1) % 2];
  FuzzedDataProvider bytes(data + 1, size - 1);
  Decoder decoder(bytes, robot);
  sd::JointStateCache::Snapshot state;
  robot.cache->snapshot(state);
  try {
    if (data[0] % 2 == 0) {
      sd::IdentifyPayload::Request req;
      decoder.fill(req);
      sd::IdentifyPayload::Response res;
      sd::compute_identify_payload({robot.model, *robot.decoder, state, decoder.prior()}, req.frame, req.samples,
                                   req.identify_friction, res);
      check(res);
    } else {
      sd::ExcitationTrajectory::Request req;
      decoder.fill(req);
      sd::ExcitationTrajectory::Response res;
      sd::compute_excitation_trajectory({robot.model, *robot.decoder, state, sd::Payload{}}, req, res);
      check(res, robot);
    }
  } catch (const std::exception& e) {
    if (std::strlen(e.what()) == 0) finding("an error without a message");
  }
  return 0;
}
