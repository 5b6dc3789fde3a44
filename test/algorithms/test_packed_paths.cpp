// The RNEA and the CRBA on packed 3-vectors (algorithms/vector3_form.hpp)
// and the batched RNEA's AVX paths (lanes.hpp: 4 double lanes, columns gathered by 4×4
// transposes). This target is compiled with -mavx2 -mfma, so rnea() and crba() take the packed
// forms here, where the other unit tests (portable flags) run the scalar code. Oracles: the
// float128 reference of the same model and inputs, and the same RNEA on Eigen's 3-vectors
// (vec3::ScalarForm) compiled in the same file.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "allocation_counter.hpp"
#include "spatial_dynamics/algorithms/aba_refined.hpp"
#include "spatial_dynamics/algorithms/rnea_batch.hpp"
#include "spatial_dynamics/reduction/couple_mimic_joints.hpp"
#include "spatial_dynamics/reference/high_precision.hpp"
#include "spatial_dynamics/synthetic/random_robot.hpp"
#include "test_utils.hpp"

#ifndef SD_PACKED3
#error "test_packed_paths is compiled with -mavx2 -mfma: the packed path must be available"
#endif

namespace sd = spatial_dynamics;
using Eigen::VectorXd;

namespace {

bool cpu_runs_packed_code() { return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"); }

#define SKIP_WITHOUT_AVX2_FMA() \
  if (!cpu_runs_packed_code()) GTEST_SKIP() << "this CPU has no AVX2 and FMA"

// Every joint kind the packed path distinguishes: revolute about x, y, z, −y (a general axis) and
// a tilted axis; prismatic along x, y, z and a tilted axis; two branches from one body.
const char* const kEveryJointKindUrdf = R"(<robot name='kinds'>
  <link name='base'/>
  <link name='l1'><inertial><mass value='1.3'/><origin xyz='0.1 0.02 -0.03'/><inertia ixx='0.02' ixy='0.001' ixz='-0.002' iyy='0.03' iyz='0.003' izz='0.025'/></inertial></link>
  <link name='l2'><inertial><mass value='0.9'/><origin xyz='-0.04 0.1 0.01'/><inertia ixx='0.011' ixy='-0.001' ixz='0.0005' iyy='0.014' iyz='0.001' izz='0.009'/></inertial></link>
  <link name='l3'><inertial><mass value='1.1'/><origin xyz='0.02 -0.03 0.12'/><inertia ixx='0.015' ixy='0.002' ixz='0' iyy='0.012' iyz='-0.001' izz='0.017'/></inertial></link>
  <link name='l4'><inertial><mass value='0.7'/><origin xyz='0.05 0.05 0.05'/><inertia ixx='0.006' ixy='0' ixz='0.001' iyy='0.007' iyz='0' izz='0.008'/></inertial></link>
  <link name='l5'><inertial><mass value='0.6'/><origin xyz='0 0.03 -0.02'/><inertia ixx='0.004' ixy='0.0005' ixz='0' iyy='0.005' iyz='0.0002' izz='0.006'/></inertial></link>
  <link name='l6'><inertial><mass value='0.5'/><origin xyz='0.01 0 0.04'/><inertia ixx='0.003' ixy='0' ixz='0' iyy='0.004' iyz='0.0003' izz='0.0035'/></inertial></link>
  <link name='l7'><inertial><mass value='0.8'/><origin xyz='-0.02 0.01 0.03'/><inertia ixx='0.005' ixy='0.001' ixz='0' iyy='0.006' iyz='0' izz='0.004'/></inertial></link>
  <link name='l8'><inertial><mass value='0.4'/><origin xyz='0.03 -0.01 0'/><inertia ixx='0.002' ixy='0' ixz='0.0001' iyy='0.003' iyz='0' izz='0.0025'/></inertial></link>
  <link name='l9'><inertial><mass value='0.3'/><origin xyz='0 0 0.02'/><inertia ixx='0.001' ixy='0' ixz='0' iyy='0.0012' iyz='0' izz='0.0011'/></inertial></link>
  <joint name='rx' type='continuous'><parent link='base'/><child link='l1'/><origin xyz='0 0 0.1' rpy='0.1 0.2 0.3'/><axis xyz='1 0 0'/></joint>
  <joint name='ry' type='continuous'><parent link='l1'/><child link='l2'/><origin xyz='0.2 0 0' rpy='-0.4 0.1 0'/><axis xyz='0 1 0'/></joint>
  <joint name='rz' type='continuous'><parent link='l2'/><child link='l3'/><origin xyz='0 0.15 0.05' rpy='0 0.5 -0.2'/><axis xyz='0 0 1'/></joint>
  <joint name='px' type='prismatic'><parent link='l3'/><child link='l4'/><origin xyz='0.1 0 0' rpy='0.3 0 0'/><axis xyz='1 0 0'/><limit lower='-1' upper='1' effort='100' velocity='1'/></joint>
  <joint name='rneg' type='continuous'><parent link='l4'/><child link='l5'/><origin xyz='0 0 0.1'/><axis xyz='0 -1 0'/></joint>
  <joint name='rtilt' type='continuous'><parent link='l5'/><child link='l6'/><origin xyz='0.05 0.05 0' rpy='0.7 -0.3 0.2'/><axis xyz='0.48 0.6 0.64'/></joint>
  <joint name='py' type='prismatic'><parent link='l3'/><child link='l7'/><origin xyz='0 -0.1 0'/><axis xyz='0 1 0'/><limit lower='-1' upper='1' effort='100' velocity='1'/></joint>
  <joint name='pz' type='prismatic'><parent link='l7'/><child link='l8'/><origin xyz='0 0 -0.1' rpy='0 0 1'/><axis xyz='0 0 1'/><limit lower='-1' upper='1' effort='100' velocity='1'/></joint>
  <joint name='ptilt' type='prismatic'><parent link='l8'/><child link='l9'/><origin xyz='0.02 0 0'/><axis xyz='0.6 0 0.8'/><limit lower='-1' upper='1' effort='100' velocity='1'/></joint>
</robot>)";

static_assert(std::is_same<sd::vec3::Form<double>, sd::vec3::PackedForm>::value, "double takes the packed form here");

/// The RNEA on Eigen's 3-vectors, in this file's build.
VectorXd scalar_rnea(const sd::Model<double>& model, sd::Data<double>& data, const VectorXd& q, const VectorXd& qd,
                     const VectorXd& qdd, const sd::ForceVector<double>* f_ext) {
  return sd::detail::rnea_with_form<sd::vec3::ScalarForm<double>>(model, data, q, qd, qdd, f_ext, model.gravity);
}

/// Checks the packed RNEA against the float128 reference and against the scalar RNEA on `states`
/// random states (with random external forces when `with_external_forces`); returns the largest
/// relative error against the reference.
double check_against_references(const sd::Model<double>& model, int states, bool with_external_forces,
                                double bound, std::mt19937& rng) {
  sd::Data<double> data(model), scalar_data(model);
  const sd::Model<sd::Quad> ref_model = model.cast<sd::Quad>();
  sd::Data<sd::Quad> ref(ref_model);
  std::vector<sd::ForceVector<double>> f_ext(model.nbodies(), sd::ForceVector<double>::Zero());
  std::vector<sd::ForceVector<sd::Quad>> f_ext_ref(model.nbodies(), sd::ForceVector<sd::Quad>::Zero());
  double worst = 0;
  for (int s = 0; s < states; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const VectorXd qd = sd_test::random_vector(model.nv, rng), qdd = sd_test::random_vector(model.nv, rng);
    if (with_external_forces)
      for (int i = 1; i < model.nbodies(); ++i) {
        f_ext[i] = sd::ForceVector<double>(sd_test::random_vector(6, rng, 5.0));
        f_ext_ref[i] = sd::ForceVector<sd::Quad>(sd::to_quad(f_ext[i].toVector()));
      }
    const VectorXd tau = with_external_forces ? sd::rnea(model, data, q, qd, qdd, f_ext) : sd::rnea(model, data, q, qd, qdd);
    const sd::VectorX<sd::Quad> Q = sd::to_quad(q), QD = sd::to_quad(qd), QDD = sd::to_quad(qdd);
    const sd::VectorX<sd::Quad> tau_ref =
        with_external_forces ? sd::rnea(ref_model, ref, Q, QD, QDD, f_ext_ref) : sd::rnea(ref_model, ref, Q, QD, QDD);
    const double error = sd::relative_error_to(tau, tau_ref);
    worst = std::max(worst, error);
    EXPECT_LE(error, bound) << "state " << s;
    // The scalar RNEA on the same inputs: both within the bound of the reference, so within
    // twice of each other.
    const VectorXd tau_scalar = scalar_rnea(model, scalar_data, q, qd, qdd, with_external_forces ? f_ext.data() : nullptr);
    EXPECT_LE(sd_test::relative_error(tau, tau_scalar), 2 * bound) << "state " << s;
  }
  return worst;
}

/// Checks the CRBA on packed 3-vectors, with both carries (per ancestor, from base coordinates), against the
/// float128 reference on `states` random states: relative error within `bound`, both triangles
/// equal, and the entries of joints on different branches exactly 0.
double check_mass_matrix(const sd::Model<double>& model, int states, double bound, std::mt19937& rng) {
  sd::Data<double> data(model), in_base(model);
  data.crba_in_base_coordinates = false;
  in_base.crba_in_base_coordinates = true;
  const sd::Model<sd::Quad> ref_model = model.cast<sd::Quad>();
  sd::Data<sd::Quad> ref(ref_model);
  double worst = 0;
  for (int s = 0; s < 2 * states; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const Eigen::MatrixXd M = sd::crba(model, s % 2 == 0 ? data : in_base, q);
    const double error = sd::relative_error_to(M, sd::crba(ref_model, ref, sd::to_quad(q)));
    worst = std::max(worst, error);
    EXPECT_LE(error, bound) << "state " << s;
    EXPECT_EQ(M, M.transpose());
    for (int i = 1; i < model.nbodies(); ++i)
      for (int k = 1; k < model.nbodies(); ++k) {
        bool related = false;
        for (int a = i; a > 0 && !related; a = model.parent[a]) related = a == k;
        for (int a = k; a > 0 && !related; a = model.parent[a]) related = a == i;
        if (!related) EXPECT_EQ(M(model.joints[i].idx_v, model.joints[k].idx_v), 0.0) << i << ", " << k;
      }
  }
  return worst;
}

}  // namespace

// The RNEA's and the CRBA's packed forms serve every model, a floating base and a coupled joint
// (a master's coordinate scaled and accumulated) included, against the float128 reference (and
// the RNEA against the scalar form).
TEST(PackedPaths, TakesThePathWhereItApplies) {
  SKIP_WITHOUT_AVX2_FMA();
  for (const std::string& file : sd_test::robot_files()) {
    const sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path(file));
    const sd::Data<double> data(model);
    // The CRBA carries columns per ancestor, or from base coordinates on trees with 4 or more
    // ancestors per body in runs of 2 or more on average (of these robots, talos).
    EXPECT_EQ(data.crba_in_base_coordinates, file == "talos.urdf") << file;
  }
  sd::ModelBuildOptions floating;
  floating.floating_base = true;
  const std::string coupled_urdf =
      "<robot name='c'><link name='base'/><link name='a'><inertial><mass value='1'/><inertia ixx='0.01' ixy='0' "
      "ixz='0' iyy='0.02' iyz='0' izz='0.02'/></inertial></link><link name='b'><inertial><mass value='1'/><origin "
      "xyz='0.1 0 0'/><inertia ixx='0.01' ixy='0' ixz='0' iyy='0.02' iyz='0' izz='0.02'/></inertial></link><joint "
      "name='ja' type='continuous'><parent link='base'/><child link='a'/><axis xyz='0 0 1'/></joint><joint name='jb' "
      "type='continuous'><parent link='a'/><child link='b'/><origin xyz='0.3 0 0'/><axis xyz='0 1 0'/><mimic "
      "joint='ja' multiplier='-2.5' offset='0.7'/></joint></robot>";
  std::mt19937 rng(5), mass_matrix_rng(7);
  std::mt19937 chain_rng(3);
  const sd::Model<double> long_chain =
      sd::build_model_from_urdf_string(sd::synthetic::to_urdf("chain", sd::synthetic::random_chain(30, chain_rng)));
  EXPECT_TRUE(sd::Data<double>(long_chain).crba_in_base_coordinates);  // 14.5 ancestors per body, one run
  for (const sd::Model<double>& model :
       {sd::build_model_from_urdf_file(sd_test::robot_path("solo12.urdf"), floating),
        sd::couple_mimic_joints(sd::build_model_from_urdf_string(coupled_urdf))}) {
    check_against_references(model, 50, true, 4e-15, rng);
    EXPECT_LE(check_mass_matrix(model, 25, 4e-15, mass_matrix_rng), 4e-15);
  }
}

// The shared robots: within the RNEA bound (4e-15) of the float128 reference on
// 300 random states each.
TEST(PackedPaths, SharedRobotsAgainstTheReference) {
  SKIP_WITHOUT_AVX2_FMA();
  std::mt19937 rng(17);
  for (const std::string& file : sd_test::robot_files()) {
    const double worst = check_against_references(sd::build_model_from_urdf_file(sd_test::robot_path(file)), 300, false,
                                                  4e-15, rng);
    std::printf("%-22s packed RNEA, worst relative error %.2e\n", file.c_str(), worst);
    const sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path(file));
    std::printf("%-22s packed CRBA, worst relative error %.2e\n", file.c_str(), check_mass_matrix(model, 300, 4e-15, rng));
  }
}

// Every joint kind, a branched tree and external forces on every body.
TEST(PackedPaths, EveryJointKindWithExternalForces) {
  SKIP_WITHOUT_AVX2_FMA();
  const sd::Model<double> model = sd::build_model_from_urdf_string(kEveryJointKindUrdf);
  int prismatic = 0, general = 0;
  for (int i = 1; i < model.nbodies(); ++i) {
    prismatic += model.joints[i].type == sd::JointType::Prismatic;
    general += model.joints[i].axis_kind == sd::AxisKind::General;
  }
  ASSERT_EQ(prismatic, 4);
  ASSERT_GE(general, 3);
  std::mt19937 rng(23);
  check_against_references(model, 300, false, 4e-15, rng);
  check_against_references(model, 300, true, 4e-15, rng);
  check_mass_matrix(model, 300, 4e-15, rng);
}

// A 50-body chain with random axes: per body and pass at most ~5ε (test_hard_cases.cpp), so
// 10·d·ε with d = 50 bounds the error where nothing cancels; 4× that leaves room for the
// cancellation of gravity against the accelerations on random states (the scalar RNEA measures
// 5.2e-15 on such a chain in the benchmark).
TEST(PackedPaths, RandomChainAgainstTheReference) {
  SKIP_WITHOUT_AVX2_FMA();
  std::mt19937 rng(29);
  const sd::Model<double> model =
      sd::build_model_from_urdf_string(sd::synthetic::to_urdf("chain", sd::synthetic::random_chain(50, rng)));
  check_against_references(model, 100, false, 4 * 10 * 50 * std::numeric_limits<double>::epsilon(), rng);
  check_mass_matrix(model, 100, 4 * 10 * 50 * std::numeric_limits<double>::epsilon(), rng);
}

// Nonlinear effects, gravity torques and the CRBA + Cholesky forward dynamics go through the
// packed paths; a NaN
// configuration still fails with the message naming the joint force or the mass matrix column,
// and the calls allocate nothing.
TEST(PackedPaths, CallersErrorsAndAllocations) {
  SKIP_WITHOUT_AVX2_FMA();
  const sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path("panda.urdf"));
  sd::Data<double> data(model);
  const sd::Model<sd::Quad> ref_model = model.cast<sd::Quad>();
  sd::Data<sd::Quad> ref(ref_model);
  std::mt19937 rng(41);
  const VectorXd q = sd_test::random_configuration(model, rng), qd = sd_test::random_vector(model.nv, rng);
  const VectorXd h = sd::nonlinear_effects(model, data, q, qd);
  EXPECT_LE(sd::relative_error_to(h, sd::nonlinear_effects(ref_model, ref, sd::to_quad(q), sd::to_quad(qd))), 4e-15);
  const VectorXd g = sd::gravity_torques(model, data, q);
  EXPECT_LE(sd::relative_error_to(g, sd::gravity_torques(ref_model, ref, sd::to_quad(q))), 4e-15);
  const VectorXd tau = sd_test::random_vector(model.nv, rng, 10.0);
  const VectorXd qdd = sd::forward_dynamics(model, data, q, qd, tau);
  const VectorXd qdd_ref = sd::aba(ref_model, ref, sd::to_quad(q), sd::to_quad(qd), sd::to_quad(tau)).cast<double>();
  EXPECT_LE(sd_test::relative_error(qdd, qdd_ref), 1e-12);

  VectorXd bad = q;
  bad[3] = std::numeric_limits<double>::quiet_NaN();
  try {
    sd::rnea(model, data, bad, qd, qd);
    ADD_FAILURE() << "a NaN angle gave a finite torque";
  } catch (const std::domain_error& e) {
    EXPECT_NE(std::string(e.what()).find("inverse dynamics"), std::string::npos) << e.what();
  }
  EXPECT_THROW(sd::rnea(model, data, q.head(3), qd, qd), std::invalid_argument);
  try {
    sd::crba(model, data, bad);
    ADD_FAILURE() << "a NaN angle gave a finite mass matrix";
  } catch (const std::domain_error& e) {
    EXPECT_NE(std::string(e.what()).find("mass matrix"), std::string::npos) << e.what();
  }
  EXPECT_THROW(sd::crba(model, data, q.head(3)), std::invalid_argument);

  const long before = bench::allocation_count();
  for (int k = 0; k < 100; ++k) {
    sd::rnea(model, data, q, qd, qd);
    sd::gravity_torques(model, data, q);
    sd::crba(model, data, q);
  }
  EXPECT_EQ(bench::allocation_count() - before, 0);
}

// The batched RNEA with 4 AVX lanes: the columns gathered 4×4 at a time plus a remainder (nq = 6,
// 9 and 12 here), a last partial block of 3 states; every column against the float128 reference
// and against the scalar RNEA of its state.
TEST(PackedPaths, BatchedRneaAgainstTheReference) {
  SKIP_WITHOUT_AVX2_FMA();
  static_assert(sd::kDefaultBatchLanes<double> == 4, "this target is compiled for AVX2 lanes");
  std::mt19937 rng(43);
  for (const std::string& file : {"ur5.urdf", "panda.urdf", "solo12.urdf"}) {
    const sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path(file));
    sd::BatchData<double> batch(model);
    sd::Data<double> scalar_data(model);
    const sd::Model<sd::Quad> ref_model = model.cast<sd::Quad>();
    sd::Data<sd::Quad> ref(ref_model);
    const int states = 11;
    Eigen::MatrixXd q(model.nq, states), qd(model.nv, states), qdd(model.nv, states), tau(model.nv, states);
    for (int c = 0; c < states; ++c) {
      q.col(c) = sd_test::random_configuration(model, rng);
      qd.col(c) = sd_test::random_vector(model.nv, rng);
      qdd.col(c) = sd_test::random_vector(model.nv, rng);
    }
    sd::rnea_batch(model, batch, q, qd, qdd, tau);
    for (int c = 0; c < states; ++c) {
      const VectorXd tau_scalar = sd::detail::rnea_impl(model, scalar_data, q.col(c), qd.col(c), qdd.col(c),
                                                        static_cast<const sd::ForceVector<double>*>(nullptr));
      // Formula by formula, but the compiler fuses multiply-adds differently in the two.
      EXPECT_LE(sd_test::relative_error(VectorXd(tau.col(c)), tau_scalar), 8e-15) << file << ", state " << c;
      const sd::VectorX<sd::Quad> tau_ref =
          sd::rnea(ref_model, ref, sd::to_quad(VectorXd(q.col(c))), sd::to_quad(VectorXd(qd.col(c))),
                   sd::to_quad(VectorXd(qdd.col(c))));
      EXPECT_LE(sd::relative_error_to(VectorXd(tau.col(c)), tau_ref), 4e-15) << file << ", state " << c;
    }
  }
}

/// τ − τ_g(q) in float128 from the transforms (and sines and cosines) a double ABA left in data:
/// the gravity split's sums (gravity_split.hpp) written out, g_i = E_i g_λ, f_i = (g_i × h_i ;
/// −m_i g_i), f_λ += X_iᵀ f_i, τ_i − S_iᵀ f_i, rounded once to double.
VectorXd tau_less_gravity_in_quad(const sd::Model<double>& model, const sd::Data<double>& data, const VectorXd& tau) {
  using sd::Quad;
  const sd::Model<Quad> model_q = model.cast<Quad>();
  std::vector<sd::Vector3<Quad>> g(model.nbodies());
  std::vector<sd::ForceVector<Quad>> f(model.nbodies(), sd::ForceVector<Quad>::Zero());
  g[0] = model.gravity.cast<Quad>();
  std::vector<sd::PluckerTransform<Quad>> X(model.nbodies());
  for (int i = 1; i < model.nbodies(); ++i) {
    X[i].E = data.X_up[i].E.cast<Quad>();
    X[i].r = data.X_up[i].r.cast<Quad>();
    g[i] = X[i].E * g[model.parent[i]];
    const sd::RigidInertia<Quad>& I = model_q.inertia[i];
    f[i] = sd::ForceVector<Quad>(g[i].cross(I.first_moment), -I.mass * g[i]);
  }
  VectorXd out(model.nv);
  for (int i = model.nbodies() - 1; i >= 1; --i) {
    const sd::Joint<Quad>& j = model_q.joints[i];
    Quad projected[6];
    sd::joint_project(j, Quad(data.joint_sin[i]), Quad(data.joint_cos[i]), f[i], projected);
    for (int k = 0; k < j.nv; ++k) out[j.idx_v + k] = static_cast<double>(Quad(tau[j.idx_v + k]) - projected[k]);
    if (model.parent[i] > 0) f[model.parent[i]] += X[i].applyInverse(f[i]);
  }
  return out;
}

// The ABA's gravity split on packed 3-vectors (spatial/number/wide_vector3.hpp) against the same sums in
// float128 from the same transforms: τ − τ_g is formed in double-double and rounded once, so it
// is within one unit in the last place of the float128 value. And the ABA on this path within the
// anchors on the shared robots (test_gravity_split.cpp: the build the library dispatches to).
TEST(PackedPaths, GravitySplitWithinAnUlpOfFloat128) {
  SKIP_WITHOUT_AVX2_FMA();
  sd::ModelBuildOptions floating;
  floating.floating_base = true;
  struct Case {
    sd::Model<double> model;
    double aba_bound;  // 0: not a shared robot
  };
  const std::vector<Case> cases = {
      {sd::build_model_from_urdf_string(kEveryJointKindUrdf), 0},
      {sd::build_model_from_urdf_file(sd_test::robot_path("panda.urdf")), 3.9e-14},
      {sd::build_model_from_urdf_file(sd_test::robot_path("ur5.urdf")), 1.8e-14},
      {sd::build_model_from_urdf_file(sd_test::robot_path("talos.urdf")), 9.2e-14},
      {sd::build_model_from_urdf_file(sd_test::robot_path("solo12.urdf"), floating), 1.35e-13},
      {sd::build_model_from_urdf_file(sd_test::robot_path("talos.urdf"), floating), 8.2e-13},
  };
  const double eps = std::numeric_limits<double>::epsilon();
  std::mt19937 rng(29);
  for (const Case& c : cases) {
    const sd::Model<double>& model = c.model;
    const sd::Model<sd::Quad> model_q = model.cast<sd::Quad>();
    sd::Data<double> data(model);
    sd::Data<sd::Quad> data_q(model_q);
    int ulps = 0;
    double worst_aba = 0;
    for (int s = 0; s < 300; ++s) {
      const VectorXd q = sd_test::random_configuration(model, rng);
      const VectorXd qd = sd_test::random_vector(model.nv, rng);
      const VectorXd tau = sd::rnea(model, data, q, qd, sd_test::random_vector(model.nv, rng));
      const VectorXd qdd = sd::aba(model, data, q, qd, tau);
      const VectorXd expected = tau_less_gravity_in_quad(model, data, tau);
      for (int k = 0; k < model.nv; ++k) {
        const double difference = std::abs(data.tau_less_gravity[k] - expected[k]);
        ASSERT_LE(difference, eps * std::abs(expected[k])) << "coordinate " << k;
        ulps += difference > 0;
      }
      const sd::VectorX<sd::Quad> reference = sd::aba(model_q, data_q, sd::to_quad(q), sd::to_quad(qd), sd::to_quad(tau));
      worst_aba = std::max(worst_aba, sd::relative_error_to(qdd, reference));
    }
    std::printf("packed gravity split: %d coordinates one ulp from float128; worst ABA error %.2e\n", ulps,
                worst_aba);
    if (c.aba_bound > 0) EXPECT_LE(worst_aba, c.aba_bound);
  }
}

// The ABA's outward pass on packed 3-vectors (algorithms/aba.hpp): per body v_i = X v_λ + S q̇,
// c_i = c_J + v_i × S q̇, pᴬ_i = v_i ×* I v_i − f_ext and Iᴬ_i = I_i, against the same products
// of 6×6 matrices and the joint models' S q̇ and c_J, on every joint kind, a branched tree and a
// floating base, with external forces.
TEST(PackedPaths, AbaVelocityPassAgainstMatrices) {
  SKIP_WITHOUT_AVX2_FMA();
  sd::ModelBuildOptions floating;
  floating.floating_base = true;
  std::mt19937 rng(29);
  double worst = 0;
  for (const sd::Model<double>& model : {sd::build_model_from_urdf_string(kEveryJointKindUrdf),
                                         sd::build_model_from_urdf_string(kEveryJointKindUrdf, floating)}) {
    sd::Data<double> data(model);
    for (int s = 0; s < 50; ++s) {
      const VectorXd q = sd_test::random_configuration(model, rng), qd = sd_test::random_vector(model.nv, rng, 3.0);
      std::vector<sd::ForceVector<double>> f_ext(model.nbodies());
      for (auto& f : f_ext) f = sd::ForceVector<double>(sd::Vector6<double>(sd_test::random_vector(6, rng)));
      sd::detail::aba_velocity_pass(model, data, sd::ConstVectorRef<double>(q), sd::ConstVectorRef<double>(qd),
                                    f_ext.data(), true);
      for (int i = 1; i < model.nbodies(); ++i) {
        const sd::Vector6<double> vJ = sd::body_joint_motion(model, data, i, qd.data()).toVector();
        const sd::Vector6<double> v = data.X_up[i].toMotionMatrix() * data.v[model.parent[i]].toVector() + vJ;
        const sd::Vector6<double> c = sd::body_joint_bias(model, data, i, qd.data()).toVector() +
                                      sd::motion_cross_matrix(data.v[i]) * vJ;
        const sd::Matrix6<double> I = model.inertia[i].toMatrix();
        const sd::Vector6<double> p = sd::force_cross_matrix(data.v[i]) * (I * v) - f_ext[i].toVector();
        const auto relative = [](const sd::Vector6<double>& x, const sd::Vector6<double>& y) {
          return (x - y).norm() / std::max(1.0, y.norm());
        };
        worst = std::max({worst, relative(data.v[i].toVector(), v), relative(data.c[i].toVector(), c),
                          relative(data.f[i].toVector(), p)});
        if (!data.has_children[i]) EXPECT_EQ(data.IA[i].matrix, I) << model.joint_names[i];  // a parent's: pass 2
      }
    }
  }
  EXPECT_LE(worst, 1e-14);
  std::printf("packed ABA outward pass: worst relative difference %.1e from the 6x6 products\n", worst);
}

// The ABA's inward step on an articulated inertia's packed blocks (spatial/number/packed3_articulated_inertia.hpp):
// Xᵀ (Iᴬ − U D⁻¹ Uᵀ) X and Xᵀ Iᴬ X added to an inertia, (Iᴬ − U D⁻¹ Uᵀ) c and Iᴬ v, against the same products of
// 6×6 matrices (PluckerTransform::toMotionMatrix) on random transforms and random symmetric
// positive definite Iᴬ, with U a column of Iᴬ (a coordinate axis' U = Iᴬ S).
TEST(PackedPaths, ArticulatedInertiaStepAgainstMatrices) {
  SKIP_WITHOUT_AVX2_FMA();
  using Matrix6 = sd::Matrix6<double>;
  std::mt19937 rng(47);
  std::uniform_real_distribution<double> u(-1, 1);
  const auto random_spd = [&]() {
    Matrix6 L;
    for (int k = 0; k < 36; ++k) L(k % 6, k / 6) = u(rng);
    return Matrix6(L * L.transpose() + 0.1 * Matrix6::Identity());
  };
  double worst_step = 0, worst_add = 0, worst_product = 0, worst_downdated_product = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    const sd::PluckerTransform<double> X(sd::coordinate_rotation(axis, 3 * u(rng)),
                                         Eigen::Vector3d(u(rng), u(rng), u(rng)));
    const Matrix6 Xm = X.toMotionMatrix();
    const Matrix6 Ia = random_spd(), start = random_spd();
    const int column = trial % 6;
    const sd::Vector6<double> U = Ia.col(column);
    const double D_inv = 1 / Ia(column, column);

    const sd::MotionVector<double> c(Eigen::Vector3d(u(rng), u(rng), u(rng)), Eigen::Vector3d(u(rng), u(rng), u(rng)));
    const sd::Vector6<double> W = Xm.transpose() * U;  // U in the parent's coordinates
    namespace p3 = sd::packed3;
    sd::ArticulatedInertia<double> out(start);
    const sd::Vector6<double> Ia_c =
        X.applyInverseAddLessRankOne(sd::ArticulatedInertia<double>(Ia), p3::load3(U.data()), p3::load3(U.data() + 3),
                                     D_inv, p3::load3(W.data()), p3::load3(W.data() + 3), c, out)
            .toVector();
    const Matrix6 Ia_less = Ia - U * D_inv * U.transpose();
    const Matrix6 expected_step = start + Xm.transpose() * Ia_less * Xm;
    worst_step = std::max(worst_step, (out.matrix - expected_step).norm() / expected_step.norm());
    const sd::Vector6<double> expected_Ia_c = Ia_less * c.toVector();
    worst_downdated_product = std::max(worst_downdated_product, (Ia_c - expected_Ia_c).norm() / expected_Ia_c.norm());

    sd::ArticulatedInertia<double> sum(start);
    X.applyInverseAdd(sd::ArticulatedInertia<double>(Ia), sum);
    const Matrix6 expected_sum = start + Xm.transpose() * Ia * Xm;
    worst_add = std::max(worst_add, (sum.matrix - expected_sum).norm() / expected_sum.norm());

    const sd::MotionVector<double> v(Eigen::Vector3d(u(rng), u(rng), u(rng)), Eigen::Vector3d(u(rng), u(rng), u(rng)));
    const sd::Vector6<double> product = (sd::ArticulatedInertia<double>(Ia) * v).toVector();
    const sd::Vector6<double> expected_product = Ia * v.toVector();
    worst_product = std::max(worst_product, (product - expected_product).norm() / expected_product.norm());
  }
  EXPECT_LE(worst_step, 1e-14);
  EXPECT_LE(worst_add, 1e-14);
  EXPECT_LE(worst_product, 1e-15);
  EXPECT_LE(worst_downdated_product, 1e-14);
  std::printf("packed articulated inertia: step %.1e, sum %.1e, product %.1e, downdated product %.1e relative to the "
              "6x6 products\n", worst_step, worst_add, worst_product, worst_downdated_product);
}

// Rotations about a coordinate axis (packed3.hpp's AxisRotation, rotation_about_axis.hpp): their
// products with a vector, with a double-double vector and the articulated inertia's transform
// Xᵀ Iᴬ X against the same products with E's nine coefficients, E = coordinate_rotation(e_k, θ).
TEST(PackedPaths, AxisRotationsAgainstMatrices) {
  SKIP_WITHOUT_AVX2_FMA();
  using namespace sd::packed3;
  using Matrix6 = sd::Matrix6<double>;
  std::mt19937 rng(53);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst_vector = 0, worst_wide = 0, worst_step = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int axis = trial % 3, m = (axis + 1) % 3, n = (axis + 2) % 3;
    const double angle = 3 * u(rng), s = std::sin(angle), c = std::cos(angle);
    Eigen::Matrix3d E = Eigen::Matrix3d::Zero();  // rx, ry, rz (RBDA Table 2.2) with its exact 0 and 1
    E(axis, axis) = 1;
    E(m, m) = E(n, n) = c;
    E(m, n) = s;
    E(n, m) = -s;
    ASSERT_LE((E - sd::coordinate_rotation(Eigen::Vector3d(Eigen::Vector3d::Unit(axis)), angle)).norm(), 1e-15);
    const sd::PluckerTransform<double> X(E, Eigen::Vector3d(u(rng), u(rng), u(rng)));
    const Eigen::Vector3d y(u(rng), u(rng), u(rng));
    const Eigen::Vector3d Ey = X.E * y, Ety = X.E.transpose() * y;
    const PackedDoubleDouble wide_y{load3(y), make(u(rng), u(rng), u(rng)) * 1e-17};
    const sd::Matrix6<double> L = Matrix6::NullaryExpr([&] { return u(rng); });
    const Matrix6 Ia = L * L.transpose() + 0.1 * Matrix6::Identity(), start = Matrix6::Identity();
    const Matrix6 expected = start + X.toMotionMatrix().transpose() * Ia * X.toMotionMatrix();
    with_axis(axis, [&](auto k) {
      const AxisRotation<decltype(k)::value> rotation(s, c);
      worst_vector = std::max({worst_vector, (to_vector3(rotation.times(load3(y))) - Ey).norm() / y.norm(),
                               (to_vector3(rotation.transposed_times(load3(y))) - Ety).norm() / y.norm()});
      for (bool transposed : {false, true}) {
        const PackedDoubleDouble by_lanes = times(rotation, wide_y, transposed);
        const PackedDoubleDouble by_columns = transposed ? transposed_columns(X.E) * wide_y : columns(X.E) * wide_y;
        for (int lane = 0; lane < 3; ++lane) {  // the two products' difference, in double-double
          const long double difference = (static_cast<long double>(by_lanes.hi[lane]) - by_columns.hi[lane]) +
                                         (static_cast<long double>(by_lanes.lo[lane]) - by_columns.lo[lane]);
          worst_wide = std::max(worst_wide, static_cast<double>(std::fabs(difference)) / y.norm());
        }
      }
    });
    Matrix6 out = start;
    add_transformed(X.E, X.r, load_blocks(Ia), out, axis, s, c);
    worst_step = std::max(worst_step, (out - expected).norm() / expected.norm());
  }
  EXPECT_LE(worst_vector, 2.3e-16);
  EXPECT_LE(worst_wide, 1e-30);
  EXPECT_LE(worst_step, 1e-14);
  std::printf("rotations about an axis: vector %.1e, double-double %.1e, Xᵀ Iᴬ X %.1e relative to E's coefficients\n",
              worst_vector, worst_wide, worst_step);
}

// ^iX_λ's E = B0 + c B1 + s B2 from a revolute joint's terms (axis_operations.hpp's
// revolute_rotation_terms) against Rodrigues' formula times E_tree in float128, for general unit
// axes, rotated tree transforms and angles over several turns: in double-double (the residual
// RNEA's E, far below double's rounding, which a wrong term would exceed), rounded once to double
// (Data::up_rotation_terms), and the packed passes' E that the ABA leaves in data.X_up.
TEST(PackedPaths, RotationTermsAgainstRodriguesInFloat128) {
  SKIP_WITHOUT_AVX2_FMA();
  using sd::Quad;
  using DD = sd::DoubleDouble;
  std::mt19937 rng(61);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst_wide = 0, worst_rounded = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d a = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    const Eigen::Matrix3d E_tree = sd::coordinate_rotation(Eigen::Vector3d(Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized()), 3 * u(rng));
    const double angle = 10 * u(rng);
    const Quad s_quad = boost::multiprecision::sin(Quad(angle)), c_quad = boost::multiprecision::cos(Quad(angle));
    // Rodrigues' c 1 − s a× + (1 − c) a aᵀ (RBDA eq. 2.24) times E_tree, in float128.
    const Eigen::Matrix<Quad, 3, 1> a_quad = a.cast<Quad>();
    Eigen::Matrix<Quad, 3, 3> a_cross;
    a_cross << Quad(0), -a_quad.z(), a_quad.y(), a_quad.z(), Quad(0), -a_quad.x(), -a_quad.y(), a_quad.x(), Quad(0);
    const Eigen::Matrix<Quad, 3, 3> expected =
        (c_quad * Eigen::Matrix<Quad, 3, 3>::Identity() - s_quad * a_cross + (Quad(1) - c_quad) * a_quad * a_quad.transpose()) *
        E_tree.cast<Quad>();
    const sd::detail::RevoluteRotationTerms terms = sd::detail::revolute_rotation_terms(a, E_tree);
    const auto to_dd = [](const Quad& x) {  // the nearest double-double
      const double hi = static_cast<double>(x);
      return DD(hi, static_cast<double>(x - Quad(hi)));
    };
    const DD s = to_dd(s_quad), c = to_dd(c_quad);
    for (int k = 0; k < 3; ++k)
      for (int m = 0; m < 3; ++m) {
        const DD wide = terms.B[0][k][m] + c * terms.B[1][k][m] + s * terms.B[2][k][m];
        const double rounded = static_cast<double>(terms.B[0][k][m]) + static_cast<double>(c_quad) * static_cast<double>(terms.B[1][k][m]) +
                               static_cast<double>(s_quad) * static_cast<double>(terms.B[2][k][m]);
        worst_wide = std::max(worst_wide, std::fabs(static_cast<double>((Quad(wide.hi) + Quad(wide.lo)) - expected(m, k))));
        worst_rounded = std::max(worst_rounded, std::fabs(static_cast<double>(Quad(rounded) - expected(m, k))));
      }
  }
  EXPECT_LE(worst_wide, 1e-30);
  EXPECT_LE(worst_rounded, 8e-16);
  // The packed passes' E on a random chain (general axes, rotated tree transforms).
  std::mt19937 chain_rng(62);
  const sd::Model<double> model =
      sd::build_model_from_urdf_string(sd::synthetic::to_urdf("chain", sd::synthetic::random_chain(12, chain_rng)));
  sd::Data<double> data(model);
  double worst_packed = 0;
  for (int state = 0; state < 20; ++state) {
    const VectorXd q = sd_test::random_configuration(model, rng), zero = VectorXd::Zero(model.nv);
    sd::aba(model, data, q, zero, zero);
    for (int i = 1; i < model.nbodies(); ++i) {
      const sd::Joint<double>& j = model.joints[i];
      const Quad angle = Quad(q[j.idx_q]);
      const Eigen::Matrix<Quad, 3, 1> axis = j.axis.cast<Quad>();
      Eigen::Matrix<Quad, 3, 3> axis_cross;
      axis_cross << Quad(0), -axis.z(), axis.y(), axis.z(), Quad(0), -axis.x(), -axis.y(), axis.x(), Quad(0);
      const Quad s = boost::multiprecision::sin(angle), c = boost::multiprecision::cos(angle);
      const Eigen::Matrix<Quad, 3, 3> expected =
          (c * Eigen::Matrix<Quad, 3, 3>::Identity() - s * axis_cross + (Quad(1) - c) * axis * axis.transpose()) *
          model.X_tree[i].E.cast<Quad>();
      worst_packed = std::max(worst_packed, static_cast<double>((data.X_up[i].E.cast<Quad>() - expected).cwiseAbs().maxCoeff()));
    }
  }
  EXPECT_LE(worst_packed, 1e-15);
  std::printf("E from the rotation terms against Rodrigues' formula in float128: double-double %.1e, rounded terms %.1e, "
              "packed passes %.1e\n", worst_wide, worst_rounded, worst_packed);
}

// The ABA with the rotations' structure (Data::up_rotation_axis) on a tree whose revolute joints
// about x, y and z have tree transforms without rotation (and one with), fixed and floating:
// against the same call with the structure cleared (every E by its coefficients) and against the
// float128 reference; the refined forward dynamics, which solves on the same factorisation, too.
TEST(PackedPaths, AbaWithAxisRotations) {
  SKIP_WITHOUT_AVX2_FMA();
  const char* const urdf = R"(<robot name='axes'>
  <link name='base'><inertial><mass value='2.0'/><inertia ixx='0.05' ixy='0' ixz='0' iyy='0.06' iyz='0' izz='0.07'/></inertial></link>
  <link name='a'><inertial><mass value='1.2'/><origin xyz='0.1 0.02 -0.03'/><inertia ixx='0.02' ixy='0.001' ixz='-0.002' iyy='0.03' iyz='0.003' izz='0.025'/></inertial></link>
  <link name='b'><inertial><mass value='0.9'/><origin xyz='-0.04 0.1 0.01'/><inertia ixx='0.011' ixy='-0.001' ixz='0.0005' iyy='0.014' iyz='0.001' izz='0.009'/></inertial></link>
  <link name='c'><inertial><mass value='1.1'/><origin xyz='0.02 -0.03 0.12'/><inertia ixx='0.015' ixy='0.002' ixz='0' iyy='0.012' iyz='-0.001' izz='0.017'/></inertial></link>
  <link name='d'><inertial><mass value='0.7'/><origin xyz='0.05 0.05 0.05'/><inertia ixx='0.006' ixy='0' ixz='0.001' iyy='0.007' iyz='0' izz='0.008'/></inertial></link>
  <link name='e'><inertial><mass value='0.6'/><origin xyz='0 0.03 -0.02'/><inertia ixx='0.004' ixy='0.0005' ixz='0' iyy='0.005' iyz='0.0002' izz='0.006'/></inertial></link>
  <joint name='z1' type='continuous'><parent link='base'/><child link='a'/><origin xyz='0 0 0.1'/><axis xyz='0 0 1'/></joint>
  <joint name='y2' type='continuous'><parent link='a'/><child link='b'/><origin xyz='0.2 0 0'/><axis xyz='0 1 0'/></joint>
  <joint name='x3' type='continuous'><parent link='b'/><child link='c'/><origin xyz='0 0.15 0.05'/><axis xyz='1 0 0'/></joint>
  <joint name='y4' type='continuous'><parent link='c'/><child link='d'/><origin xyz='0.1 0 0' rpy='0.3 0 0'/><axis xyz='0 1 0'/></joint>
  <joint name='x5' type='continuous'><parent link='a'/><child link='e'/><origin xyz='0 -0.1 0'/><axis xyz='1 0 0'/></joint>
</robot>)";
  for (const bool floating : {false, true}) {
    sd::ModelBuildOptions options;
    options.floating_base = floating;
    const sd::Model<double> model = sd::build_model_from_urdf_string(urdf, options);
    sd::Data<double> data(model), by_coefficients(model);
    int about_axes = 0;
    for (int i = 1; i < model.nbodies(); ++i) about_axes += data.up_rotation_axis[i] >= 0;
    ASSERT_EQ(about_axes, 4) << "floating " << floating;
    std::fill(by_coefficients.up_rotation_axis.begin(), by_coefficients.up_rotation_axis.end(), -1);
    const sd::Model<sd::Quad> model_q = model.cast<sd::Quad>();
    sd::Data<sd::Quad> data_q(model_q);
    sd::RefinementWorkspace<double> refinement(model);
    std::mt19937 rng(59);
    double worst_difference = 0, worst_error = 0, worst_refined = 0;
    for (int k = 0; k < 200; ++k) {
      const VectorXd q = sd_test::random_configuration(model, rng), qd = sd_test::random_vector(model.nv, rng),
                     tau = sd_test::random_vector(model.nv, rng);
      const VectorXd qdd = sd::aba(model, data, q, qd, tau);
      const VectorXd expected = sd::aba(model, by_coefficients, q, qd, tau);
      const sd::VectorX<sd::Quad> reference = sd::aba(model_q, data_q, sd::to_quad(q), sd::to_quad(qd), sd::to_quad(tau));
      worst_difference = std::max(worst_difference, (qdd - expected).norm() / expected.norm());
      worst_error = std::max(worst_error, sd::relative_error_to(qdd, reference));
      const VectorXd refined = sd::aba_refined(model, data, refinement, q, qd, tau);
      worst_refined = std::max(worst_refined, sd::relative_error_to(refined, reference));
    }
    EXPECT_LE(worst_difference, 1e-14) << "floating " << floating;
    EXPECT_LE(worst_error, 1e-14) << "floating " << floating;
    EXPECT_LE(worst_refined, 1e-15) << "floating " << floating;
    std::printf("ABA with rotations about axes (%s): %.1e from the same by E's coefficients, %.1e from float128, "
                "refined %.1e\n", floating ? "floating" : "fixed", worst_difference, worst_error, worst_refined);
  }
}

// aba_refined's residual RNEA on the double model in packed double-double
// (algorithms/wide_residual_form.hpp) against the RNEA on Model<DoubleDouble> it replaces: ID(q, q̇, x)
// under gravity and M δ = ID(q, 0, δ) without, for double-double x and δ (low parts set), on the
// shared robots, every joint kind and a random chain. Both are exact to a few 2^-104 of the terms;
// their difference is far below double's rounding, which a wrong term would exceed. Models with
// joints of several coordinates stay on the wide model's RNEA.
TEST(PackedPaths, WideResidualFormAgainstWideModel) {
  SKIP_WITHOUT_AVX2_FMA();
  using DD = sd::DoubleDouble;
  std::mt19937 rng(53), chain_rng(54);
  std::vector<sd::Model<double>> models;
  for (const std::string& file : sd_test::robot_files()) models.push_back(sd::build_model_from_urdf_file(sd_test::robot_path(file)));
  models.push_back(sd::build_model_from_urdf_string(kEveryJointKindUrdf));
  models.push_back(sd::build_model_from_urdf_string(sd::synthetic::to_urdf("chain", sd::synthetic::random_chain(30, chain_rng))));
  const auto widened = [&](const VectorXd& x) {  // x plus low parts of about 1e-17 |x|
    sd::VectorX<DD> w(x.size());
    for (int k = 0; k < x.size(); ++k) w[k] = DD(x[k], 1e-17 * x[k] * (rng() % 1000) / 1000.0);
    return w;
  };
  const auto difference = [](const sd::VectorX<DD>& a, const sd::VectorX<DD>& b) {  // ‖a − b‖ / ‖b‖ in double
    double d = 0, n = 0;
    for (int k = 0; k < a.size(); ++k) {
      const double e = static_cast<double>(a[k] - b[k]), v = static_cast<double>(b[k]);
      d += e * e;
      n += v * v;
    }
    return std::sqrt(d / n);
  };
  double worst_id = 0, worst_product = 0;
  for (const sd::Model<double>& model : models) {
    sd::RefinementWorkspace<double> ws(model);
    ASSERT_TRUE(ws.wide_form_takes_model) << model.name;
    for (int s = 0; s < 20; ++s) {
      const VectorXd q = sd_test::random_configuration(model, rng);
      for (int k = 0; k < model.nq; ++k) ws.q_wide[k] = DD(q[k]);
      ws.qd_wide = widened(sd_test::random_vector(model.nv, rng));
      ws.x_wide = widened(sd_test::random_vector(model.nv, rng));
      ws.delta_wide = widened(sd_test::random_vector(model.nv, rng, 1e-6));
      const sd::VectorX<DD> id = sd::detail::wide_inverse_dynamics(model, ws, ws.qd_wide, ws.x_wide, true);
      const sd::VectorX<DD> id_wide_model = sd::detail::rnea_impl(ws.model_wide, ws.data_wide, ws.q_wide, ws.qd_wide, ws.x_wide,
                                                                  static_cast<const sd::ForceVector<DD>*>(nullptr));
      worst_id = std::max(worst_id, difference(id, id_wide_model));
      const sd::VectorX<DD> product = sd::detail::wide_inverse_dynamics(model, ws, ws.data_wide.zero_v, ws.delta_wide, false);
      const sd::VectorX<DD> product_wide_model = sd::detail::mass_matrix_times(ws.model_wide, ws.data_wide, ws.q_wide, ws.delta_wide);
      worst_product = std::max(worst_product, difference(product, product_wide_model));
    }
  }
  EXPECT_LE(worst_id, 1e-28);
  EXPECT_LE(worst_product, 1e-28);
  std::printf("wide residual form: ID %.1e, M x %.1e relative to the RNEA on the wide model\n", worst_id, worst_product);
  sd::ModelBuildOptions floating;
  floating.floating_base = true;
  EXPECT_FALSE(sd::RefinementWorkspace<double>(sd::build_model_from_urdf_file(sd_test::robot_path("solo12.urdf"), floating))
                   .wide_form_takes_model);
}
