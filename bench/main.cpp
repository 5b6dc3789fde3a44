// Speed against error: every algorithm of spatial_dynamics (float and double) and of the
// comparators found at build time (KDL, DART, MuJoCo) on the same models and the same random
// states, timed per call and checked against the float128 reference. Writes results.csv,
// results.md, and through plot.py and summary.py benchmark.png and summary.md, into --out DIR.
//
//   benchmark [--model PATH]... [--floating] [--quick] [--portable | --default-build] [--out DIR]
// Our rows come from a -march=native build of the adapter (native_adapter.hpp) when it is built,
// or with --portable from the package's default build: the compiled library's double instances with the
// build chosen at run time from the CPU (simd_backend.hpp), as the node and every downstream program run them.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <time.h>

#include "allocation_counter.hpp"
#include "benchmark_types.hpp"
#include "random_states.hpp"
#include "reference.hpp"
#include "spatial_dynamics_adapter.hpp"
#include "spatial_dynamics/estimation/excitation_trajectory.hpp"
#include "spatial_dynamics/estimation/payload_identification.hpp"
#include "spatial_dynamics/synthetic/random_robot.hpp"
#include "spatial_dynamics/reduction/reduce_model.hpp"
#include "spatial_dynamics/simd_backend.hpp"
#include "spatial_dynamics/urdf/model_builder.hpp"
#include "urdf_text.hpp"
#ifdef SD_BENCH_WITH_NATIVE
#include "native_adapter.hpp"
#endif
#ifdef SD_BENCH_WITH_KDL
#include "kdl_adapter.hpp"
#endif
#ifdef SD_BENCH_WITH_DART
#include "dart_adapter.hpp"
#endif
#ifdef SD_BENCH_WITH_MUJOCO
#include "mujoco_adapter.hpp"
#endif

namespace sd = spatial_dynamics;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

#ifndef SD_BENCH_BUILD_FLAGS
#define SD_BENCH_BUILD_FLAGS "unknown"
#endif
/// The compiler flags of this executable (every row is measured in it).
constexpr const char* kBuildFlags = SD_BENCH_BUILD_FLAGS;

namespace bench {
namespace {

struct Settings {
  std::vector<std::string> models;  // --model PATH (repeatable); empty: the default set
  bool floating = false;            // --floating: also run --model files with a free root
  bool quick = false;
  bool portable = false;            // --portable: our rows from the package's default build (simd_backend.hpp)
  bool default_build = false;       // --default-build: beside the -march=native rows, the default build's in double
  std::string out = "benchmark_results";
  // Derived from quick.
  int states = 1000;                // random states for the errors (and the timing pool)
  int repeats = 5;
  int calls = 10000;                // calls per repeat …
  double repeat_seconds = 1.0;      // … or as many as fit in this time when a call is slower
  double mass_matrix_seconds = 60;  // budget of the float128 mass matrices per model
  double error_seconds = 30;        // budget of one row's calls while measuring errors
  int min_mass_matrices = 3;
  long min_calls = 10;
};

struct ModelSpec {
  std::string name, base, path;  // base: "fixed" or "floating"
  /// Non-empty: the reduced scene of the file's robot that keeps these joints (the others locked
  /// at 0); only spatial_dynamics has scenes, so the comparators sit out.
  std::vector<std::string> kept_joints = {};
};

struct Row {
  std::string library, algorithm, method, model, base, scalar;
  int dof = 0;
  double ns_median = 0, ns_min = 0, ns_max = 0, max_err = 0, median_err = 0, allocs = 0;
  double paired_ratio = NAN;  // a row with actuator terms: its time over its rigid-body row's, paired blocks (time_paired)
  double paired_to_kdl = NAN;  // our aba (the default build's): its time over KDL's forward dynamics, paired blocks
  double max_err_first_100 = 0;  // over the first 100 states, as the peers' anchor figures were measured
  long calls = 0;
  int repeats = 0, error_states = 0;
  std::string failure;  // non-empty: the call failed (message), no figures
};

std::string format_g(double x, int digits = 2) {
  char b[32];
  std::snprintf(b, sizeof b, "%.*e", digits - 1, x);
  return b;
}

/// The default set: the shared robots (fixed; talos and solo12 also floating) and the synthetic
/// models, whose URDF is written into out/models.
std::vector<ModelSpec> default_models(const Settings& settings) {
  std::vector<ModelSpec> specs;
  const std::string robots = SD_ROBOTS_DIR;
  for (const char* r : {"double_pendulum", "panda", "ur5", "solo12", "talos"})
    specs.push_back({r, "fixed", robots + "/" + r + ".urdf"});
  for (const char* r : {"solo12", "talos"}) specs.push_back({r, "floating", robots + "/" + r + ".urdf"});
  std::vector<std::string> left_arm;
  for (int k = 1; k <= 7; ++k) left_arm.push_back("arm_left_" + std::to_string(k) + "_joint");
  specs.push_back({"talos_left_arm", "fixed", robots + "/talos.urdf", left_arm});  // against "talos" above
  const std::string dir = settings.out + "/models";
  fs::create_directories(dir);
  auto add = [&](const std::string& name, const std::vector<sd::synthetic::Link>& links) {
    const std::string path = dir + "/" + name + ".urdf";
    write_file(path, sd::synthetic::to_urdf(name, links));
    specs.push_back({name, "fixed", path});
  };
  for (int n : {10, 50, 200, 1000}) {
    std::mt19937 rng(n);
    add("chain_" + std::to_string(n), sd::synthetic::random_chain(n, rng));
  }
  {
    std::mt19937 rng(51);
    add("tree_50", sd::synthetic::random_tree(50, rng));
  }
  {
    std::mt19937 rng(201);
    sd::synthetic::RandomOptions options;
    options.mass_min = 1e-4;
    options.mass_max = 1e2;
    options.log_uniform_mass = true;  // box inertias scale with the mass
    add("mass_span_200", sd::synthetic::random_chain(200, rng, options));
  }
  return specs;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// One timed row: what it calls, how many calls a repeat takes, and the repeats' ns per call.
struct Timing {
  Adapter* adapter = nullptr;
  Algorithm algorithm = Algorithm::Rnea;
  Row* row = nullptr;
  long calls = 0;
  long allocations = 0;
  std::vector<double> ns;
};

/// Warm-up, and the number of calls per repeat (fewer than settings.calls when a call is slow).
void calibrate(Timing& t, int pool, const Settings& settings) {
  const auto warm_start = Clock::now();
  int warm = 0;
  do t.adapter->run(t.algorithm, warm++ % pool);
  while (warm < 100 && std::chrono::duration<double>(Clock::now() - warm_start).count() < 20 * settings.repeat_seconds);
  const double per_call = std::chrono::duration<double>(Clock::now() - warm_start).count() / warm;
  t.calls = std::max(settings.min_calls, std::min<long>(settings.calls, static_cast<long>(settings.repeat_seconds / per_call)));
}

/// CPU time of the calling thread, in ns: time while the thread is descheduled (a shared machine
/// running other work) is not counted, as wall-clock time would count it.
double thread_cpu_ns() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e9 * static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec);
}

/// One repeat: `calls` calls cycling through the state pool, timed in thread CPU time;
/// allocations counted.
void time_repeat(Timing& t, int pool) {
  for (long c = 0; c < std::min<long>(10, t.calls / 10); ++c) t.adapter->run(t.algorithm, static_cast<int>(c % pool));  // caches back
  const long before = allocation_count();
  const double start = thread_cpu_ns();
  for (long c = 0; c < t.calls; ++c) t.adapter->run(t.algorithm, static_cast<int>(c % pool));
  const double stop = thread_cpu_ns();
  t.allocations += allocation_count() - before;
  t.ns.push_back((stop - start) / t.calls);
}

/// Two rows' time ratio (second over first), robust to the machine's drift: 41 pairs of blocks of
/// the same number of calls (about 2 ms of the first row), the two rows back to back in alternating
/// order, and the median of the pairs' ratios. Each pair sees the machine in the same phase, so the
/// drift, which moves two rows' separate medians by ±20 % here, cancels. For an actuated row against
/// its rigid-body row, and for our ABA against KDL's forward dynamics.
double time_paired(Adapter& first_adapter, Algorithm first, Adapter& second_adapter, Algorithm second, double first_ns,
                   int pool) {
  const long calls = std::max(10L, static_cast<long>(2e6 / std::max(first_ns, 1.0)));
  auto block = [&](Adapter& adapter, Algorithm a) {
    for (long c = 0; c < std::min(10L, calls / 10); ++c) adapter.run(a, static_cast<int>(c % pool));
    const double start = thread_cpu_ns();
    for (long c = 0; c < calls; ++c) adapter.run(a, static_cast<int>(c % pool));
    return thread_cpu_ns() - start;
  };
  std::vector<double> ratios;
  for (int k = 0; k < 41; ++k) {
    double t_first, t_second;
    if (k % 2 == 0) {
      t_first = block(first_adapter, first);
      t_second = block(second_adapter, second);
    } else {
      t_second = block(second_adapter, second);
      t_first = block(first_adapter, first);
    }
    ratios.push_back(t_second / t_first);
  }
  return median(ratios);
}

/// KDL's forward dynamics for the speed targets: ChainFdSolver_RNE (the crba_cholesky row) on a
/// serial model, TreeIdSolver_RNE (its rnea row: KDL has no tree forward dynamics) on a tree.
Algorithm kdl_forward_dynamics(const Row& kdl_rnea) {
  return kdl_rnea.method == "ChainIdSolver_RNE" ? Algorithm::CrbaCholesky : Algorithm::Rnea;
}

/// Every row of a model timed together: warm-up, then `repeats` rounds, each timing one repeat of
/// every row in turn, so that a slow phase of a shared machine hits all libraries alike; per row
/// the median, min and max over the repeats.
void time_interleaved(std::vector<Timing>& timings, int pool, const Settings& settings) {
  for (Timing& t : timings) calibrate(t, pool, settings);
  for (int r = 0; r < settings.repeats; ++r)
    for (Timing& t : timings) time_repeat(t, pool);
  for (Timing& t : timings) {
    Row& row = *t.row;
    const double states = t.adapter->states_per_call(t.algorithm);  // a batched call: time per state
    row.ns_median = median(t.ns) / states;
    row.ns_min = *std::min_element(t.ns.begin(), t.ns.end()) / states;
    row.ns_max = *std::max_element(t.ns.begin(), t.ns.end()) / states;
    row.allocs = static_cast<double>(t.allocations) / (static_cast<double>(t.calls) * settings.repeats);
    row.calls = t.calls;
    row.repeats = settings.repeats;
  }
}

/// The package's default build (the compiled library, its build chosen at run time) under a
/// library name of its own, for rows beside the -march=native ones of the same run.
class DefaultBuildAdapter : public SpatialDynamicsAdapter<double> {
 public:
  using SpatialDynamicsAdapter<double>::SpatialDynamicsAdapter;
  std::string library() const override { return "spatial_dynamics_default_build"; }
};

/// Per model and algorithm, the default build's time over the -march=native build's, both from this run.
std::string default_build_ratios(const std::vector<Row>& rows) {
  std::ostringstream s;
  s << "| model | base | algorithm | -march=native (ns) | default build (ns) | ratio |\n|---|---|---|---|---|---|\n";
  char line[256];
  for (const Row& d : rows) {
    if (d.library != "spatial_dynamics_default_build" || !d.failure.empty()) continue;
    for (const Row& n : rows)
      if (n.library == "spatial_dynamics" && n.scalar == "double" && n.algorithm == d.algorithm && n.model == d.model &&
          n.base == d.base && n.failure.empty()) {
        std::snprintf(line, sizeof line, "| %s | %s | %s | %.0f | %.0f | %.3f |\n", d.model.c_str(), d.base.c_str(),
                      d.algorithm.c_str(), n.ns_median, d.ns_median, d.ns_median / n.ns_median);
        s << line;
      }
  }
  return s.str();
}

struct Loaded {
  std::unique_ptr<Adapter> adapter;
  std::string library, why;
};

std::vector<Loaded> load_adapters(const sd::Model<double>& model, const ModelSpec& spec, const Settings& settings) {
  std::vector<Loaded> out;
#ifdef SD_BENCH_WITH_NATIVE
  if (!settings.portable) {
    out.push_back({make_native_spatial_dynamics_adapter(model, false), "spatial_dynamics", ""});
    out.push_back({make_native_spatial_dynamics_adapter(model, true), "spatial_dynamics", ""});
  }
#endif
  if (!out.empty() && settings.default_build)
    out.push_back({std::make_unique<DefaultBuildAdapter>(model), "spatial_dynamics_default_build", ""});
  if (out.empty()) {
    out.push_back({std::make_unique<SpatialDynamicsAdapter<double>>(model), "spatial_dynamics", ""});
    out.push_back({std::make_unique<SpatialDynamicsAdapter<float>>(model), "spatial_dynamics", ""});
  }
  if (!spec.kept_joints.empty()) return out;  // a reduced scene: spatial_dynamics only
  // Comparators get the URDF without geometry (meshes they would try to open).
  [[maybe_unused]] const std::string text = without_geometry(read_file(spec.path));
  [[maybe_unused]] const std::string dir = settings.out + "/comparator_urdf";
  fs::create_directories(dir);
  [[maybe_unused]] std::string why;
#ifdef SD_BENCH_WITH_KDL
  why.clear();
  auto kdl = make_kdl_adapter(model, text, why);
  out.push_back({std::move(kdl), "kdl", why});
#endif
#ifdef SD_BENCH_WITH_DART
  why.clear();
  auto dart = make_dart_adapter(model, text, why);
  out.push_back({std::move(dart), "dart", why});
#endif
#ifdef SD_BENCH_WITH_MUJOCO
  why.clear();
  const std::string mj_text = model.floating_base ? with_floating_root(text, model.body_names[1], model.joint_names[1]) : text;
  const std::string mj_path = dir + "/" + spec.name + "_" + spec.base + ".urdf";
  write_file(mj_path, mj_text);
  auto mujoco = make_mujoco_adapter(model, mj_path, why);
  out.push_back({std::move(mujoco), "mujoco", why});
#endif
  return out;
}

void run_model(const ModelSpec& spec, const Settings& settings, std::vector<Row>& rows,
               std::vector<std::string>& load_failures) {
  sd::ModelBuildOptions options;
  options.floating_base = spec.base == "floating";
  const sd::Model<double> model =
      spec.kept_joints.empty()
          ? sd::build_model_from_urdf_file(spec.path, options)
          : sd::reduce_model(sd::build_model_from_urdf_file(spec.path, options), sd::Scene{spec.kept_joints, {}});
  const auto t0 = Clock::now();
  const std::vector<State> states = random_states(model, settings.states, 12345);
  std::vector<Loaded> adapters = load_adapters(model, spec, settings);
  for (Loaded& l : adapters) {
    if (!l.adapter) {
      load_failures.push_back(l.library + " | " + spec.name + " (" + spec.base + ") | " + l.why);
      continue;
    }
    l.adapter->prepare(states);
  }

  // Errors against the reference, state by state; the float128 mass matrix within a budget. The
  // rows with actuator terms on the shared robots (not their scenes).
  std::error_code ec;
  const bool shared_robot =
      spec.kept_joints.empty() && fs::equivalent(fs::path(spec.path).parent_path(), SD_ROBOTS_DIR, ec);
  Reference reference(model, shared_robot);
  struct Tally {
    std::vector<double> errors;
    std::string failure;
    double seconds = 0;  // spent in this row's calls; past settings.error_seconds it takes no more states
  };
  std::map<std::pair<Adapter*, Algorithm>, Tally> tallies;
  std::vector<double> result;  // one call's result (Adapter::result_into)
  int mass_matrix_states = settings.states;
  const auto ref_start = Clock::now();
  for (int s = 0; s < settings.states; ++s) {
    bool with_M = s < mass_matrix_states;
    try {
      reference.compute(states[s], with_M);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: reference failed: %s\n", spec.name.c_str(), e.what());
      return;
    }
    if (s == 0) {  // budget the O(n²) float128 mass matrices from the first one's cost
      const double seconds = std::chrono::duration<double>(Clock::now() - ref_start).count();
      mass_matrix_states = std::max(settings.min_mass_matrices,
                                    std::min(settings.states, static_cast<int>(settings.mass_matrix_seconds / seconds)));
    }
    for (Loaded& l : adapters) {
      if (!l.adapter) continue;
      for (Algorithm a : all_algorithms()) {
        if (!l.adapter->supports(a) || !reference.has(a)) continue;
        Tally& t = tallies[{l.adapter.get(), a}];
        if (!t.failure.empty() || (t.seconds > settings.error_seconds && !t.errors.empty())) continue;
        try {
          const auto call_start = Clock::now();
          l.adapter->run(a, s);
          t.seconds += std::chrono::duration<double>(Clock::now() - call_start).count();
          l.adapter->result_into(a, result);
          const Eigen::Map<const Eigen::VectorXd> x(result.data(), static_cast<Eigen::Index>(result.size()));
          t.errors.push_back(x.allFinite() ? sd::relative_error_to(x, reference.of(a)) : INFINITY);
        } catch (const std::exception& e) {
          t.failure = e.what();
        }
      }
    }
  }
  const double ref_seconds = std::chrono::duration<double>(Clock::now() - ref_start).count();

  std::vector<Row> model_rows;
  std::vector<std::pair<Adapter*, Algorithm>> timed;  // parallel to model_rows; nullptr: a failed row
  for (Loaded& l : adapters) {
    if (!l.adapter) continue;
    for (Algorithm a : all_algorithms()) {
      if (!l.adapter->supports(a) || (is_actuated(a) && !shared_robot)) continue;
      Row row;
      row.library = l.adapter->library();
      row.algorithm = name(a);
      row.method = l.adapter->method(a);
      row.model = spec.name;
      row.base = spec.base;
      row.scalar = l.adapter->scalar();
      row.dof = model.nv;
      const Tally& t = tallies[{l.adapter.get(), a}];
      if (!t.failure.empty()) {
        row.failure = t.failure;
        model_rows.push_back(row);
        timed.push_back({nullptr, a});
        continue;
      }
      row.error_states = static_cast<int>(t.errors.size());
      row.max_err = *std::max_element(t.errors.begin(), t.errors.end());
      row.max_err_first_100 = *std::max_element(t.errors.begin(), t.errors.begin() + std::min<std::size_t>(100, t.errors.size()));
      row.median_err = median(t.errors);
      model_rows.push_back(row);
      timed.push_back({l.adapter.get(), a});
    }
  }
  std::vector<Timing> timings;
  for (std::size_t k = 0; k < model_rows.size(); ++k)
    if (timed[k].first) timings.push_back({timed[k].first, timed[k].second, &model_rows[k]});
  time_interleaved(timings, settings.states, settings);
  for (std::size_t k = 0; k < model_rows.size(); ++k) {  // the actuated rows against their rigid rows, paired
    Row& row = model_rows[k];
    if (!timed[k].first || !is_actuated(timed[k].second)) continue;
    const Algorithm rigid = timed[k].second == Algorithm::RneaActuated ? Algorithm::Rnea : Algorithm::Aba;
    for (const Row& r : model_rows)
      if (r.library == row.library && r.scalar == row.scalar && r.algorithm == name(rigid) && r.failure.empty())
        row.paired_ratio =
            time_paired(*timed[k].first, rigid, *timed[k].first, timed[k].second, r.ns_median, settings.states);
  }
  // Our aba against KDL's forward dynamics, paired (forward_dynamics_targets), where a call of KDL's
  // takes under 1 ms (the pairs' time; the larger chains are orders of magnitude inside the targets).
  const std::string ours = settings.default_build ? "spatial_dynamics_default_build" : "spatial_dynamics";
  if (spec.base == "fixed" && spec.kept_joints.empty() && (settings.default_build || settings.portable)) {
    Row* aba = nullptr;
    const Row* kdl_rnea = nullptr;
    Adapter *our_adapter = nullptr, *kdl_adapter = nullptr;
    for (std::size_t k = 0; k < model_rows.size(); ++k) {
      if (!timed[k].first) continue;
      const Row& r = model_rows[k];
      if (r.library == ours && r.scalar == "double" && r.algorithm == "aba") aba = &model_rows[k], our_adapter = timed[k].first;
      if (r.library == "kdl" && r.algorithm == "rnea") kdl_rnea = &r, kdl_adapter = timed[k].first;
    }
    if (aba && kdl_rnea) {
      const Algorithm kdl_fd = kdl_forward_dynamics(*kdl_rnea);
      for (const Row& r : model_rows)
        if (r.library == "kdl" && r.algorithm == name(kdl_fd) && r.failure.empty() && r.ns_median < 1e6)
          aba->paired_to_kdl = time_paired(*kdl_adapter, kdl_fd, *our_adapter, Algorithm::Aba, r.ns_median, settings.states);
    }
  }
  rows.insert(rows.end(), model_rows.begin(), model_rows.end());
  std::printf("%-16s %-8s nv %4d: reference %.1f s (%d mass matrices), total %.1f s\n", spec.name.c_str(), spec.base.c_str(),
              model.nv, ref_seconds, mass_matrix_states, std::chrono::duration<double>(Clock::now() - t0).count());
  std::fflush(stdout);
}

void write_csv(const std::string& path, const std::vector<Row>& rows) {
  std::ostringstream s;
  s << "library,algorithm,model,base,dof,scalar,ns_median,ns_min,ns_max,max_rel_err,median_rel_err,allocs_per_call\n";
  char line[512];
  for (const Row& r : rows) {
    if (!r.failure.empty()) {
      std::snprintf(line, sizeof line, "%s,%s,%s,%s,%d,%s,nan,nan,nan,nan,nan,nan\n", r.library.c_str(), r.algorithm.c_str(),
                    r.model.c_str(), r.base.c_str(), r.dof, r.scalar.c_str());
    } else {
      std::snprintf(line, sizeof line, "%s,%s,%s,%s,%d,%s,%.1f,%.1f,%.1f,%.3e,%.3e,%g\n", r.library.c_str(), r.algorithm.c_str(),
                    r.model.c_str(), r.base.c_str(), r.dof, r.scalar.c_str(), r.ns_median, r.ns_min, r.ns_max, r.max_err,
                    r.median_err, r.allocs);
    }
    s << line;
  }
  write_file(path, s.str());
}

/// The best peer's forward-dynamics error (RBDL or Pinocchio against float128, max over 100 states), by model.
const std::map<std::string, double>& anchor_fd() {
  static const std::map<std::string, double> anchors = {{"panda", 3.9e-14},      {"ur5", 1.8e-14},
                                                         {"talos", 9.2e-14},
                                                         {"chain_200", 5.6e-10}, {"chain_1000", 6.8e-08},
                                                         {"mass_span_200", 3.3e-07}};
  return anchors;
}

const Row* find(const std::vector<Row>& rows, const std::string& lib, const std::string& alg, const std::string& model,
                const std::string& base, const std::string& scalar = "double") {
  for (const Row& r : rows)
    if (r.library == lib && r.algorithm == alg && r.model == model && r.base == base && r.scalar == scalar && r.failure.empty())
      return &r;
  return nullptr;
}

/// The comparators' smallest forward-dynamics error on a model (not our default build's rows).
double best_peer_fd(const std::vector<Row>& rows, const std::string& model, const std::string& base) {
  double best = INFINITY;
  for (const Row& r : rows)
    if (r.library.rfind("spatial_dynamics", 0) != 0 && r.model == model && r.base == base && r.failure.empty() &&
        (r.algorithm == "aba" || r.algorithm == "crba_cholesky"))
      best = std::min(best, r.max_err);
  return best;
}

/// The bound a rigid-body row's error is held to: RNEA 4e-15; ABA its anchor, else the best
/// comparator's forward dynamics on the model.
double rigid_row_bound(const Row& r, const std::vector<Row>& rows) {
  if (r.algorithm == "rnea") return 4e-15;
  const auto anchor = anchor_fd().find(r.base == "fixed" ? r.model : "");
  return anchor != anchor_fd().end() ? anchor->second : best_peer_fd(rows, r.model, r.base);
}

/// The rows with actuator terms against their rigid-body rows of the same run: time ratio (≤ 1.10)
/// and error against the float128 reference within the rigid row's bound.
std::string actuated_rows(const std::vector<Row>& rows) {
  std::ostringstream s;
  s << "| model | base | library | row | ns | rigid-body row (ns) | ratio of medians | paired ratio | ≤ 1.10 | max error | "
       "bound | within |\n"
       "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  char line[512];
  for (const Row& a : rows) {
    if ((a.algorithm != "rnea_actuated" && a.algorithm != "aba_actuated") || a.scalar != "double" || !a.failure.empty())
      continue;
    const std::string rigid = a.algorithm == "rnea_actuated" ? "rnea" : "aba";
    for (const Row& r : rows) {
      if (r.library != a.library || r.algorithm != rigid || r.model != a.model || r.base != a.base ||
          r.scalar != a.scalar || !r.failure.empty())
        continue;
      const double ratio = a.ns_median / r.ns_median, bound = rigid_row_bound(r, rows);
      std::snprintf(line, sizeof line, "| %s | %s | %s | %s | %.0f | %.0f | %.3f | %.3f | %s | %.2e | %.1e | %s |\n",
                    a.model.c_str(), a.base.c_str(), a.library.c_str(), a.algorithm.c_str(), a.ns_median, r.ns_median,
                    ratio, a.paired_ratio, a.paired_ratio <= 1.10 ? "yes" : "**no**", a.max_err, bound,
                    a.max_err <= bound ? "yes" : "**no**");
      s << line;
    }
  }
  return s.str();
}

std::string acceptance(const std::vector<Row>& rows, const std::vector<ModelSpec>& specs) {
  std::ostringstream s;
  s << "| model | base | RNEA | CRBA | ≤ 4e-15 | ABA | ABA, first 100 states | best anchor FD (100 states) | "
       "best comparator FD (this run) | ABA ok | refined FD | time refined / ABA | refined ok |\n"
       "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const ModelSpec& m : specs) {
    const Row* rnea = find(rows, "spatial_dynamics", "rnea", m.name, m.base);
    const Row* crba = find(rows, "spatial_dynamics", "crba", m.name, m.base);
    const Row* aba = find(rows, "spatial_dynamics", "aba", m.name, m.base);
    const Row* ref = find(rows, "spatial_dynamics", "aba_refined", m.name, m.base);
    if (!rnea || !crba || !aba || !ref) continue;
    const double best_peer = best_peer_fd(rows, m.name, m.base);
    std::error_code ec;
    const bool robot = fs::equivalent(fs::path(m.path).parent_path(), SD_ROBOTS_DIR, ec);  // a shared robot
    const auto anchor = anchor_fd().find(m.base == "fixed" ? m.name : "");
    const double target = anchor != anchor_fd().end() ? anchor->second : best_peer;
    const bool id_ok = rnea->max_err <= 4e-15 && crba->max_err <= 4e-15;
    const double ratio = ref->ns_median / aba->ns_median;
    const bool aba_ok = aba->max_err <= target;
    // Robots: refined ≤ 1e-15 at ≤ 4× ABA's time; hard chains: ≥ 1000× better than the anchor.
    const bool hard = anchor != anchor_fd().end() && !robot;
    const bool refined_ok = hard ? ref->max_err * 1000 <= target : (ref->max_err <= 1e-15 && ratio <= 4.0);
    s << "| " << m.name << " | " << m.base << " | " << format_g(rnea->max_err) << " | " << format_g(crba->max_err) << " | "
      << (robot ? (id_ok ? "yes" : "**no**") : "—") << " | " << format_g(aba->max_err) << " | "
      << format_g(aba->max_err_first_100) << " | "
      << (anchor != anchor_fd().end() ? format_g(anchor->second) : "—") << " | "
      << (std::isfinite(best_peer) ? format_g(best_peer) : "—") << " | " << (aba_ok ? "yes" : "**no**") << " | "
      << format_g(ref->max_err) << " | " << format_g(ratio, 3) << " | "
      << (robot || hard ? (refined_ok ? "yes" : "**no**") : "—") << " |\n";
  }
  return s.str();
}

/// Speed ratios and their targets. Serial models (KDL took the chain solvers): our time over KDL's,
/// RNEA ≤ 0.30 × ChainIdSolver_RNE, ABA ≤ 0.33 × ChainFdSolver_RNE, CRBA ≤ 0.20 × JntToMass. Trees:
/// RNEA ≤ 0.10 × TreeIdSolver_RNE; ABA and CRBA (no KDL solver) ≤ 0.8 × the best peer figure of
/// the peers' table (RBDL, Pinocchio), rescaled by KDL's tree RNEA time in this run over the one measured beside it.
struct PeerFigures {
  double kdl_tree_rnea_ns, fd_ns, crba_ns;
};
const std::map<std::string, PeerFigures>& peer_figures() {
  static const std::map<std::string, PeerFigures> peers = {{"panda", {5240, 2080, 752}}, {"talos", {34500, 10600, 4790}}};
  return peers;
}

std::string speed_targets(const std::vector<Row>& rows, const std::vector<ModelSpec>& specs) {
  std::ostringstream s;
  char line[512];
  s << "| model | algorithm | ours (ns) | compared with | its ns | ratio | target | met |\n"
       "|---|---|---|---|---|---|---|---|\n";
  auto emit = [&](const ModelSpec& m, const char* alg, const Row* ours, const std::string& what, double ns, double target) {
    const double ratio = ours->ns_median / ns;
    std::snprintf(line, sizeof line, "| %s | %s | %.0f | %s | %.0f | %.3f | %.2f | %s |\n", m.name.c_str(), alg, ours->ns_median,
                  what.c_str(), ns, ratio, target, ratio <= target ? "yes" : "**no**");
    s << line;
  };
  for (const ModelSpec& m : specs) {
    if (m.base != "fixed" || !m.kept_joints.empty()) continue;
    const Row* kdl_rnea = find(rows, "kdl", "rnea", m.name, m.base);
    if (!kdl_rnea) continue;
    const bool serial = kdl_rnea->method == "ChainIdSolver_RNE";
    const Row* rnea = find(rows, "spatial_dynamics", "rnea", m.name, m.base);
    const Row* aba = find(rows, "spatial_dynamics", "aba", m.name, m.base);
    const Row* crba = find(rows, "spatial_dynamics", "crba", m.name, m.base);
    if (rnea) emit(m, "rnea", rnea, "kdl " + kdl_rnea->method, kdl_rnea->ns_median, serial ? 0.30 : 0.10);
    if (serial) {
      const Row* kdl_fd = find(rows, "kdl", "crba_cholesky", m.name, m.base);
      const Row* kdl_m = find(rows, "kdl", "crba", m.name, m.base);
      if (aba && kdl_fd) emit(m, "aba", aba, "kdl ChainFdSolver_RNE", kdl_fd->ns_median, 0.33);
      if (crba && kdl_m) emit(m, "crba", crba, "kdl " + kdl_m->method, kdl_m->ns_median, 0.20);
      continue;
    }
    const auto peer = peer_figures().find(m.name);
    if (peer == peer_figures().end()) continue;
    const double scale = kdl_rnea->ns_median / peer->second.kdl_tree_rnea_ns;
    char what[128];
    std::snprintf(what, sizeof what, "best peer FD %.0f ns × %.2f (KDL tree RNEA %.0f / %.0f)", peer->second.fd_ns, scale,
                  kdl_rnea->ns_median, peer->second.kdl_tree_rnea_ns);
    if (aba) emit(m, "aba", aba, what, peer->second.fd_ns * scale, 0.8);
    std::snprintf(what, sizeof what, "best peer CRBA %.0f ns × %.2f (KDL tree RNEA %.0f / %.0f)", peer->second.crba_ns, scale,
                  kdl_rnea->ns_median, peer->second.kdl_tree_rnea_ns);
    if (crba) emit(m, "crba", crba, what, peer->second.crba_ns * scale, 0.8);
  }
  // Linear cost: ns per body of the random chains, RNEA and ABA, within 1.5× from 10 to 1000 bodies.
  s << "\n| algorithm |";
  std::vector<const ModelSpec*> chains;
  for (const ModelSpec& m : specs)
    if (m.base == "fixed" && m.name.rfind("chain_", 0) == 0) chains.push_back(&m), s << " " << m.name << " (ns/body) |";
  s << " max/min | target | met |\n|---|";
  for (std::size_t k = 0; k < chains.size(); ++k) s << "---|";
  s << "---|---|---|\n";
  for (const char* alg : {"rnea", "aba"}) {
    double lo = INFINITY, hi = 0;
    s << "| " << alg << " |";
    for (const ModelSpec* m : chains) {
      const Row* r = find(rows, "spatial_dynamics", alg, m->name, m->base);
      if (!r) {
        s << " — |";
        continue;
      }
      const double per_body = r->ns_median / r->dof;
      lo = std::min(lo, per_body), hi = std::max(hi, per_body);
      std::snprintf(line, sizeof line, " %.1f |", per_body);
      s << line;
    }
    std::snprintf(line, sizeof line, " %.2f | 1.50 | %s |\n", hi / lo, hi / lo <= 1.5 ? "yes" : "**no**");
    s << line;
  }
  return s.str();
}

/// The momentum observer's rows against our own (issue targets): coriolis_matrix ≤ 2 × crba, one
/// observer update ≤ rnea + crba, ratios of the rows' medians in this run, with their errors.
std::string observer_targets(const std::vector<Row>& rows, const std::vector<ModelSpec>& specs) {
  std::ostringstream s;
  char line[512];
  s << "| model | base | build | coriolis_matrix (ns) | crba (ns) | ratio | target | met | C error (max) | observer update (ns) "
       "| rnea + crba (ns) | ratio | target | met | update error (max) |\n"
       "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const ModelSpec& m : specs) {
    if (!m.kept_joints.empty()) continue;
    for (const char* library : {"spatial_dynamics", "spatial_dynamics_default_build"}) {
      const Row* coriolis = find(rows, library, "coriolis_matrix", m.name, m.base);
      const Row* update = find(rows, library, "observer_update", m.name, m.base);
      const Row* crba = find(rows, library, "crba", m.name, m.base);
      const Row* rnea = find(rows, library, "rnea", m.name, m.base);
      if (!coriolis || !update || !crba || !rnea) continue;
      const double c_ratio = coriolis->ns_median / crba->ns_median;
      const double u_ratio = update->ns_median / (rnea->ns_median + crba->ns_median);
      std::snprintf(line, sizeof line,
                    "| %s | %s | %s | %.0f | %.0f | %.2f | 2.00 | %s | %.2g | %.0f | %.0f | %.2f | 1.00 | %s | %.2g |\n",
                    m.name.c_str(), m.base.c_str(), std::string(library) == "spatial_dynamics" ? "native" : "default",
                    coriolis->ns_median, crba->ns_median, c_ratio, c_ratio <= 2.0 ? "yes" : "**no**", coriolis->max_err,
                    update->ns_median, rnea->ns_median + crba->ns_median, u_ratio, u_ratio <= 1.0 ? "yes" : "**no**",
                    update->max_err);
      s << line;
    }
  }
  return s.str();
}

/// The joint-torque regressor against our RNEA (issue target: at most 4 × its time), ratios of the
/// rows' medians in this run, with the error of Y π against the float128 RNEA.
std::string regressor_targets(const std::vector<Row>& rows, const std::vector<ModelSpec>& specs) {
  std::ostringstream s;
  char line[512];
  s << "| model | base | build | joint_torque_regressor (ns) | rnea (ns) | ratio | target | met | Y π error (max) | "
       "rnea error (max) |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const ModelSpec& m : specs) {
    if (!m.kept_joints.empty()) continue;
    for (const char* library : {"spatial_dynamics", "spatial_dynamics_default_build"}) {
      const Row* regressor = find(rows, library, "joint_torque_regressor", m.name, m.base);
      const Row* rnea = find(rows, library, "rnea", m.name, m.base);
      if (!regressor || !rnea) continue;
      const double ratio = regressor->ns_median / rnea->ns_median;
      std::snprintf(line, sizeof line, "| %s | %s | %s | %.0f | %.0f | %.2f | 4.00 | %s | %.2g | %.2g |\n", m.name.c_str(),
                    m.base.c_str(), std::string(library) == "spatial_dynamics" ? "native" : "default",
                    regressor->ns_median, rnea->ns_median, ratio, ratio <= 4.0 ? "yes" : "**no**", regressor->max_err,
                    rnea->max_err);
      s << line;
    }
  }
  return s.str();
}

/// The contact rows against our own rows of the same run (issue targets): inverse_dynamics_with_contacts
/// within one RNEA plus one CRBA, forward_dynamics_with_contacts within 2.5 × the ABA; errors of
/// (τ ; λ) and (q̈ ; λ) against the dense float128 solutions.
std::string contact_targets(const std::vector<Row>& rows, const std::vector<ModelSpec>& specs) {
  std::ostringstream s;
  char line[512];
  s << "| model | base | build | contact ID (ns) | rnea + crba (ns) | ratio | met | (τ ; λ) error (max) | contact FD (ns) "
       "| aba (ns) | ratio to aba | target | met | (q̈ ; λ) error (max) |\n"
       "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const ModelSpec& m : specs) {
    if (!m.kept_joints.empty()) continue;
    for (const char* library : {"spatial_dynamics", "spatial_dynamics_default_build"}) {
      const Row* id = find(rows, library, "inverse_dynamics_with_contacts", m.name, m.base);
      const Row* fd = find(rows, library, "forward_dynamics_with_contacts", m.name, m.base);
      const Row* rnea = find(rows, library, "rnea", m.name, m.base);
      const Row* crba = find(rows, library, "crba", m.name, m.base);
      const Row* aba = find(rows, library, "aba", m.name, m.base);
      if (!id || !fd || !rnea || !crba || !aba) continue;
      const double id_ratio = id->ns_median / (rnea->ns_median + crba->ns_median), fd_ratio = fd->ns_median / aba->ns_median;
      std::snprintf(line, sizeof line, "| %s | %s | %s | %.0f | %.0f | %.2f | %s | %.2g | %.0f | %.0f | %.2f | 2.50 | %s | %.2g |\n",
                    m.name.c_str(), m.base.c_str(), std::string(library) == "spatial_dynamics" ? "native" : "default",
                    id->ns_median, rnea->ns_median + crba->ns_median, id_ratio, id_ratio <= 1.0 ? "yes" : "**no**",
                    id->max_err, fd->ns_median, aba->ns_median, fd_ratio, fd_ratio <= 2.5 ? "yes" : "**no**", fd->max_err);
      s << line;
    }
  }
  return s.str();
}

/// One identify_payload of 4,000 samples on the panda (20 s of the excitation trajectory at 200 Hz,
/// exact efforts of a 2.1 kg tool on panda_link8): wall time, median (min–max) of 7 runs, target
/// 0.5 s, and the relative error of the identified parameters.
std::string identification_timing(const std::vector<ModelSpec>& specs) {
  const auto panda = std::find_if(specs.begin(), specs.end(), [](const ModelSpec& m) { return m.name == "panda" && m.base == "fixed"; });
  if (panda == specs.end()) return "(no panda among the models)\n";
  const sd::Model<double> model = sd::build_model_from_urdf_file(panda->path);
  sd::Payload tool;
  tool.mass = 2.1;
  tool.center_of_mass = Eigen::Vector3d(0.012, -0.021, 0.085);
  tool.inertia = Eigen::Vector3d(0.02, 0.03, 0.04).asDiagonal();
  const sd::Model<double> truth = sd::with_payloads(model, {{"panda_link8", tool}});
  std::vector<std::string> joints;
  for (int k = 1; k <= 7; ++k) joints.push_back("panda_joint" + std::to_string(k));
  sd::ExcitationOptions options;
  options.sample_period = 0.005;
  options.frame = "panda_link8";
  const sd::Excitation e = sd::excitation_trajectory(model, joints, 19.995, options);
  const int n = static_cast<int>(e.time.size());
  sd::PayloadSamples samples{Eigen::MatrixXd::Zero(model.nq, n), Eigen::MatrixXd::Zero(model.nv, n),
                             Eigen::MatrixXd::Zero(model.nv, n), Eigen::MatrixXd::Zero(model.nv, n)};
  samples.position.topRows(7) = e.position;
  samples.velocity.topRows(7) = e.velocity;
  samples.acceleration.topRows(7) = e.acceleration;
  sd::Data<double> data(model);
  for (int k = 0; k < n; ++k)
    samples.effort.col(k) = sd::rnea(truth, data, samples.position.col(k), samples.velocity.col(k), samples.acceleration.col(k));
  std::vector<double> seconds;
  sd::PayloadIdentification result;
  for (int run = 0; run < 7; ++run) {
    const auto start = Clock::now();
    result = sd::identify_payload(model, data, "panda_link8", samples);
    seconds.push_back(std::chrono::duration<double>(Clock::now() - start).count());
  }
  std::sort(seconds.begin(), seconds.end());
  sd::InertialParameters truth_pi;
  sd::payload_inertia("panda_link8", tool).toParameters(truth_pi.data());
  char line[512];
  std::snprintf(line, sizeof line,
                "| panda | %d | %.3f (%.3f–%.3f) | 0.5 | %s | %.2g | %.3g |\n", n, seconds[3], seconds[0], seconds[6],
                seconds[3] <= 0.5 ? "yes" : "**no**", (result.parameters - truth_pi).norm() / truth_pi.norm(),
                result.condition_number);
  return std::string("| model | samples | seconds, median (min–max) of 7 | target | met | parameter error | condition number |\n"
                     "|---|---|---|---|---|---|---|\n") + line;
}

/// Forward dynamics against KDL in the package's default build (run-time dispatch), at 0.7 × the
/// best peer's ABA: over ChainFdSolver_RNE on the serial models ≤ 0.21 (RBDL-clang's ABA ≈ 0.30 × KDL's
/// forward dynamics on the UR5) and, where KDL has no forward dynamics, over TreeIdSolver_RNE on panda
/// ≤ 0.17 and talos ≤ 0.10 (the best peer's ABA 0.245 and 0.147 × KDL's tree RNEA on this machine).
std::string forward_dynamics_targets(const std::vector<Row>& rows, const std::vector<ModelSpec>& specs,
                                     const Settings& settings) {
  const std::string ours = settings.default_build ? "spatial_dynamics_default_build" : "spatial_dynamics";
  if (!settings.default_build && !settings.portable)
    return "(needs the default build: run with --default-build or --portable)\n";
  const std::map<std::string, double> tree_targets = {{"panda", 0.17}, {"talos", 0.10}};
  std::ostringstream s;
  char line[512];
  s << "| model | ours: aba, default build (ns) | KDL | KDL (ns) | ratio | target | met | paired ratio | aba_refined / aba |\n"
       "|---|---|---|---|---|---|---|---|---|\n";
  for (const ModelSpec& m : specs) {
    if (m.base != "fixed" || !m.kept_joints.empty()) continue;
    const Row* kdl_rnea = find(rows, "kdl", "rnea", m.name, m.base);
    const Row* aba = find(rows, ours, "aba", m.name, m.base);
    const Row* refined = find(rows, ours, "aba_refined", m.name, m.base);
    if (!kdl_rnea || !aba) continue;
    const bool serial = kdl_forward_dynamics(*kdl_rnea) == Algorithm::CrbaCholesky;
    const Row* kdl = find(rows, "kdl", name(kdl_forward_dynamics(*kdl_rnea)), m.name, m.base);
    const auto tree = tree_targets.find(m.name);
    if (!kdl || (!serial && tree == tree_targets.end())) continue;
    const double target = serial ? 0.21 : tree->second;
    const double ratio = aba->ns_median / kdl->ns_median;
    char refined_ratio[32] = "—";
    if (refined) std::snprintf(refined_ratio, sizeof refined_ratio, "%.2f", refined->ns_median / aba->ns_median);
    char paired[32] = "—";
    if (std::isfinite(aba->paired_to_kdl)) std::snprintf(paired, sizeof paired, "%.3f", aba->paired_to_kdl);
    std::snprintf(line, sizeof line, "| %s | %.0f | %s | %.0f | %.3f | %.2f | %s | %s | %s |\n", m.name.c_str(),
                  aba->ns_median, serial ? "ChainFdSolver_RNE" : "TreeIdSolver_RNE", kdl->ns_median, ratio, target,
                  ratio <= target ? "yes" : "**no**", paired, refined_ratio);
    s << line;
  }
  return s.str();
}

/// The flags our rows were measured with.
std::string our_build_flags(const Settings& settings) {
#ifdef SD_BENCH_WITH_NATIVE
  if (!settings.portable) return std::string(native_build_flags()) + " (a shared library of the benchmark's)";
#endif
  (void)settings;
  return std::string(kBuildFlags) + " (the package's default build: libspatial_dynamics, its " + sd::simd_backend() +
         " instances chosen at run time)";
}

void write_markdown(const std::string& path, const std::vector<Row>& rows, const std::vector<ModelSpec>& specs,
                    const std::vector<std::string>& load_failures, const Settings& settings, const std::string& identification) {
  std::ostringstream s;
  s << "# Speed against error\n\n"
    << "Errors: norm-wise relative error ‖x − x_ref‖/‖x_ref‖ (Frobenius for M; for FK the stacked rotation matrices and "
       "positions of every moving body) against spatial_dynamics in float128 on the same model (converted exactly) and "
       "inputs; max and median over the random states (q ∈ U(−π, π), q̇, q̈ ∈ U(−1, 1), forward dynamics fed τ = RNEA "
       "in double). Float rows get the same double inputs rounded to float. Times (thread CPU time, so that time the "
       "thread spends descheduled on a shared machine does not count): median (min–max) of "
    << settings.repeats << " interleaved repeats (each round times one repeat of every row of the model) of up to " << settings.calls << " calls over the state pool after a warm-up; fewer calls "
    << "per repeat when one repeat would take more than " << settings.repeat_seconds << " s (the calls column). "
    << "Errors over " << settings.states << " states, except that a row whose calls have taken " << settings.error_seconds
    << " s stops taking states, and the float128 mass matrices get " << settings.mass_matrix_seconds
    << " s per model (the states column). "
    << "Comparators: Debian's builds (SSE2, no FMA), called from adapters built with " << kBuildFlags << ". "
    << "spatial_dynamics rows: " << our_build_flags(settings) << ".\n\n";
  s << "## Accuracy bounds\n\n" << acceptance(rows, specs) << "\n";
  s << "## Actuator dynamics\n\n`rnea_actuated` (inverse_dynamics_actuated) and `aba_actuated` "
       "(forward_dynamics_actuated) with random armature (0–0.5), damping (0–2), Coulomb friction (0–1) and "
       "friction_velocity (1e-3–0.1) on every joint (bench/benchmark_actuators.hpp), on the shared robots, against "
       "their rigid-body rows of the same run: time ratio (bound 1.10: the paired ratio, the median over 41 pairs of "
       "back-to-back blocks of the two rows, which the machine's drift between the rows' separate repeats does not "
       "move; the ratio of the medians beside it) and error against the float128 reference "
       "with the same terms (bound: the rigid row's, RNEA 4e-15, ABA its anchor or the best comparator).\n\n"
    << actuated_rows(rows) << "\n";
  s << "## Speed ratios\n\nOur double time over the comparator's, both from this run; the best-peer figures are RBDL "
       "3.3.1's and Pinocchio 3.7.0's (built from source with -O3 -march=native on this kind of machine; Debian packages "
       "neither), rescaled by KDL's tree RNEA time in this run over the one measured beside them. Flags: as above.\n\n"
    << speed_targets(rows, specs) << "\n";
  s << "## Forward dynamics against KDL, default build\n\nThe package's own build (run-time dispatch, not "
       "-march=native): `aba` over KDL's ChainFdSolver_RNE on the serial models and over its TreeIdSolver_RNE on the "
       "trees, where KDL has no forward dynamics; the targets are 0.7 × the best peer's ABA (RBDL or Pinocchio, -O3 "
       "-march=native, their faster compiler) on this kind of machine, as ratios to KDL. `ratio` is the ratio of "
       "the two rows' medians, as the targets are stated; `paired ratio` the median over 41 pairs of back-to-back "
       "blocks of the two (time_paired), which the machine's drift between the rows' repeats does not move (where a "
       "call of KDL's takes under 1 ms). The last column is aba_refined's time over aba's.\n\n"
    << forward_dynamics_targets(rows, specs, settings) << "\n";
  s << "## Coriolis matrix and momentum observer\n\n`coriolis_matrix` (C(q, q̇), error as M's: Frobenius) and one "
       "`MomentumObserver::update` (the benchmark's actuator terms, K = 50/s, Δt = 1 ms; its error over p = M q̇ and "
       "u = τ_m − τ_a + Cᵀ q̇ − g stacked, τ_m the state's τ) against our own rows of the same run: C within 2 × the "
       "CRBA's time, an update within one RNEA plus one CRBA (doc/external_torques.md).\n\n"
    << observer_targets(rows, specs) << "\n";
  s << "## Joint-torque regressor and payload identification\n\n`joint_torque_regressor` (Y, with Y π against the "
       "float128 RNEA) against our `rnea` of the same run, target 4 × its time; and one `identify_payload` of 4,000 "
       "samples on the panda (doc/payload_identification.md), target 0.5 s.\n\n"
    << regressor_targets(rows, specs) << "\n" << identification << "\n";
  s << "## Contacts\n\n`inverse_dynamics_with_contacts` and `forward_dynamics_with_contacts` (doc/library.md, *Contacts "
       "and the centre of mass*) on the floating talos standing on its two soles (`surface`) and the floating solo12 on "
       "its four feet (`point`), against our own rows of the same run: contact-consistent ID within one RNEA plus one "
       "CRBA, constrained FD within 2.5 × the ABA; errors against dense float128 solutions (the base rows' and the KKT "
       "system's pseudo-inverses).\n\n"
    << contact_targets(rows, specs) << "\n";
  if (settings.default_build)
    s << "## The default build against -march=native\n\nThe package's default build (`spatial_dynamics_default_build`: "
         "libspatial_dynamics, its " << sd::simd_backend() << " instances chosen at run time) over our -march=native rows, "
         "both from this run.\n\n" << default_build_ratios(rows) << "\n";
  s << "## Comparators that could not load a model\n\n| library | model | why |\n|---|---|---|\n";
  for (const std::string& f : load_failures) s << "| " << f << " |\n";
  s << "\n## All rows\n\n| model | base | dof | library | scalar | algorithm | method | ns/call median (min–max) | "
       "max err | median err | allocs/call | calls × repeats | states |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows) {
    s << "| " << r.model << " | " << r.base << " | " << r.dof << " | " << r.library << " | " << r.scalar << " | " << r.algorithm
      << " | " << r.method << " | ";
    if (!r.failure.empty()) {
      s << "fails: " << r.failure << " | | | | | |\n";
      continue;
    }
    char t[96];
    std::snprintf(t, sizeof t, "%.0f (%.0f–%.0f)", r.ns_median, r.ns_min, r.ns_max);
    s << t << " | " << (std::isfinite(r.max_err) ? format_g(r.max_err) : "non-finite") << " | "
      << (std::isfinite(r.median_err) ? format_g(r.median_err) : "non-finite") << " | " << r.allocs << " | " << r.calls
      << " × " << r.repeats << " | " << r.error_states << " |\n";
  }
  write_file(path, s.str());
}

int usage(const char* argv0) {
  std::fprintf(stderr, "usage: %s [--model PATH]... [--floating] [--quick] [--portable | --default-build] [--out DIR]\n",
               argv0);
  return 2;
}

}  // namespace
}  // namespace bench

int main(int argc, char** argv) {
  using namespace bench;
  Settings settings;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--model" && i + 1 < argc) settings.models.push_back(argv[++i]);
    else if (arg == "--out" && i + 1 < argc) settings.out = argv[++i];
    else if (arg == "--quick") settings.quick = true;
    else if (arg == "--portable") settings.portable = true;
    else if (arg == "--default-build") settings.default_build = true;
    else if (arg == "--floating") settings.floating = true;
    else return usage(argv[0]);
  }
  if (settings.quick) {
    settings.states = 10;
    settings.repeats = 5;
    settings.calls = 10000;
    settings.repeat_seconds = 0.005;
    settings.mass_matrix_seconds = 0.5;
    settings.error_seconds = 0.3;
    settings.min_mass_matrices = 1;
    settings.min_calls = 1;
  }
  fs::create_directories(settings.out);
  std::vector<ModelSpec> specs;
  if (settings.models.empty()) {
    specs = default_models(settings);
  } else {
    for (const std::string& path : settings.models) {
      const std::string name = fs::path(path).stem().string();
      specs.push_back({name, "fixed", path});
      if (settings.floating) specs.push_back({name, "floating", path});
    }
  }
  const auto start = Clock::now();
  std::vector<Row> rows;
  std::vector<std::string> load_failures;
  for (const ModelSpec& spec : specs) {
    try {
      run_model(spec, settings, rows, load_failures);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s (%s): %s\n", spec.name.c_str(), spec.base.c_str(), e.what());
      return 1;
    }
  }
  const std::string identification = identification_timing(specs);
  write_csv(settings.out + "/results.csv", rows);
  write_markdown(settings.out + "/results.md", rows, specs, load_failures, settings, identification);
  std::printf("\nSpeed targets\n\n%s\n", speed_targets(rows, specs).c_str());
  std::printf("\nForward dynamics against KDL, default build\n\n%s\n", forward_dynamics_targets(rows, specs, settings).c_str());
  std::printf("\nCoriolis matrix and momentum observer\n\n%s\n", observer_targets(rows, specs).c_str());
  std::printf("\nJoint-torque regressor and payload identification\n\n%s\n%s\n", regressor_targets(rows, specs).c_str(),
              identification.c_str());
  std::printf("\nContacts\n\n%s\n", contact_targets(rows, specs).c_str());
  if (settings.default_build) std::printf("\nDefault build against -march=native\n\n%s\n", default_build_ratios(rows).c_str());
  std::printf("\nActuator rows against the rigid-body rows\n\n%s\n",
              actuated_rows(rows).c_str());
  std::printf("wrote %s/results.csv and results.md (%zu rows) in %.0f s\n", settings.out.c_str(), rows.size(),
              std::chrono::duration<double>(Clock::now() - start).count());
  const std::string plot = std::string("/usr/bin/python3 ") + SD_BENCH_PLOT_SCRIPT + " " + settings.out + "/results.csv " +
                           settings.out + "/benchmark.png";
  const std::string summary = std::string("/usr/bin/python3 ") + SD_BENCH_SUMMARY_SCRIPT + " " + settings.out +
                              "/results.csv " + settings.out + "/summary.md";
  for (const std::string& command : {plot, summary}) {
    if (std::system(command.c_str()) != 0) {
      std::fprintf(stderr, "failed: %s\n", command.c_str());
      return 1;
    }
  }
  return 0;
}
