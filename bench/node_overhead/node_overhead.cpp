// The node's own overhead (scripts/run_node_overhead.sh starts the processes on loopback):
//  1. service round trip: InverseDynamics calls to the dynamics node against the same calls to
//     a node that computes nothing (empty_service_node), over persistent connections, in
//     interleaved repeats; median per repeat, then the median of the repeats and their ratio;
//  2. joint_states → ~computed_torques at a fixed rate: the node's own latency from a message's
//     arrival to its computed torques (read from the node's diagnostics), and the end-to-end
//     latency a subscriber sees (publish stamp to receipt, two loopback hops).
// Usage: node_overhead [--calls 2000] [--repeats 5] [--seconds 20] [--rate 1000] [--out FILE]
#include <diagnostic_msgs/DiagnosticArray.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

#include <algorithm>
#include <cmath>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <random>
#include <sstream>
#include <string>
#include <thread>

#include "spatial_dynamics/InverseDynamics.h"
#include "spatial_dynamics/urdf/model_builder.hpp"

namespace sd = spatial_dynamics;
using Clock = std::chrono::steady_clock;

namespace {

struct Options {
  int calls = 2000, repeats = 5;
  double seconds = 20, rate = 1000;
  std::string out;
};

/// Nearest-rank percentile (⌈p·n⌉-th smallest) of `values` (sorted in place).
double percentile(std::vector<double>& values, double p) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(values.size())));
  return values[std::max<std::size_t>(rank, 1) - 1];
}

struct RoundTrips {
  std::vector<double> repeat_medians_us;
  std::vector<double> all_us;
  long failures = 0;
};

/// One repeat: `calls` calls through `client`, cycling through `requests`.
void time_calls(ros::ServiceClient& client, std::vector<sd::InverseDynamics>& requests, int calls, RoundTrips& out) {
  std::vector<double> us;
  us.reserve(calls);
  for (int k = 0; k < calls; ++k) {
    sd::InverseDynamics& srv = requests[k % requests.size()];
    const auto start = Clock::now();
    const bool ok = client.call(srv);
    us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - start).count());
    if (!ok || !srv.response.success) ++out.failures;
  }
  out.all_us.insert(out.all_us.end(), us.begin(), us.end());
  out.repeat_medians_us.push_back(percentile(us, 0.5));
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "node_overhead", ros::init_options::AnonymousName);
  Options opt;
  for (int k = 1; k + 1 < argc; k += 2) {
    const std::string key = argv[k], value = argv[k + 1];
    if (key == "--calls") opt.calls = std::stoi(value);
    else if (key == "--repeats") opt.repeats = std::stoi(value);
    else if (key == "--seconds") opt.seconds = std::stod(value);
    else if (key == "--rate") opt.rate = std::stod(value);
    else if (key == "--out") opt.out = value;
    else {
      std::fprintf(stderr, "unknown option %s\n", key.c_str());
      return 2;
    }
  }
  std::string urdf;
  for (int k = 0; k < 300 && !ros::param::get("robot_description", urdf); ++k) ros::WallDuration(0.1).sleep();
  if (urdf.empty()) {
    std::fprintf(stderr, "robot_description is not set\n");
    return 1;
  }
  const sd::Model<double> model = sd::build_model_from_urdf_string(urdf);
  const std::vector<std::string> names(model.joint_names.begin() + 1, model.joint_names.end());
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(2);
  spinner.start();

  // 1. Service round trips, interleaved: real then empty in even repeats, the reverse in odd ones.
  const std::string real_name = "/dynamics/inverse_dynamics", empty_name = "/empty_service/inverse_dynamics";
  if (!ros::service::waitForService(real_name, ros::Duration(30)) ||
      !ros::service::waitForService(empty_name, ros::Duration(30))) {
    std::fprintf(stderr, "the services %s and %s are not both up\n", real_name.c_str(), empty_name.c_str());
    return 1;
  }
  ros::ServiceClient real = nh.serviceClient<sd::InverseDynamics>(real_name, true);
  ros::ServiceClient empty = nh.serviceClient<sd::InverseDynamics>(empty_name, true);
  // States a controller would send: positions inside the URDF limits (outside, the answer carries a
  // warning per joint and is longer than the yardstick's).
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> uniform(-1.5, 1.5), unit(0.0, 1.0);
  std::vector<sd::InverseDynamics> requests(64);
  for (auto& srv : requests) {
    srv.request.name = names;
    for (std::size_t j = 0; j < names.size(); ++j) {
      const auto& limits = model.joints[model.jointBody(names[j])].limits;
      const double lower = std::max(limits.position_lower, -1.5), upper = std::min(limits.position_upper, 1.5);
      srv.request.position.push_back(upper > lower ? lower + unit(rng) * (upper - lower) : 0.5 * (lower + upper));
      srv.request.velocity.push_back(uniform(rng));
      srv.request.acceleration.push_back(uniform(rng));
    }
  }
  RoundTrips real_trips, empty_trips, warm_up;
  time_calls(real, requests, 500, warm_up);
  time_calls(empty, requests, 500, warm_up);
  for (int r = 0; r < opt.repeats; ++r) {
    if (r % 2 == 0) {
      time_calls(real, requests, opt.calls, real_trips);
      time_calls(empty, requests, opt.calls, empty_trips);
    } else {
      time_calls(empty, requests, opt.calls, empty_trips);
      time_calls(real, requests, opt.calls, real_trips);
    }
  }
  const double real_median = percentile(real_trips.repeat_medians_us, 0.5);
  const double empty_median = percentile(empty_trips.repeat_medians_us, 0.5);
  const double real_p99 = percentile(real_trips.all_us, 0.99), empty_p99 = percentile(empty_trips.all_us, 0.99);

  // 2. joint_states at opt.rate; the node's computed torques carry the joint_states header.
  std::mutex mutex;
  std::vector<double> end_to_end_us;
  std::atomic<long> torques{0};
  ros::Subscriber torque_sub = nh.subscribe<sensor_msgs::JointState>(
      "/dynamics/computed_torques", 10000,
      [&](const sensor_msgs::JointState::ConstPtr& msg) {
        const double us = (ros::Time::now() - msg->header.stamp).toSec() * 1e6;
        std::lock_guard<std::mutex> lock(mutex);
        end_to_end_us.push_back(us);
        ++torques;
      },
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  std::map<std::string, double> node_figures;
  ros::Subscriber diag_sub = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 10, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& msg) {
        for (const auto& status : msg->status)
          for (const auto& kv : status.values)
            if (kv.key.rfind("computed_torques latency", 0) == 0) {
              std::lock_guard<std::mutex> lock(mutex);
              node_figures[kv.key] = std::atof(kv.value.c_str());
            }
      });
  ros::Publisher joint_states = nh.advertise<sensor_msgs::JointState>("/joint_states", 10000);
  for (int k = 0; k < 100 && (joint_states.getNumSubscribers() == 0 || torque_sub.getNumPublishers() == 0); ++k)
    ros::Duration(0.05).sleep();
  sensor_msgs::JointState msg;
  msg.name = names;
  msg.position.assign(names.size(), 0.0);
  msg.velocity.assign(names.size(), 0.0);
  const auto period = std::chrono::duration<double>(1.0 / opt.rate);
  const long count = static_cast<long>(opt.seconds * opt.rate);
  const auto start = Clock::now();
  for (long k = 0; k < count && ros::ok(); ++k) {
    std::this_thread::sleep_until(start + std::chrono::duration_cast<Clock::duration>(period * k));
    for (std::size_t j = 0; j < names.size(); ++j) msg.position[j] = 0.5 * std::sin(1e-3 * k + j);
    msg.header.stamp = ros::Time::now();
    joint_states.publish(msg);
  }
  ros::Duration(2.5).sleep();  // the last torques arrive; the node's diagnostics (1 Hz) cover the run's end
  std::vector<double> e2e;
  std::map<std::string, double> node;
  {
    std::lock_guard<std::mutex> lock(mutex);
    e2e = end_to_end_us;
    node = node_figures;
  }
  const double e2e_p50 = percentile(e2e, 0.5), e2e_p99 = percentile(e2e, 0.99), e2e_max = e2e.empty() ? 0 : e2e.back();

  std::ostringstream report;
  char line[512];
  report << "| figure | value |\n|---|---|\n";
  std::snprintf(line, sizeof line,
                "| InverseDynamics round trip, median of %d repeat medians (%d calls each) | %.1f µs (p99 %.1f µs) |\n",
                opt.repeats, opt.calls, real_median, real_p99);
  report << line;
  std::snprintf(line, sizeof line, "| empty service of the same message sizes, same run | %.1f µs (p99 %.1f µs) |\n",
                empty_median, empty_p99);
  report << line;
  std::snprintf(line, sizeof line, "| ratio (target ≤ 1.15) | %.3f |\n", real_median / empty_median);
  report << line;
  std::snprintf(line, sizeof line, "| failed calls | %ld |\n", real_trips.failures + empty_trips.failures);
  report << line;
  std::snprintf(line, sizeof line, "| joint_states published / computed_torques received (%.0f Hz, %.0f s) | %ld / %ld |\n",
                opt.rate, opt.seconds, count, static_cast<long>(torques));
  report << line;
  const auto figure = [&](const char* key) { return node.count(key) ? node.at(key) : -1.0; };
  std::snprintf(line, sizeof line,
                "| node: arrival → computed_torques published, p50 / p99 / max (last %.0f messages; target p99 ≤ 100 µs) | %.1f / %.1f / %.1f µs |\n",
                figure("computed_torques latency window [messages]"), figure("computed_torques latency p50 [us]"),
                figure("computed_torques latency p99 [us]"), figure("computed_torques latency max [us]"));
  report << line;
  std::snprintf(line, sizeof line, "| end to end: publish → receipt by a subscriber (two loopback hops), p50 / p99 / max | %.1f / %.1f / %.1f µs |\n",
                e2e_p50, e2e_p99, e2e_max);
  report << line;
  std::printf("%s", report.str().c_str());
  if (!opt.out.empty()) std::ofstream(opt.out) << report.str();
  const bool ok = real_trips.failures == 0 && empty_trips.failures == 0 && torques == count && !node.empty();
  return ok ? 0 : 1;
}
