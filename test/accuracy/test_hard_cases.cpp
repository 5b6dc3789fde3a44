// The hard-case suite: generated models that break naive code, each checked against the float128
// reference (reference/: RNEA, CRBA and ABA on 6×6 matrices, on the same model and inputs,
// converted exactly). For every case the norm-wise relative
// errors of RNEA, ABA and CRBA must stay below a bound of the form c·κ·ε, and every output must be
// finite. The table is printed; README.md ("Hard cases") summarises it.
//
// The bounds (ε = 2⁻⁵², d = depth of the tree).
// RNEA and CRBA solve nothing: each outward step of the recursions (v = X v_λ + S q̇, a = X a_λ + …)
// and each inward step (f_λ += Xᵀ f, F = Xᵀ F) is a fixed sequence of 3-term dot and cross
// products, adding at most about 5ε of relative error per body and pass in the worst case (γ₃
// for the products plus the additions); two passes along a path of depth d add ≤ 10·d·ε. So
// their condition number is κ = d·A, with A = ‖|terms|‖/‖result‖ the cancellation factor (the
// gravity, velocity and acceleration parts of τ added in magnitude, over ‖τ‖; 1 for M), and
// c = 10.
// ABA solves M q̈ = τ − h: by the perturbation theory of linear systems its error is ≤ κ(M) times
// its norm-wise backward error, whose first-order term is the rounding of τ − h: ε·G with
// G = (‖τ‖ + ‖h‖)/‖M q̈‖ (gravity or velocity terms large against the accelerations they leave).
// So ABA gets c·G·κ(M)·ε with c = 1; the per-body rounding of the recursions would add a factor
// up to d in the worst case, but that needs errors aligned with M's smallest eigenvector, which
// random states do not produce (the measured ratio error/(G κ ε) stays ≤ 0.05 on every case).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "spatial_dynamics/reference/forward_dynamics.hpp"
#include "spatial_dynamics/reference/high_precision.hpp"
#include "spatial_dynamics/reference/inverse_dynamics.hpp"
#include "spatial_dynamics/reference/mass_matrix.hpp"
#include "spatial_dynamics/synthetic/random_robot.hpp"
#include "test_utils.hpp"

namespace sd = spatial_dynamics;
namespace syn = spatial_dynamics::synthetic;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPerBodyStep = 10.0;  // c for RNEA and CRBA: ≤ 5ε per body and pass, two passes
constexpr double kSolve = 1.0;         // c for ABA: the rounding of τ − h (see above)

struct CaseResult {
  std::string name;
  int nv = 0, depth = 0;
  double kappa = 0, cancellation = 1, growth = 1;  // κ(M), A, G (maxima over the states)
  double rnea = 0, aba = 0, crba = 0;              // max relative errors
  double rnea_bound = 0, aba_bound = 0, crba_bound = 0;
  bool finite = true;
};

std::vector<CaseResult>& table() {
  static std::vector<CaseResult> rows;
  return rows;
}

int depth_of(const sd::Model<double>& model) {
  std::vector<int> depth(model.nbodies(), 0);
  int d = 0;
  for (int i = 1; i < model.nbodies(); ++i) d = std::max(d, depth[i] = depth[model.parent[i]] + 1);
  return d;
}

/// 2-norm condition number of the symmetric positive definite M, from its eigenvalues in long
/// double (M taken from the float128 reference, so κ up to ~1e17 is resolved).
double condition_number(const sd::MatrixX<sd::Quad>& M) {
  const Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic> Ml = M.cast<long double>();
  const auto lambda = Eigen::SelfAdjointEigenSolver<decltype(Ml)>(Ml, Eigen::EigenvaluesOnly).eigenvalues();
  return static_cast<double>(lambda.maxCoeff() / lambda.minCoeff());
}

/// RNEA with every product replaced by its absolute value: the size of what the result sums.
sd::VectorX<sd::Quad> absolute_torques(const sd::Model<sd::Quad>& model, const sd::VectorX<sd::Quad>& q,
                                       const sd::VectorX<sd::Quad>& qd, const sd::VectorX<sd::Quad>& qdd) {
  // Gravity, velocity and acceleration contributions taken separately and added in magnitude:
  // |ID(q, 0, 0)| + |ID(q, q̇, 0) − ID(q, 0, 0)| + |ID(q, 0, q̈) − ID(q, 0, 0)|, a cheap stand-in for
  // the sum of absolute terms that is exact when only one of them is large.
  const sd::VectorX<sd::Quad> zero = sd::VectorX<sd::Quad>::Zero(model.nv);
  const sd::VectorX<sd::Quad> g = sd::reference::gravity_torques(model, q);
  const sd::VectorX<sd::Quad> hv = sd::reference::nonlinear_effects(model, q, qd) - g;
  const sd::VectorX<sd::Quad> Ma = sd::reference::inverse_dynamics(model, q, zero, qdd) - g;
  return g.cwiseAbs() + hv.cwiseAbs() + Ma.cwiseAbs();
}

struct Sampling {
  int states = 10;
  double qd_scale = 1.0;
  bool forward_dynamics = true;
};

CaseResult run_case(const std::string& name, const sd::Model<double>& model, const Sampling& sampling, unsigned seed) {
  const auto start = std::chrono::steady_clock::now();
  CaseResult r;
  r.name = name;
  r.nv = model.nv;
  r.depth = depth_of(model);
  sd::Data<double> data(model);
  const sd::Model<sd::Quad> ref_model = model.cast<sd::Quad>();
  std::mt19937 rng(seed);
  for (int s = 0; s < sampling.states; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const VectorXd qd = sd_test::random_vector(model.nv, rng, sampling.qd_scale);
    const VectorXd qdd = sd_test::random_vector(model.nv, rng);
    const sd::VectorX<sd::Quad> Q = sd::to_quad(q), QD = sd::to_quad(qd), QDD = sd::to_quad(qdd);

    const VectorXd tau = sd::rnea(model, data, q, qd, qdd);
    const sd::VectorX<sd::Quad> tau_ref = sd::reference::inverse_dynamics(ref_model, Q, QD, QDD);
    r.finite = r.finite && tau.allFinite();
    r.rnea = std::max(r.rnea, sd::relative_error_to(tau, tau_ref));
    const double A = static_cast<double>(absolute_torques(ref_model, Q, QD, QDD).norm() / tau_ref.norm());
    r.cancellation = std::max(r.cancellation, A);

    const MatrixXd M = sd::crba(model, data, q);
    const sd::MatrixX<sd::Quad> M_ref = sd::reference::mass_matrix(ref_model, Q);
    r.finite = r.finite && M.allFinite();
    r.crba = std::max(r.crba, sd::relative_error_to(M, M_ref));

    if (sampling.forward_dynamics) {
      if (s == 0) r.kappa = condition_number(M_ref);
      const VectorXd qdd_fd = sd::aba(model, data, q, qd, tau);
      const sd::VectorX<sd::Quad> qdd_ref = sd::reference::forward_dynamics(ref_model, Q, QD, sd::to_quad(tau));
      r.finite = r.finite && qdd_fd.allFinite();
      r.aba = std::max(r.aba, sd::relative_error_to(qdd_fd, qdd_ref));
      const sd::VectorX<sd::Quad> h = sd::reference::nonlinear_effects(ref_model, Q, QD);
      const double G = static_cast<double>((sd::to_quad(tau).norm() + h.norm()) / (M_ref * qdd_ref).norm());
      r.growth = std::max(r.growth, G);
    }
  }
  r.rnea_bound = kPerBodyStep * r.depth * r.cancellation * kEps;
  r.crba_bound = kPerBodyStep * r.depth * kEps;
  r.aba_bound = kSolve * r.growth * r.kappa * kEps;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[hard case] %-38s nv %4d  d %4d  kappa %8.2g  A %7.2g  G %7.2g  RNEA %8.2g (bound %8.2g)  "
              "ABA %8.2g (bound %8.2g)  CRBA %8.2g (bound %8.2g)  %.1f s\n",
              name.c_str(), r.nv, r.depth, r.kappa, r.cancellation, r.growth, r.rnea, r.rnea_bound, r.aba, r.aba_bound,
              r.crba, r.crba_bound, seconds);
  table().push_back(r);
  return r;
}

void expect_within_bounds(const CaseResult& r, bool forward_dynamics = true) {
  EXPECT_TRUE(r.finite) << r.name << ": non-finite output";
  EXPECT_LE(r.rnea, r.rnea_bound) << r.name << ": RNEA";
  EXPECT_LE(r.crba, r.crba_bound) << r.name << ": CRBA";
  if (forward_dynamics) {
    EXPECT_LE(r.aba, r.aba_bound) << r.name << ": ABA";
    EXPECT_GT(r.aba, 0.0) << r.name << ": ABA was not measured";
  }
}

sd::Model<double> from_links(const std::vector<syn::Link>& links, bool floating = false) {
  sd::ModelBuildOptions options;
  options.floating_base = floating;
  return sd::build_model_from_urdf_string(syn::to_urdf("hard_case", links), options);
}

/// Lengths × L, masses × m, inertias × m L².
void scale(std::vector<syn::Link>& links, double L, double m) {
  for (syn::Link& l : links) {
    l.joint_xyz *= L;
    l.com *= L;
    l.mass *= m;
    l.inertia *= m * L * L;
  }
}

}  // namespace

// 1. A 1000-body chain with random axes.
TEST(HardCases, ThousandBodyChainWithRandomAxes) {
  std::mt19937 rng(1000);
  Sampling sampling;
  sampling.states = 2;  // the float128 CRBA of 1000 bodies takes about a second
  expect_within_bounds(run_case("1000-body chain, random axes", from_links(syn::random_chain(1000, rng)), sampling, 1));
}

// 2. Masses and inertias spanning 1e-6 to 1e3 kg along one chain (log-uniform, random order).
TEST(HardCases, MassesSpanningNineDecades) {
  std::mt19937 rng(2);
  syn::RandomOptions options;
  options.mass_min = 1e-6;
  options.mass_max = 1e3;
  options.log_uniform_mass = true;
  std::vector<syn::Link> links = syn::random_chain(40, rng, options);
  expect_within_bounds(run_case("masses 1e-6..1e3 kg, 40 bodies", from_links(links), {}, 2));
}

// 3. Massless dummy links between consecutive revolute joints (a wrist), and a massless leaf.
TEST(HardCases, MasslessIntermediateLinksAndLeaf) {
  std::mt19937 rng(3);
  std::vector<syn::Link> links = syn::random_chain(9, rng);
  for (int i : {2, 4, 6}) {  // links 2, 4, 6 are massless; the next joint sits at the same origin
    links[i].mass = 0.0;
    links[i + 1].joint_xyz.setZero();
  }
  expect_within_bounds(run_case("massless intermediate links", from_links(links), {}, 3));

  links.push_back(syn::random_link(9, rng));
  links.back().mass = 0.0;  // joint10 carries a massless leaf: D = Sᵀ Iᴬ S = 0
  const sd::Model<double> model = from_links(links);
  Sampling no_fd;
  no_fd.forward_dynamics = false;
  expect_within_bounds(run_case("massless leaf (ID and M only)", model, no_fd, 4), false);
  sd::Data<double> data(model);
  const VectorXd zero = VectorXd::Zero(model.nv);
  try {
    const VectorXd qdd = sd::aba(model, data, zero, zero, zero);
    FAIL() << "forward dynamics of a massless leaf returned " << qdd.transpose() << " instead of failing";
  } catch (const std::domain_error& e) {
    EXPECT_NE(std::string(e.what()).find("joint 'joint10'"), std::string::npos) << e.what();
  }
}

// 4. Nearly parallel and nearly coincident joint axes: pairs of joints 1e-4 rad and 1e-6 m apart,
// joined by a massless link (a wrist): M is nearly singular, κ grows as 1/angle².
TEST(HardCases, NearlyParallelNearlyCoincidentAxes) {
  std::mt19937 rng(4);
  std::vector<syn::Link> links = syn::random_chain(12, rng);
  for (int i = 2; i <= 12; i += 2) {
    links[i - 1].mass = 0.0;       // between the two joints of a pair: a massless wrist link
    links[i].joint_rpy.setZero();  // joint i's frame is link i−1's frame, which turns about joint i−1's axis
    links[i].joint_xyz = 1e-6 * syn::random_unit_vector(rng);
    const Eigen::Vector3d tilt = links[i - 1].axis.cross(syn::random_unit_vector(rng)).normalized();
    links[i].axis = Eigen::AngleAxisd(1e-4, tilt) * links[i - 1].axis;
  }
  expect_within_bounds(run_case("nearly parallel, coincident axes", from_links(links), {}, 5));
}

// 5. Joint velocities up to 1e3 rad/s.
TEST(HardCases, JointVelocitiesUpToAThousandRadPerSecond) {
  std::mt19937 rng(5);
  Sampling sampling;
  sampling.qd_scale = 1e3;
  expect_within_bounds(run_case("velocities up to 1e3 rad/s", from_links(syn::random_chain(20, rng)), sampling, 6));
}

// 6. A robot scaled to millimetres and milligrams, and to tonnes and tens of metres.
TEST(HardCases, ScaledToMillimetresAndToTonnes) {
  std::mt19937 rng(6);
  const std::vector<syn::Link> base = syn::random_chain(20, rng);
  std::vector<syn::Link> small = base, large = base;
  scale(small, 1e-3, 1e-6);  // 5–15 mm links of 0.5–2 mg
  scale(large, 1e2, 1e3);    // 5–15 m links of 0.5–2 t
  expect_within_bounds(run_case("scaled to mm and mg", from_links(small), {}, 7));
  expect_within_bounds(run_case("scaled to tonnes and tens of metres", from_links(large), {}, 8));
}

// 7. A floating base 1e4 times heavier than its limbs, and the reverse.
TEST(HardCases, FloatingBaseMuchHeavierOrLighterThanLimbs) {
  std::mt19937 rng(7);
  const std::vector<syn::Link> tree = syn::random_tree(12, rng);
  std::vector<syn::Link> heavy = tree, light = tree;
  heavy[0].mass = 1e4;  // limbs weigh 0.5–2 kg
  heavy[0].inertia = syn::box_inertia(1e4, 0.5, 0.4, 0.3, Eigen::Matrix3d::Identity());
  for (std::size_t i = 1; i < light.size(); ++i) {
    light[i].mass *= 1e4;
    light[i].inertia *= 1e4;
  }
  light[0].mass = 1.0;  // limbs weigh 5–20 t
  expect_within_bounds(run_case("floating base 1e4 x heavier than limbs", from_links(heavy, true), {}, 9));
  expect_within_bounds(run_case("floating base 1e4 x lighter than limbs", from_links(light, true), {}, 10));
}

TEST(HardCases, PrintTable) {
  std::printf("\n| case | nv | d | κ(M) | A | G | RNEA (bound) | ABA (bound) | CRBA (bound) |\n"
              "|---|---|---|---|---|---|---|---|---|\n");
  for (const CaseResult& r : table()) {
    char kappa[32] = "singular", growth[32] = "—", aba[64] = "throws, naming the joint";
    if (r.kappa > 0) {
      std::snprintf(kappa, sizeof kappa, "%.1e", r.kappa);
      std::snprintf(growth, sizeof growth, "%.2g", r.growth);
      std::snprintf(aba, sizeof aba, "%.1e (%.0e)", r.aba, r.aba_bound);
    }
    std::printf("| %s | %d | %d | %s | %.2g | %s | %.1e (%.0e) | %s | %.1e (%.0e) |\n", r.name.c_str(), r.nv, r.depth,
                kappa, r.cancellation, growth, r.rnea, r.rnea_bound, aba, r.crba, r.crba_bound);
  }
  SUCCEED();
}
