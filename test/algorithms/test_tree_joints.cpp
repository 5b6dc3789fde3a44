// Planar and floating joints inside the tree (model/joints/planar.hpp, free.hpp), through every
// algorithm:
//  - a planar joint equals the same robot written with two prismatic joints and a revolute joint
//    between massless links (its definition), to 1e-13: RNEA, gravity torques, nonlinear effects,
//    CRBA, ABA, forward dynamics, refined forward dynamics, frame poses and Jacobians, energy;
//  - ID(FD(τ)) = τ to 1e-12, M symmetric positive definite, the batch RNEA equal to the RNEA;
//  - RNEA and CRBA within 4e-15 of the float128 reference (the floating joint directly, a planar
//    joint through its elementary equivalent);
//  - scenes keep such joints and refuse to lock them, naming the joint;
//  - a helical joint (a screw) against the float128 reference and the identities, and at pitch 0
//    a revolute joint.
// The robots: the Panda on a planar cart (normal z, and a tilted normal with an offset mount), a
// UR5 with a planar tool plate at its wrist (a moving parent, with a spinning tool below it), and
// a Panda holding an object on a floating joint (fixed and floating base).
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "spatial_dynamics/algorithms/aba_refined.hpp"
#include "spatial_dynamics/algorithms/rnea_batch.hpp"
#include "spatial_dynamics/reduction/reduce_model.hpp"
#include "spatial_dynamics/reference/high_precision.hpp"
#include "spatial_dynamics/reference/inverse_dynamics.hpp"
#include "spatial_dynamics/reference/mass_matrix.hpp"
#include "test_utils.hpp"

namespace {

namespace sd = spatial_dynamics;
namespace ref = spatial_dynamics::reference;
using Eigen::VectorXd;
using sd::Quad;
using sd_test::relative_error;

using sd_test::robot_text;
using sd_test::with_extra_elements;

std::string vec(const Eigen::Vector3d& v) {
  char text[96];
  std::snprintf(text, sizeof text, "%.17g %.17g %.17g", v.x(), v.y(), v.z());
  return text;
}

std::string massive_link(const std::string& name, double mass, const std::string& com) {
  return "<link name=\"" + name + "\"><inertial><origin xyz=\"" + com + "\" rpy=\"0.1 -0.2 0.3\"/><mass value=\"" +
         std::to_string(mass) +
         "\"/><inertia ixx=\"0.3\" ixy=\"0.01\" ixz=\"-0.02\" iyy=\"0.25\" iyz=\"0.015\" izz=\"0.4\"/></inertial></link>\n";
}

/// A planar joint `name` from `parent` to `child` (which the caller adds), or — with `elementary`
/// — the same motion as prismatic joints along e₁ and e₂ and a continuous joint about the normal,
/// between two massless links (e₁ and e₂ as the builder chose them for the planar joint).
struct PlanarSpec {
  std::string name, parent, child, origin, normal;
};
std::string planar_joint(const PlanarSpec& p) {
  return "<joint name=\"" + p.name + "\" type=\"planar\"><parent link=\"" + p.parent + "\"/><child link=\"" + p.child +
         "\"/>" + p.origin + "<axis xyz=\"" + p.normal + "\"/></joint>\n";
}
std::string elementary_joints(const PlanarSpec& p, const sd::Joint<double>& planar) {
  const std::string limit = "<limit lower=\"-10\" upper=\"10\" effort=\"100\" velocity=\"10\"/>";
  return "<link name=\"" + p.name + "_x_link\"/><link name=\"" + p.name + "_y_link\"/>\n" +  //
         "<joint name=\"" + p.name + "_x\" type=\"prismatic\"><parent link=\"" + p.parent + "\"/><child link=\"" +
         p.name + "_x_link\"/>" + p.origin + "<axis xyz=\"" + vec(planar.plane_x) + "\"/>" + limit + "</joint>\n" +
         "<joint name=\"" + p.name + "_y\" type=\"prismatic\"><parent link=\"" + p.name + "_x_link\"/><child link=\"" +
         p.name + "_y_link\"/><axis xyz=\"" + vec(planar.plane_y) + "\"/>" + limit + "</joint>\n" +
         "<joint name=\"" + p.name + "_yaw\" type=\"continuous\"><parent link=\"" + p.name + "_y_link\"/><child link=\"" +
         p.child + "\"/><axis xyz=\"" + vec(planar.axis) + "\"/></joint>\n";
}

struct PlanarCase {
  std::string name;
  sd::Model<double> planar, elementary;
  std::string tip;  // a frame below the planar joint
};

/// The robot `base_urdf` with the links `links` and the planar joint p, both ways.
PlanarCase planar_case(const std::string& name, const std::string& base_urdf, const std::string& links,
                       const PlanarSpec& p, const std::string& tip) {
  PlanarCase c{name, sd::build_model_from_urdf_string(with_extra_elements(base_urdf, links + planar_joint(p))), {}, tip};
  const sd::Joint<double>& j = c.planar.joints[c.planar.jointBody(p.name)];
  EXPECT_EQ(j.type, sd::JointType::Planar);
  c.elementary = sd::build_model_from_urdf_string(with_extra_elements(base_urdf, links + elementary_joints(p, j)));
  EXPECT_EQ(c.elementary.nv, c.planar.nv);
  return c;
}

/// The Panda on a cart: world —planar→ cart —fixed→ panda_link0.
std::string panda_on_cart(const std::string& panda, const std::string& mount_origin) {
  std::string urdf = with_extra_elements(panda, "<link name=\"world\"/>\n" + massive_link("cart", 25.0, "0.05 -0.02 0.1") +
                                           "<joint name=\"cart_mount\" type=\"fixed\"><parent link=\"cart\"/><child "
                                           "link=\"panda_link0\"/>" + mount_origin + "</joint>\n");
  return urdf;
}

std::vector<PlanarCase> planar_cases() {
  std::vector<PlanarCase> cases;
  const std::string panda = robot_text("panda.urdf");
  cases.push_back(planar_case("panda on a cart (normal z)", panda_on_cart(panda, "<origin xyz=\"0.1 0 0.3\"/>"), "",
                              {"cart_joint", "world", "cart", "", "0 0 1"}, "panda_hand"));
  cases.push_back(planar_case(
      "panda on a cart (tilted normal)", panda_on_cart(panda, "<origin xyz=\"0.1 -0.2 0.3\" rpy=\"0.2 0 -0.4\"/>"), "",
      {"cart_joint", "world", "cart", "<origin xyz=\"0.5 0.2 -0.1\" rpy=\"0.3 -0.1 0.7\"/>", "0.3 -0.4 0.5"},
      "panda_hand"));
  // ur5: wrist_3_link —planar (normal x)→ plate —revolute→ tool: a planar joint with a moving parent.
  const std::string tool = massive_link("plate", 0.8, "0.02 0.03 0.01") + massive_link("tool", 0.5, "0 0.01 0.08") +
                           "<joint name=\"tool_spin\" type=\"revolute\"><parent link=\"plate\"/><child link=\"tool\"/>"
                           "<origin xyz=\"0 0.05 0.1\" rpy=\"0.4 0 0\"/><axis xyz=\"0 0 1\"/><limit lower=\"-3\" "
                           "upper=\"3\" effort=\"10\" velocity=\"3\"/></joint>\n";
  cases.push_back(planar_case("ur5 with a planar tool plate", robot_text("ur5.urdf"), tool,
                              {"plate_joint", "wrist_3_link", "plate", "<origin xyz=\"0 0.1 0\" rpy=\"0 0.5 0\"/>", "1 0 0"},
                              "tool"));
  return cases;
}

/// The Panda holding an object on a floating joint below panda_link4 (fixed base, or floating).
sd::Model<double> panda_with_floating_object(bool floating_base) {
  const std::string object =
      massive_link("object", 1.5, "0.01 -0.03 0.05") +
      "<joint name=\"object_joint\" type=\"floating\"><parent link=\"panda_link4\"/><child link=\"object\"/>"
      "<origin xyz=\"0.1 0 0.05\" rpy=\"0 0.3 0\"/></joint>\n";
  sd::ModelBuildOptions options;
  options.floating_base = floating_base;
  return sd::build_model_from_urdf_string(with_extra_elements(robot_text("panda.urdf"), object), options);
}

struct State {
  VectorXd q, qd, qdd;
};
State random_state(const sd::Model<double>& model, std::mt19937& rng) {
  return {sd_test::random_configuration(model, rng), sd_test::random_vector(model.nv, rng),
          sd_test::random_vector(model.nv, rng)};
}

constexpr double kEquivalent = 1e-13;
constexpr double kIdentity = 1e-12;
constexpr double kReference = 4e-15;

}  // namespace

TEST(PlanarJoint, EqualsTwoPrismaticJointsAndARevoluteJointBetweenMasslessLinks) {
  unsigned seed = 1;
  for (const PlanarCase& c : planar_cases()) {
    sd::Data<double> dp(c.planar), de(c.elementary);
    sd::RefinementWorkspace<double> wp(c.planar), we(c.elementary);
    const int tip_p = c.planar.frameIndex(c.tip), tip_e = c.elementary.frameIndex(c.tip);
    std::mt19937 rng(seed++);
    double worst = 0;
    auto track = [&](const char* what, double error) {
      EXPECT_LE(error, kEquivalent) << c.name << ": " << what;
      worst = std::max(worst, error);
    };
    for (int s = 0; s < 30; ++s) {
      const State x = random_state(c.planar, rng);
      track("rnea", relative_error(VectorXd(sd::rnea(c.planar, dp, x.q, x.qd, x.qdd)),
                                   sd::rnea(c.elementary, de, x.q, x.qd, x.qdd)));
      track("gravity", relative_error(VectorXd(sd::gravity_torques(c.planar, dp, x.q)),
                                      sd::gravity_torques(c.elementary, de, x.q)));
      track("nonlinear effects", relative_error(VectorXd(sd::nonlinear_effects(c.planar, dp, x.q, x.qd)),
                                                sd::nonlinear_effects(c.elementary, de, x.q, x.qd)));
      track("crba", relative_error(Eigen::MatrixXd(sd::crba(c.planar, dp, x.q)), sd::crba(c.elementary, de, x.q)));
      const VectorXd tau = sd_test::random_vector(c.planar.nv, rng, 20.0);
      track("aba", relative_error(VectorXd(sd::aba(c.planar, dp, x.q, x.qd, tau)), sd::aba(c.elementary, de, x.q, x.qd, tau)));
      track("forward dynamics", relative_error(VectorXd(sd::forward_dynamics(c.planar, dp, x.q, x.qd, tau)),
                                               sd::forward_dynamics(c.elementary, de, x.q, x.qd, tau)));
      track("aba_refined", relative_error(VectorXd(sd::aba_refined(c.planar, dp, wp, x.q, x.qd, tau)),
                                          sd::aba_refined(c.elementary, de, we, x.q, x.qd, tau)));
      sd::forward_kinematics(c.planar, dp, x.q, x.qd);
      sd::forward_kinematics(c.elementary, de, x.q, x.qd);
      track("tip pose", relative_error(dp.X_frame_base[tip_p].toMotionMatrix(), de.X_frame_base[tip_e].toMotionMatrix()));
      track("tip Jacobian",
            relative_error(Eigen::MatrixXd(sd::frame_jacobian(c.planar, dp, x.q, tip_p, sd::ReferenceFrame::Local)),
                           sd::frame_jacobian(c.elementary, de, x.q, tip_e, sd::ReferenceFrame::Local)));
      const double T = sd::kinetic_energy(c.planar, dp, x.q, x.qd), T_e = sd::kinetic_energy(c.elementary, de, x.q, x.qd);
      track("kinetic energy", std::abs(T - T_e) / T_e);
    }
    std::printf("[planar = elementary joints] %-34s worst %.2g\n", c.name.c_str(), worst);
  }
}

TEST(TreeJoints, InverseOfForwardDynamicsIsTheEffortAndTheMassMatrixIsPositiveDefinite) {
  std::vector<std::pair<std::string, sd::Model<double>>> models;
  for (PlanarCase& c : planar_cases()) models.emplace_back(c.name, std::move(c.planar));
  models.emplace_back("panda with a floating object", panda_with_floating_object(false));
  models.emplace_back("floating panda with a floating object", panda_with_floating_object(true));
  unsigned seed = 11;
  for (const auto& [name, model] : models) {
    EXPECT_TRUE(model.has_multi_dof_tree_joints) << name;
    sd::Data<double> data(model);
    sd::RefinementWorkspace<double> ws(model);
    sd::BatchData<double> batch(model);
    std::mt19937 rng(seed++);
    double aba = 0, fd = 0, refined = 0;
    for (int s = 0; s < 50; ++s) {
      const State x = random_state(model, rng);
      const VectorXd tau = sd_test::random_vector(model.nv, rng, 20.0);
      const VectorXd qdd_aba = sd::aba(model, data, x.q, x.qd, tau);
      aba = std::max(aba, relative_error(VectorXd(sd::rnea(model, data, x.q, x.qd, qdd_aba)), tau));
      const VectorXd qdd_fd = sd::forward_dynamics(model, data, x.q, x.qd, tau);
      fd = std::max(fd, relative_error(VectorXd(sd::rnea(model, data, x.q, x.qd, qdd_fd)), tau));
      const VectorXd qdd_refined = sd::aba_refined(model, data, ws, x.q, x.qd, tau);
      refined = std::max(refined, relative_error(VectorXd(sd::rnea(model, data, x.q, x.qd, qdd_refined)), tau));
      const Eigen::MatrixXd M = sd::crba(model, data, x.q);
      EXPECT_EQ(M, M.transpose()) << name;
      EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues().minCoeff(), 0.0) << name;
      // M q̈ = ID(q, q̇, q̈) − ID(q, q̇, 0): the mass matrix and the RNEA agree.
      const VectorXd h = sd::nonlinear_effects(model, data, x.q, x.qd);
      EXPECT_LE(relative_error(VectorXd(M * x.qdd + h), VectorXd(sd::rnea(model, data, x.q, x.qd, x.qdd))), kIdentity)
          << name;
      // The batch (one state at a time for these models) gives the RNEA's numbers.
      Eigen::MatrixXd tau_batch(model.nv, 1);
      sd::rnea_batch(model, batch, x.q, x.qd, x.qdd, tau_batch);
      EXPECT_EQ(VectorXd(tau_batch.col(0)), VectorXd(sd::rnea(model, data, x.q, x.qd, x.qdd))) << name;
    }
    std::printf("[ID(FD(tau)) = tau] %-40s ABA %.2g  CRBA + Cholesky %.2g  refined %.2g\n", name.c_str(), aba, fd, refined);
    EXPECT_LE(aba, kIdentity) << name;
    EXPECT_LE(fd, kIdentity) << name;
    EXPECT_LE(refined, kIdentity) << name;
  }
}

TEST(TreeJoints, RneaAndCrbaWithin4e15OfTheFloat128Reference) {
  // The floating joint: the reference's own free-joint model. A planar joint: the reference on
  // its elementary equivalent (the reference's S is constant per joint, as spatial_v2's).
  struct Pair {
    std::string name;
    sd::Model<double> model, reference_model;
  };
  std::vector<Pair> pairs;
  for (PlanarCase& c : planar_cases()) pairs.push_back({c.name, c.planar, c.elementary});
  for (bool floating : {false, true}) {
    const sd::Model<double> m = panda_with_floating_object(floating);
    pairs.push_back({floating ? "floating panda with a floating object" : "panda with a floating object", m, m});
  }
  unsigned seed = 21;
  for (const Pair& p : pairs) {
    const sd::Model<Quad> model_q = p.reference_model.cast<Quad>();
    sd::Data<double> data(p.model);
    std::mt19937 rng(seed++);
    double rnea = 0, crba = 0;
    for (int s = 0; s < 50; ++s) {
      const State x = random_state(p.model, rng);
      const sd::VectorX<Quad> q = sd::to_quad(x.q), qd = sd::to_quad(x.qd), qdd = sd::to_quad(x.qdd);
      rnea = std::max(rnea, sd::relative_error_to(sd::rnea(p.model, data, x.q, x.qd, x.qdd),
                                                  ref::inverse_dynamics(model_q, q, qd, qdd)));
      crba = std::max(crba, sd::relative_error_to(sd::crba(p.model, data, x.q), ref::mass_matrix(model_q, q)));
    }
    std::printf("[against float128] %-40s RNEA %.2g  CRBA %.2g\n", p.name.c_str(), rnea, crba);
    EXPECT_LE(rnea, kReference) << p.name;
    EXPECT_LE(crba, kReference) << p.name;
  }
}

TEST(TreeJoints, ScenesKeepPlanarAndFloatingJointsAndRefuseToLockThem) {
  const sd::Model<double> cart = planar_cases()[0].planar;
  const sd::Model<double> reduced = sd::reduce_model(cart, sd::Scene{{"panda_joint1"}, {}});
  EXPECT_TRUE(reduced.hasJoint("cart_joint"));
  EXPECT_EQ(reduced.nv, 4);  // x, y, yaw and panda_joint1
  try {
    sd::reduce_model(cart, sd::Scene{{"panda_joint1"}, {{"cart_joint", 0.0}}});
    ADD_FAILURE() << "a planar joint was locked";
  } catch (const sd::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("'cart_joint'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cannot be locked"), std::string::npos) << e.what();
  }
  // The reduced model is the full one with the other joints at zero: its RNEA is the full one's
  // at those coordinates.
  sd::Data<double> full_data(cart), reduced_data(reduced);
  std::mt19937 rng(31);
  const State x = random_state(reduced, rng);
  VectorXd q = VectorXd::Zero(cart.nq), qd = VectorXd::Zero(cart.nv), qdd = VectorXd::Zero(cart.nv);
  q.head(4) = x.q;
  qd.head(4) = x.qd;
  qdd.head(4) = x.qdd;
  const VectorXd tau_full = sd::rnea(cart, full_data, q, qd, qdd);
  EXPECT_LE(relative_error(VectorXd(sd::rnea(reduced, reduced_data, x.q, x.qd, x.qdd)), VectorXd(tau_full.head(4))),
            kEquivalent);
}

// The helical joint (model/joints/helical.hpp): UR5 with its shoulder-lift and wrist-2 joints made
// screws (pitch 0.05 and −0.2 m/rad) through the RNEA and the CRBA against the float128 reference
// (its own screw model, X_J = rot(E(a, q)) xlt(h q a)), ID(FD(τ)) = τ through the ABA, the
// refined ABA and CRBA + Cholesky, and at pitch 0 the same numbers as the revolute joints.
TEST(HelicalJoint, ThroughEveryAlgorithmAgainstTheReferenceAndAtPitchZeroARevoluteJoint) {
  const sd::Model<double> ur5 = sd::build_model_from_urdf_string(robot_text("ur5.urdf"));
  const auto with_screws = [&](double pitch_lift, double pitch_wrist) {
    sd::Model<double> model = ur5;
    for (const auto& [name, pitch] : {std::pair<std::string, double>{"shoulder_lift_joint", pitch_lift},
                                      {"wrist_2_joint", pitch_wrist}}) {
      sd::Joint<double>& j = model.joints[model.jointBody(name)];
      j.type = sd::JointType::Helical;
      j.pitch = pitch;
    }
    model.finalize();
    return model;
  };
  const sd::Model<double> screws = with_screws(0.05, -0.2), flat = with_screws(0.0, 0.0);
  const sd::Model<Quad> screws_q = screws.cast<Quad>();
  sd::Data<double> data(screws), data_flat(flat), data_ur5(ur5);
  sd::RefinementWorkspace<double> ws(screws);
  std::mt19937 rng(31);
  double rnea = 0, crba = 0, aba = 0, refined = 0, fd = 0, revolute = 0;
  for (int s = 0; s < 50; ++s) {
    const State x = random_state(screws, rng);
    const VectorXd tau = sd_test::random_vector(screws.nv, rng, 20.0);
    const sd::VectorX<Quad> q = sd::to_quad(x.q), qd = sd::to_quad(x.qd), qdd = sd::to_quad(x.qdd);
    rnea = std::max(rnea, sd::relative_error_to(sd::rnea(screws, data, x.q, x.qd, x.qdd),
                                                ref::inverse_dynamics(screws_q, q, qd, qdd)));
    crba = std::max(crba, sd::relative_error_to(sd::crba(screws, data, x.q), ref::mass_matrix(screws_q, q)));
    const VectorXd qdd_aba = sd::aba(screws, data, x.q, x.qd, tau);
    aba = std::max(aba, relative_error(VectorXd(sd::rnea(screws, data, x.q, x.qd, qdd_aba)), tau));
    const VectorXd qdd_refined = sd::aba_refined(screws, data, ws, x.q, x.qd, tau);
    refined = std::max(refined, relative_error(VectorXd(sd::rnea(screws, data, x.q, x.qd, qdd_refined)), tau));
    const VectorXd qdd_fd = sd::forward_dynamics(screws, data, x.q, x.qd, tau);
    fd = std::max(fd, relative_error(VectorXd(sd::rnea(screws, data, x.q, x.qd, qdd_fd)), tau));
    revolute = std::max({revolute,
                         relative_error(VectorXd(sd::rnea(flat, data_flat, x.q, x.qd, x.qdd)),
                                        VectorXd(sd::rnea(ur5, data_ur5, x.q, x.qd, x.qdd))),
                         relative_error(Eigen::MatrixXd(sd::crba(flat, data_flat, x.q)),
                                        Eigen::MatrixXd(sd::crba(ur5, data_ur5, x.q))),
                         relative_error(VectorXd(sd::aba(flat, data_flat, x.q, x.qd, tau)),
                                        VectorXd(sd::aba(ur5, data_ur5, x.q, x.qd, tau)))});
  }
  std::printf("[helical] RNEA %.2g CRBA %.2g (float128); ID(FD) ABA %.2g refined %.2g CRBA %.2g; pitch 0 %.2g\n", rnea,
              crba, aba, refined, fd, revolute);
  EXPECT_LE(rnea, kReference);
  EXPECT_LE(crba, kReference);
  EXPECT_LE(aba, kIdentity);
  EXPECT_LE(refined, kIdentity);
  EXPECT_LE(fd, kIdentity);
  EXPECT_LE(revolute, kEquivalent);
}
