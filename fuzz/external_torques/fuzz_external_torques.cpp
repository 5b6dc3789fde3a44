// libFuzzer target: the node's external-torque estimate (ros/external_torque_estimator.hpp, on the
// library's MomentumObserver, coriolis.hpp and external_wrench.hpp), without a master. The input
// decodes into ~external_torques settings — gains and thresholds (one number or per joint, known or
// unknown joints), frames (known or not), max_gap, with NaN, ±Inf, 0, negative, huge and tiny
// values — for the whole Panda or its arm as a reduced scene, then into a stream of samples: stamps
// that advance, repeat, go back, jump or are not finite; positions, velocities and efforts of any
// value; and tares in between. The estimator must either refuse the settings with a message or
// answer every sample with finite torques and wrenches or an error with a message; anything else
// (a crash, a non-finite answer, an empty error) is a finding.
#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <limits>
#include <memory>

#include "../fuzz_common.hpp"
#include "spatial_dynamics/reduction/reduce_model.hpp"
#include "spatial_dynamics/ros/external_torque_estimator.hpp"
#include "spatial_dynamics/urdf/model_builder.hpp"

namespace sd = spatial_dynamics;

namespace {

struct Fixture {
  std::shared_ptr<const sd::Model<double>> models[2];
  std::vector<std::string> leaves = {"panda_leftfinger", "panda_rightfinger", "panda_hand_tcp", "not_a_link"};
};

const Fixture& fixture() {
  static const Fixture f = [] {
    Fixture fx;
    const sd::Model<double> full = sd::build_model_from_urdf_file(std::string(sd_test::robots_dir()) + "/panda.urdf");
    sd::Scene arm;  // the arm's seven joints; the fingers locked, a payload on the hand
    for (int k = 1; k <= 7; ++k) arm.kept_joints.push_back("panda_joint" + std::to_string(k));
    arm.locked_positions["panda_finger_joint1"] = 0.02;
    fx.models[0] = std::make_shared<const sd::Model<double>>(full);
    fx.models[1] = std::make_shared<const sd::Model<double>>(sd::reduce_model(full, arm));
    return fx;
  }();
  return f;
}

double value(FuzzedDataProvider& in) {
  static const double special[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                                   -std::numeric_limits<double>::infinity(), 0.0, -1.0, 1e308, -1e308, 1e-308, 50.0};
  if (in.ConsumeBool()) return special[in.ConsumeIntegralInRange<int>(0, 8)];
  return in.ConsumeFloatingPoint<double>();
}

std::string name(FuzzedDataProvider& in, const std::vector<std::string>& known) {
  if (in.ConsumeBool() || known.empty()) return in.ConsumeRandomLengthString(16);
  return known[in.ConsumeIntegralInRange<std::size_t>(0, known.size() - 1)];
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  fixture();  // the robot loaded before the first input's time-out starts
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  const std::shared_ptr<const sd::Model<double>>& model = fixture().models[in.ConsumeIntegralInRange<int>(0, 1)];
  const std::vector<std::string> joints = model->velocityNames();
  std::vector<std::string> frames;
  for (const auto& f : model->frames) frames.push_back(f.name);
  sd::ExternalTorqueSettings settings;
  settings.gain = value(in);
  for (int k = in.ConsumeIntegralInRange<int>(0, 3); k > 0; --k) settings.joint_gains[name(in, joints)] = value(in);
  settings.detect_collisions = in.ConsumeBool();
  settings.threshold = value(in);
  for (int k = in.ConsumeIntegralInRange<int>(0, 3); k > 0; --k) settings.joint_thresholds[name(in, joints)] = value(in);
  settings.frames_given = in.ConsumeBool();
  for (int k = in.ConsumeIntegralInRange<int>(0, 3); k > 0; --k) settings.frames.push_back(name(in, frames));
  settings.max_gap = in.ConsumeBool() ? 0.1 : value(in);
  std::unique_ptr<sd::ExternalTorqueEstimator> estimator;
  if (!sd_fuzz::result_or_error("building the estimator", [&] {
        estimator = std::make_unique<sd::ExternalTorqueEstimator>(model, settings, fixture().leaves,
                                                                  std::vector<std::string>{});
      }))
    return 0;
  const int n = model->nv;
  Eigen::VectorXd q(n), qd(n), effort(n);
  double stamp = 0.0;
  while (in.remaining_bytes() > 0) {
    switch (in.ConsumeIntegralInRange<int>(0, 3)) {
      case 0: stamp += 1e-3; break;
      case 1: stamp = value(in); break;
      case 2: estimator->tare(); continue;
      default: break;  // the same stamp again
    }
    const bool smooth = in.ConsumeBool();  // ordinary values, so that the observer runs for a while
    for (int k = 0; k < n; ++k) {
      q[k] = smooth ? 0.1 * in.ConsumeIntegralInRange<int>(-10, 10) : value(in);
      qd[k] = smooth ? 0.1 * in.ConsumeIntegralInRange<int>(-10, 10) : value(in);
      effort[k] = smooth ? in.ConsumeIntegralInRange<int>(-50, 50) : value(in);
    }
    sd_fuzz::result_or_error("a sample", [&] {
      const sd::ExternalTorqueEstimator::Estimate& e = estimator->update(stamp, q, qd, effort);
      sd_fuzz::require_finite(*e.torques, "the external torques");
      for (const auto& w : e.wrenches) sd_fuzz::require_finite(w.wrench.toVector(), "an external wrench");
      for (int k : e.over_threshold)
        if (!(std::abs((*e.torques)[k]) > 0)) sd_fuzz::finding("a joint over its threshold with |r̂| = 0");
    });
  }
  return 0;
}
