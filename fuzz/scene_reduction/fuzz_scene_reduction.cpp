// libFuzzer target: scene and reduction options → with_payloads → reduce_model (joint lists or
// scene_from_root_and_tips) → couple_mimic_joints → the algorithms.
// The input bytes (read by sd_fuzz::Reader, front to back) pick a robot — one of the shared set,
// the synthetic mobile manipulator of the tests, or a small robot generated from the bytes —,
// a fixed or floating base, payloads on frames (sometimes unknown ones; masses, centres and
// tensors including NaN, ±Inf and huge values), the joints to keep or a root link and tip links
// (sometimes unknown names), locked positions (NaN, ±Inf, huge), and whether mimic joints are
// coupled. Every step either succeeds with a model that satisfies the Model invariants or throws
// a std::exception with a message; every algorithm then returns finite numbers or throws with a
// message. Where all numbers are of moderate size, the reduced model's torques must also equal
// the full model's with the locked joints held still.
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "../fuzz_common.hpp"
#include "spatial_dynamics/reduction/couple_mimic_joints.hpp"
#include "spatial_dynamics/reduction/payload.hpp"
#include "spatial_dynamics/reduction/reduce_model.hpp"
#include "spatial_dynamics/urdf/model_builder.hpp"
#include "synthetic_robots.hpp"

namespace {

namespace sd = spatial_dynamics;

struct Robot {
  sd::Model<double> fixed, floating;
};

const std::vector<Robot>& robots() {
  static const std::vector<Robot> all = [] {
    std::vector<Robot> list;
    sd::ModelBuildOptions floating;
    floating.floating_base = true;
    for (const char* file : {"double_pendulum.urdf", "panda.urdf", "ur5.urdf", "solo12.urdf", "talos.urdf"}) {
      const std::string path = std::string(sd_test::robots_dir()) + "/" + file;
      list.push_back({sd::build_model_from_urdf_file(path), sd::build_model_from_urdf_file(path, floating)});
    }
    const std::string mobile = sd_test::mobile_manipulator_urdf();
    list.push_back({sd::build_model_from_urdf_string(mobile), sd::build_model_from_urdf_string(mobile, floating)});
    return list;
  }();
  return all;
}

/// A small robot from the bytes: up to 7 links on a tree, each joint revolute, continuous,
/// prismatic or fixed about a few axes, masses from massless to heavy, some mimic joints.
std::string generated_urdf(sd_fuzz::Reader& in) {
  static const char* types[] = {"revolute", "continuous", "prismatic", "fixed"};
  static const char* axes[] = {"1 0 0", "0 1 0", "0 0 1", "0 -1 0", "0.6 0 0.8", "1 1 1"};
  static const char* masses[] = {"0", "0.1", "1", "10"};
  const int n = 1 + in.byte() % 7;
  std::string xml = "<robot name='generated'><link name='l0'><inertial><mass value='1'/>"
                    "<inertia ixx='0.1' ixy='0' ixz='0' iyy='0.1' iyz='0' izz='0.1'/></inertial></link>";
  std::vector<int> movable;
  for (int i = 1; i < n; ++i) {
    const std::string link = "l" + std::to_string(i), joint = "j" + std::to_string(i);
    const char* mass = masses[in.byte() % 4];
    xml += "<link name='" + link + "'>";
    if (mass[0] != '0')
      xml += std::string("<inertial><origin xyz='0.1 0 0.05'/><mass value='") + mass +
             "'/><inertia ixx='0.01' ixy='0' ixz='0' iyy='0.02' iyz='0' izz='0.02'/></inertial>";
    xml += "</link>";
    const char* type = types[in.byte() % 4];
    const int parent = in.byte() % i;
    const char* axis = axes[in.byte() % 6];
    xml += "<joint name='" + joint + "' type='" + type + "'><parent link='l" + std::to_string(parent) +
           "'/><child link='" + link + "'/><origin xyz='0 0.1 0.2' rpy='0.1 0.2 0.3'/><axis xyz='" + axis +
           "'/><limit lower='-2' upper='2' effort='10' velocity='1'/>";
    if (std::string(type) != "fixed") {
      if (!movable.empty() && in.byte() % 3 == 0) {
        const int master = movable[in.byte() % movable.size()];
        const int multiplier = in.byte() % 5 - 2;
        xml += "<mimic joint='j" + std::to_string(master) + "' multiplier='" + std::to_string(multiplier) +
               "' offset='0.25'/>";
      }
      movable.push_back(i);
    }
    xml += "</joint>";
  }
  return xml + "</robot>";
}

std::vector<std::string> joint_names(const sd::Model<double>& m) {
  return std::vector<std::string>(m.joint_names.begin() + 1, m.joint_names.end());
}

std::vector<std::string> frame_names(const sd::Model<double>& m) {
  std::vector<std::string> names;
  for (const auto& f : m.frames) names.push_back(f.name);
  return names;
}

bool moderate(double x) { return std::isfinite(x) && std::abs(x) <= 1e6; }

/// The reduced model's gravity and velocity torques equal the full model's at the locked positions.
void check_reduction(const sd::Model<double>& full, const sd::Model<double>& reduced, const sd::Scene& scene,
                     std::mt19937_64& rng) {
  const sd_fuzz::State s = sd_fuzz::random_state(reduced, rng);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(full.nq), qd = Eigen::VectorXd::Zero(full.nv), qdd = qd;
  for (int i = 1; i < full.nbodies(); ++i) {
    const sd::Joint<double>& j = full.joints[i];
    if (reduced.hasJoint(full.joint_names[i])) {
      const sd::Joint<double>& r = reduced.joints[reduced.jointBody(full.joint_names[i])];
      q.segment(j.idx_q, j.nq) = s.q.segment(r.idx_q, r.nq);
      qd.segment(j.idx_v, j.nv) = s.qd.segment(r.idx_v, r.nv);
      qdd.segment(j.idx_v, j.nv) = s.qdd.segment(r.idx_v, r.nv);
    } else {
      const auto it = scene.locked_positions.find(full.joint_names[i]);
      q[j.idx_q] = it == scene.locked_positions.end() ? 0.0 : it->second;
    }
  }
  sd::Data<double> data_full(full), data_reduced(reduced);
  Eigen::VectorXd tau_full, tau_reduced;
  try {
    tau_full = sd::rnea(full, data_full, q, qd, qdd);
    tau_reduced = sd::rnea(reduced, data_reduced, s.q, s.qd, s.qdd);
  } catch (const std::exception&) {
    return;  // run_algorithms judges the errors
  }
  double scale = 1.0, worst = 0.0;
  for (int i = 1; i < reduced.nbodies(); ++i) {
    const sd::Joint<double>& r = reduced.joints[i];
    const sd::Joint<double>& j = full.joints[full.jointBody(reduced.joint_names[i])];
    for (int k = 0; k < r.nv; ++k) {
      scale = std::max(scale, std::abs(tau_full[j.idx_v + k]));
      worst = std::max(worst, std::abs(tau_full[j.idx_v + k] - tau_reduced[r.idx_v + k]));
    }
  }
  if (!(worst <= 1e-8 * scale))
    sd_fuzz::finding("reduced model's torques differ from the full model's by " + std::to_string(worst) +
                     " (scale " + std::to_string(scale) + ")");
}

}  // namespace

// The robots are loaded once, before the first input, so that their set-up never counts against an
// input's time limit.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  robots();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sd_fuzz::Reader in(data, size);
  const std::vector<Robot>& set = robots();
  const std::size_t pick = in.byte() % (set.size() + 1);
  const bool floating = in.flag();
  sd::Model<double> full;
  if (pick < set.size()) {
    full = floating ? set[pick].floating : set[pick].fixed;
  } else {
    sd::ModelBuildOptions options;
    options.floating_base = floating;
    try {
      full = sd::build_model_from_urdf_string(generated_urdf(in), options);
    } catch (const sd::ModelError&) {
      return 0;  // e.g. a mimic cycle; the URDF target fuzzes the builder
    }
  }
  bool all_moderate = true;
  auto number = [&] {
    const double x = in.number();
    all_moderate = all_moderate && moderate(x);
    return x;
  };

  // Payloads.
  std::map<std::string, sd::Payload> payloads;
  for (int k = in.byte() % 4; k > 0; --k) {
    sd::Payload p;
    p.mass = number();
    for (int k = 0; k < 3; ++k) p.center_of_mass[k] = number();
    if (in.flag()) {
      p.inertia.setZero();
      for (int k = 0; k < 3; ++k) p.inertia(k, k) = number();
    } else {
      const double xx = number(), xy = number(), xz = number(), yy = number(), yz = number(), zz = number();
      p.inertia << xx, xy, xz, xy, yy, yz, xz, yz, zz;
    }
    payloads[in.name(frame_names(full))] = p;
  }
  sd::Model<double> loaded;
  if (!sd_fuzz::result_or_error("with_payloads", [&] { loaded = sd::with_payloads(full, payloads); })) return 0;
  sd_fuzz::check_model(loaded, "model with payloads");

  // Scene.
  sd::Model<double> model = loaded;
  const int mode = in.byte() % 3;
  if (mode > 0) {
    const std::vector<std::string> joints = joint_names(loaded), frames = frame_names(loaded);
    sd::Scene scene;
    std::map<std::string, double> locked;
    for (int k = in.byte() % 8; k > 0; --k) {
      const std::string name = in.name(joints);
      locked[name] = number();
    }
    if (mode == 1) {
      for (int k = in.byte() % 8; k > 0; --k) scene.kept_joints.push_back(in.name(joints));
      scene.locked_positions = locked;
    } else {
      sd::RootTipScene spec{in.name(frames), {}, locked};
      for (int k = in.byte() % 4; k > 0; --k) spec.tip_links.push_back(in.name(frames));
      if (!sd_fuzz::result_or_error("scene_from_root_and_tips",
                                    [&] { scene = sd::scene_from_root_and_tips(loaded, spec); }))
        return 0;
    }
    if (!sd_fuzz::result_or_error("reduce_model", [&] { model = sd::reduce_model(loaded, scene); })) return 0;
    sd_fuzz::check_model(model, "reduced model");
    // Every kept joint (and a free root) stays, every other one is gone; every frame stays.
    std::set<std::string> kept(scene.kept_joints.begin(), scene.kept_joints.end());
    for (int i = 1; i < loaded.nbodies(); ++i) {
      const bool stays = kept.count(loaded.joint_names[i]) || loaded.joints[i].type == sd::JointType::Free;
      if (stays != model.hasJoint(loaded.joint_names[i]))
        sd_fuzz::finding("joint '" + loaded.joint_names[i] + "' is " + (stays ? "lost" : "kept") + " by the reduction");
    }
    if (model.frames.size() != loaded.frames.size()) sd_fuzz::finding("the reduction lost frames");
    std::mt19937_64 rng(in.u16());
    if (all_moderate) check_reduction(loaded, model, scene, rng);
  }
  if (in.flag()) {
    sd::Model<double> coupled;
    if (!sd_fuzz::result_or_error("couple_mimic_joints", [&] { coupled = sd::couple_mimic_joints(model); })) return 0;
    sd_fuzz::check_model(coupled, "coupled model");
    model = std::move(coupled);
  }

  const std::uint64_t state_seed = in.u16();
  std::mt19937_64 rng(state_seed | std::uint64_t(in.u16()) << 16);
  sd::Data<double> data_ws(model);
  for (int k = 0; k < 2; ++k) sd_fuzz::run_algorithms(model, data_ws, sd_fuzz::random_state(model, rng), rng);
  return 0;
}
