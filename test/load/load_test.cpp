// Load test of a running dynamics node (started by scripts/run_load_test.sh on loopback): joint
// states at a fixed rate and concurrent service clients for a bounded time and number of calls.
// Reports calls served, failures (an error answer, a lost call or a wrong number), latency
// percentiles, computed-torque messages against joint-state messages, and the node's CPU and
// memory over the run. Usage:
//   load_test --node-pid PID [--seconds 60] [--clients 8] [--rate 1000] [--max-calls 2000000] [--out FILE]
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <unistd.h>

#include "spatial_dynamics/ForwardDynamics.h"
#include "spatial_dynamics/InverseDynamics.h"
#include "spatial_dynamics/MassMatrix.h"
#include "spatial_dynamics/algorithms.hpp"
#include "spatial_dynamics/urdf/model_builder.hpp"

namespace sd = spatial_dynamics;
using Clock = std::chrono::steady_clock;

namespace {

struct ProcessSample {
  double seconds = 0;      // since the start of the run
  double cpu_seconds = 0;  // user + system time of the node
  long rss_kib = 0, peak_kib = 0;
};

ProcessSample sample_process(int pid, Clock::time_point start) {
  ProcessSample s;
  s.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string content((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
  const std::size_t close = content.rfind(')');
  if (close != std::string::npos) {
    std::istringstream fields(content.substr(close + 2));
    std::string field;
    long utime = 0, stime = 0;
    for (int k = 3; k <= 15 && fields >> field; ++k) {  // fields 14 and 15: utime, stime (clock ticks)
      if (k == 14) utime = std::stol(field);
      if (k == 15) stime = std::stol(field);
    }
    s.cpu_seconds = static_cast<double>(utime + stime) / sysconf(_SC_CLK_TCK);
  }
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) == 0) s.rss_kib = std::stol(line.substr(6));
    if (line.rfind("VmHWM:", 0) == 0) s.peak_kib = std::stol(line.substr(6));
  }
  return s;
}

std::vector<double> to_std(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

double percentile(std::vector<double>& sorted, double p) {
  if (sorted.empty()) return 0;
  return sorted[std::min(sorted.size() - 1, static_cast<std::size_t>(p * (sorted.size() - 1) + 0.5))];
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "load_test", ros::init_options::AnonymousName);
  int node_pid = 0, clients = 8;
  double seconds = 60, rate = 1000;
  long max_calls = 2000000;
  std::string out_file;
  for (int k = 1; k + 1 < argc; k += 2) {
    const std::string key = argv[k], value = argv[k + 1];
    if (key == "--node-pid") node_pid = std::stoi(value);
    else if (key == "--seconds") seconds = std::stod(value);
    else if (key == "--clients") clients = std::stoi(value);
    else if (key == "--rate") rate = std::stod(value);
    else if (key == "--max-calls") max_calls = std::stol(value);
    else if (key == "--out") out_file = value;
    else {
      std::fprintf(stderr, "unknown option %s\n", key.c_str());
      return 2;
    }
  }
  if (node_pid <= 0) {
    std::fprintf(stderr, "--node-pid is required\n");
    return 2;
  }
  std::string urdf;
  if (!ros::param::get("robot_description", urdf)) {
    std::fprintf(stderr, "robot_description is not set\n");
    return 2;
  }
  const sd::Model<double> model = sd::build_model_from_urdf_string(urdf);
  std::vector<std::string> names(model.joint_names.begin() + 1, model.joint_names.end());
  for (const char* s : {"inverse_dynamics", "forward_dynamics", "mass_matrix"})
    if (!ros::service::waitForService(std::string("/dynamics/") + s, ros::Duration(30))) {
      std::fprintf(stderr, "the node's services did not appear\n");
      return 1;
    }

  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  std::atomic<long> torques_received{0};
  ros::Subscriber torques = nh.subscribe<sensor_msgs::JointState>(
      "/dynamics/computed_torques", 100000, [&](const sensor_msgs::JointState::ConstPtr&) { ++torques_received; },
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  ros::Publisher joint_states = nh.advertise<sensor_msgs::JointState>("/joint_states", 100000);
  for (int k = 0; k < 200 && (joint_states.getNumSubscribers() == 0 || torques.getNumPublishers() == 0); ++k)
    ros::Duration(0.05).sleep();

  const Clock::time_point start = Clock::now();
  const Clock::time_point deadline = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  std::atomic<bool> stop{false};
  std::atomic<long> calls_started{0};
  std::vector<ProcessSample> samples{sample_process(node_pid, start)};

  long joint_states_sent = 0;
  std::thread streamer([&] {  // joint states along a smooth trajectory at `rate`
    const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / rate));
    Clock::time_point next = Clock::now();
    sensor_msgs::JointState msg;
    msg.name = names;
    msg.position.resize(names.size());
    msg.velocity.resize(names.size());
    while (!stop) {
      const double t = std::chrono::duration<double>(Clock::now() - start).count();
      for (std::size_t i = 0; i < names.size(); ++i) {
        msg.position[i] = 0.3 * std::sin(t + i);
        msg.velocity[i] = 0.3 * std::cos(t + i);
      }
      msg.header.stamp = ros::Time::now();
      joint_states.publish(msg);
      ++joint_states_sent;
      next += period;
      std::this_thread::sleep_until(next);
    }
  });

  std::mutex results_mutex;
  std::vector<double> latencies_ms;
  long failures = 0, served = 0;
  std::string first_failure;
  std::vector<std::thread> workers;
  for (int c = 0; c < clients; ++c) {
    workers.emplace_back([&, c] {
      ros::ServiceClient id = nh.serviceClient<spatial_dynamics::InverseDynamics>("/dynamics/inverse_dynamics", true);
      ros::ServiceClient fd = nh.serviceClient<spatial_dynamics::ForwardDynamics>("/dynamics/forward_dynamics", true);
      ros::ServiceClient mm = nh.serviceClient<spatial_dynamics::MassMatrix>("/dynamics/mass_matrix", true);
      sd::Data<double> data(model);
      std::mt19937 rng(1000 + c);
      std::uniform_real_distribution<double> u(-1, 1);
      std::vector<double> my_latencies;
      long my_failures = 0, my_served = 0;
      std::string my_first;
      for (long call = 0; Clock::now() < deadline && calls_started++ < max_calls; ++call) {
        Eigen::VectorXd q(model.nv), qd(model.nv), x(model.nv);
        for (int i = 0; i < model.nv; ++i) { q[i] = u(rng); qd[i] = u(rng); x[i] = u(rng); }
        bool ok = false;
        double error = 0;
        const Clock::time_point t0 = Clock::now();
        if (call % 3 == 0) {
          spatial_dynamics::InverseDynamics srv;
          srv.request.position = to_std(q);
          srv.request.velocity = to_std(qd);
          srv.request.acceleration = to_std(x);
          ok = id.call(srv) && srv.response.success;
          if (ok) error = (Eigen::Map<const Eigen::VectorXd>(srv.response.effort.data(), model.nv) - sd::rnea(model, data, q, qd, x)).norm() / std::max(1e-300, data.tau.norm());
        } else if (call % 3 == 1) {
          spatial_dynamics::ForwardDynamics srv;
          srv.request.position = to_std(q);
          srv.request.velocity = to_std(qd);
          srv.request.effort = to_std(x);
          ok = fd.call(srv) && srv.response.success;
          if (ok) error = (Eigen::Map<const Eigen::VectorXd>(srv.response.acceleration.data(), model.nv) - sd::aba(model, data, q, qd, x)).norm() / std::max(1e-300, data.qdd.norm());
        } else {
          spatial_dynamics::MassMatrix srv;
          srv.request.position = to_std(q);
          ok = mm.call(srv) && srv.response.success;
          if (ok) {
            const Eigen::MatrixXd& M = sd::crba(model, data, q);
            error = (Eigen::Map<const Eigen::Matrix<double, -1, -1, Eigen::RowMajor>>(srv.response.mass_matrix.data(), model.nv, model.nv) - M).norm() / M.norm();
          }
        }
        my_latencies.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
        if (ok && error <= 1e-12) {
          ++my_served;
        } else {
          ++my_failures;
          if (my_first.empty()) my_first = ok ? "wrong answer, relative error " + std::to_string(error) : "call failed";
        }
      }
      std::lock_guard<std::mutex> lock(results_mutex);
      latencies_ms.insert(latencies_ms.end(), my_latencies.begin(), my_latencies.end());
      failures += my_failures;
      served += my_served;
      if (first_failure.empty()) first_failure = my_first;
    });
  }
  while (Clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::seconds(5));
    samples.push_back(sample_process(node_pid, start));
  }
  for (auto& w : workers) w.join();
  stop = true;
  streamer.join();
  for (int k = 0; k < 100 && torques_received < joint_states_sent; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  samples.push_back(sample_process(node_pid, start));
  const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();

  std::sort(latencies_ms.begin(), latencies_ms.end());
  const ProcessSample& first = samples.front();
  const ProcessSample& last = samples.back();
  const ProcessSample& early = samples.size() > 2 ? samples[1] : first;  // after warm-up
  std::ostringstream report;
  report.precision(4);
  report << "| figure | value |\n|---|---|\n"
         << "| duration | " << elapsed << " s |\n"
         << "| service clients | " << clients << " (inverse dynamics, forward dynamics, mass matrix in turn) |\n"
         << "| calls served correctly | " << served << " (" << served / elapsed << " /s) |\n"
         << "| failures (error answers, lost calls, wrong numbers) | " << failures << " |\n"
         << "| latency p50 / p99 / max | " << percentile(latencies_ms, 0.5) << " / " << percentile(latencies_ms, 0.99)
         << " / " << (latencies_ms.empty() ? 0 : latencies_ms.back()) << " ms |\n"
         << "| joint_states published / computed_torques received | " << joint_states_sent << " / "
         << torques_received.load() << " |\n"
         << "| node CPU | " << 100.0 * (last.cpu_seconds - first.cpu_seconds) / (last.seconds - first.seconds)
         << " % of one core |\n"
         << "| node memory (RSS) at start / after 5 s / end / peak | " << first.rss_kib << " / " << early.rss_kib << " / "
         << last.rss_kib << " / " << last.peak_kib << " KiB |\n";
  std::printf("%s", report.str().c_str());
  std::printf("RSS samples (s: KiB):");
  for (const auto& s : samples) std::printf(" %.0f:%ld", s.seconds, s.rss_kib);
  std::printf("\n");
  if (!first_failure.empty()) std::printf("first failure: %s\n", first_failure.c_str());
  if (!out_file.empty()) std::ofstream(out_file) << report.str();
  const bool memory_grew = last.rss_kib > early.rss_kib + 2048;  // more than 2 MiB after warm-up
  if (memory_grew) std::printf("memory grew after warm-up\n");
  const bool pass = failures == 0 && torques_received == joint_states_sent && !memory_grew;
  std::printf("%s\n", pass ? "load test passed" : "load test FAILED");
  ros::shutdown();
  return pass ? 0 : 1;
}
