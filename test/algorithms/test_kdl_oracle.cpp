// Orocos KDL as an independent oracle: inverse dynamics (RNEA), gravity torques and the joint-space
// mass matrix of every shared robot, loaded fixed-base, must agree with KDL to a norm-wise relative
// error of at most 1e-12 at 100 random states per robot.
//
// KDL drops the inertia of the URDF root link (kdl_parser warns about it). For a fixed-base model
// the root link never moves, so its inertia does not affect any joint torque nor the mass matrix:
// the comparison is unaffected on every robot here, all of which are loaded fixed-base.
//
// KDL has no mass matrix for trees, so its mass matrix is rebuilt column by column from its tree
// inverse dynamics with gravity off: M e_i = ID(q, 0, e_i) − ID(q, 0, 0). On serial robots (and on
// the Panda arm with its fingers removed) KDL::ChainDynParam::JntToMass is compared as well.
//
// Joints are matched between the two libraries by name, never by position.

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <kdl/chain.hpp>
#include <kdl/chaindynparam.hpp>
#include <kdl/jntarray.hpp>
#include <kdl/jntspaceinertiamatrix.hpp>
#include <kdl/tree.hpp>
#include <kdl/treeidsolver_recursive_newton_euler.hpp>
#include <kdl_parser/kdl_parser.hpp>

#include "test_utils.hpp"

namespace {

namespace sd = spatial_dynamics;

constexpr double kTolerance = 1e-12;
constexpr int kStates = 100;

/// A deterministic seed per robot (FNV-1a of the file name), so every robot draws its own states.
std::uint32_t seed_for(const std::string& name) {
  std::uint32_t h = 2166136261u;
  for (const unsigned char c : name) {
    h ^= c;
    h *= 16777619u;
  }
  return h;
}

/// "1.234e-15": error figures for the one-line summaries and the XML report.
std::string sci(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.3e", x);
  return buffer;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Removes the first element `<tag name="name" ...> ... </tag>` from URDF text; returns false when
/// it is not found.
bool remove_element(std::string& xml, const std::string& tag, const std::string& name) {
  const std::string open = "<" + tag + " name=\"" + name + "\"";
  const std::string close = "</" + tag + ">";
  const std::size_t begin = xml.find(open);
  if (begin == std::string::npos) return false;
  const std::size_t end = xml.find(close, begin);
  if (end == std::string::npos) return false;
  xml.erase(begin, end + close.size() - begin);
  return true;
}

/// Index maps between our velocity coordinates and KDL's joint numbers, built from joint names.
struct JointMap {
  std::vector<int> kdl_of_ours;  // kdl_of_ours[our idx_v] = KDL q_nr (or chain joint number)
  int size() const { return static_cast<int>(kdl_of_ours.size()); }

  KDL::JntArray to_kdl(const Eigen::VectorXd& ours) const {
    KDL::JntArray out(size());
    for (int i = 0; i < size(); ++i) out(kdl_of_ours[i]) = ours[i];
    return out;
  }
  Eigen::VectorXd from_kdl(const KDL::JntArray& kdl) const {
    Eigen::VectorXd out(size());
    for (int i = 0; i < size(); ++i) out[i] = kdl(kdl_of_ours[i]);
    return out;
  }
  Eigen::MatrixXd from_kdl(const Eigen::MatrixXd& kdl) const {
    Eigen::MatrixXd out(size(), size());
    for (int i = 0; i < size(); ++i)
      for (int j = 0; j < size(); ++j) out(i, j) = kdl(kdl_of_ours[i], kdl_of_ours[j]);
    return out;
  }
};

/// Records, for the movable joint called `joint_name`, that our coordinate maps to KDL's `kdl_index`.
::testing::AssertionResult add_to_map(const sd::Model<double>& model, const std::string& joint_name, int kdl_index,
                                      JointMap& map) {
  if (!model.hasJoint(joint_name))
    return ::testing::AssertionFailure() << "KDL joint '" << joint_name << "' is not a joint of our model";
  const sd::Joint<double>& j = model.joints[model.jointBody(joint_name)];
  if (j.nv != 1) return ::testing::AssertionFailure() << "joint '" << joint_name << "' has nv = " << j.nv;
  if (kdl_index < 0 || kdl_index >= map.size())
    return ::testing::AssertionFailure() << "KDL index " << kdl_index << " of '" << joint_name << "' out of range";
  if (map.kdl_of_ours[j.idx_v] != -1)
    return ::testing::AssertionFailure() << "joint '" << joint_name << "' mapped twice";
  map.kdl_of_ours[j.idx_v] = kdl_index;
  return ::testing::AssertionSuccess();
}

::testing::AssertionResult map_is_complete(const JointMap& map) {
  std::vector<int> sorted = map.kdl_of_ours;
  std::sort(sorted.begin(), sorted.end());
  for (int i = 0; i < map.size(); ++i)
    if (sorted[i] != i) return ::testing::AssertionFailure() << "joint map is not a permutation";
  return ::testing::AssertionSuccess();
}

/// Our coordinates ↔ KDL tree q_nr, by joint name, skipping KDL's fixed (Joint::None) segments.
::testing::AssertionResult tree_joint_map(const sd::Model<double>& model, const KDL::Tree& tree, JointMap& map) {
  if (static_cast<int>(tree.getNrOfJoints()) != model.nv)
    return ::testing::AssertionFailure() << "KDL tree has " << tree.getNrOfJoints() << " joints, our model nv = "
                                         << model.nv;
  map.kdl_of_ours.assign(model.nv, -1);
  for (const auto& entry : tree.getSegments()) {
    const KDL::Segment& segment = GetTreeElementSegment(entry.second);
    const KDL::Joint& joint = segment.getJoint();
    if (joint.getType() == KDL::Joint::None) continue;
    const auto result = add_to_map(model, joint.getName(), static_cast<int>(GetTreeElementQNr(entry.second)), map);
    if (!result) return result;
  }
  return map_is_complete(map);
}

/// Our coordinates ↔ KDL chain joint numbers (root to tip, movable joints only), by joint name.
::testing::AssertionResult chain_joint_map(const sd::Model<double>& model, const KDL::Chain& chain, JointMap& map) {
  if (static_cast<int>(chain.getNrOfJoints()) != model.nv)
    return ::testing::AssertionFailure() << "KDL chain has " << chain.getNrOfJoints() << " joints, our model nv = "
                                         << model.nv;
  map.kdl_of_ours.assign(model.nv, -1);
  int k = 0;
  for (unsigned int s = 0; s < chain.getNrOfSegments(); ++s) {
    const KDL::Joint& joint = chain.getSegment(s).getJoint();
    if (joint.getType() == KDL::Joint::None) continue;
    const auto result = add_to_map(model, joint.getName(), k++, map);
    if (!result) return result;
  }
  return map_is_complete(map);
}

/// KDL's mass matrix of a tree in KDL's joint order: column i = ID(q, 0, e_i) − ID(q, 0, 0), no gravity.
::testing::AssertionResult kdl_tree_mass_matrix(KDL::TreeIdSolver_RNE& solver_no_gravity, const KDL::JntArray& q,
                                                Eigen::MatrixXd& M) {
  const unsigned int n = q.rows();
  const KDL::JntArray zero(n);
  KDL::JntArray tau0(n), tau(n), e(n);
  const KDL::WrenchMap no_wrenches;
  if (solver_no_gravity.CartToJnt(q, zero, zero, no_wrenches, tau0) < 0)
    return ::testing::AssertionFailure() << "KDL TreeIdSolver_RNE failed";
  M.resize(n, n);
  for (unsigned int i = 0; i < n; ++i) {
    SetToZero(e);
    e(i) = 1.0;
    if (solver_no_gravity.CartToJnt(q, zero, e, no_wrenches, tau) < 0)
      return ::testing::AssertionFailure() << "KDL TreeIdSolver_RNE failed";
    M.col(i) = tau.data - tau0.data;
  }
  return ::testing::AssertionSuccess();
}

/// Worst errors found over the random states, and where.
struct Worst {
  double error = 0.0;
  int state = -1;
  void update(double e, int k) {
    if (!(e <= error)) {  // also catches NaN
      error = e;
      state = k;
    }
  }
};

::testing::AssertionResult within_tolerance(const std::string& robot, const std::string& quantity, const Worst& w) {
  if (w.error <= kTolerance) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << robot << ": " << quantity << " differs from KDL, worst relative error "
                                       << w.error << " (state " << w.state << ") > " << kTolerance;
}

/// Tip links of the serial robots whose whole moving mass a single KDL chain carries.
/// ur5: ee_link and tool0 are massless siblings below wrist_3_link, so world → tool0 holds every
/// massive link.
const std::map<std::string, std::pair<std::string, std::string>>& serial_chains() {
  static const std::map<std::string, std::pair<std::string, std::string>> chains = {
      {"double_pendulum.urdf", {"base_link", "link2"}},
      {"ur5.urdf", {"world", "tool0"}},
  };
  return chains;
}

/// ChainDynParam::JntToMass on chain root → tip of `urdf_xml` vs our crba, at kStates random states.
void compare_chain_mass_matrix(const std::string& label, const std::string& urdf_xml, const std::string& root,
                               const std::string& tip, std::uint32_t seed, Worst& worst) {
  const sd::Model<double> model = sd::build_model_from_urdf_string(urdf_xml);
  sd::Data<double> data(model);
  KDL::Tree tree;
  ASSERT_TRUE(kdl_parser::treeFromString(urdf_xml, tree)) << label;
  KDL::Chain chain;
  ASSERT_TRUE(tree.getChain(root, tip, chain)) << label << ": no KDL chain " << root << " -> " << tip;
  JointMap map;
  ASSERT_TRUE(chain_joint_map(model, chain, map)) << label;
  KDL::ChainDynParam dyn(chain, KDL::Vector(model.gravity.x(), model.gravity.y(), model.gravity.z()));
  KDL::JntSpaceInertiaMatrix H(model.nv);
  std::mt19937 rng(seed);
  for (int k = 0; k < kStates; ++k) {
    const Eigen::VectorXd q = sd_test::random_configuration(model, rng);
    ASSERT_GE(dyn.JntToMass(map.to_kdl(q), H), 0) << label;
    const Eigen::MatrixXd M = sd::crba(model, data, q);
    worst.update(sd_test::relative_error(M, map.from_kdl(Eigen::MatrixXd(H.data))), k);
  }
}

class KdlOracle : public ::testing::TestWithParam<std::string> {};

TEST_P(KdlOracle, InverseDynamicsGravityAndMassMatrixAgreeWithKdl) {
  const std::string file = GetParam();
  const std::string path = sd_test::robot_path(file);
  const std::string robot = file.substr(0, file.rfind('.'));

  // Fixed base on every robot: KDL drops the root link inertia, which is irrelevant here (see top).
  const sd::Model<double> model = sd::build_model_from_urdf_file(path);
  ASSERT_FALSE(model.floating_base);
  ASSERT_EQ(model.nq, model.nv) << robot;
  sd::Data<double> data(model);

  KDL::Tree tree;
  ASSERT_TRUE(kdl_parser::treeFromFile(path, tree)) << robot << ": kdl_parser failed on " << path;
  JointMap map;
  ASSERT_TRUE(tree_joint_map(model, tree, map)) << robot;

  const Eigen::Vector3d& g = model.gravity;
  KDL::TreeIdSolver_RNE id_gravity(tree, KDL::Vector(g.x(), g.y(), g.z()));
  KDL::TreeIdSolver_RNE id_no_gravity(tree, KDL::Vector::Zero());
  const KDL::WrenchMap no_wrenches;
  const KDL::JntArray zero(model.nv);
  KDL::JntArray tau_kdl(model.nv);
  Eigen::MatrixXd M_kdl;

  Worst rnea_worst, gravity_worst, mass_worst;
  double asymmetry = 0.0;
  double q_spread = 0.0;  // the states must really differ in q, not only in q̇ and q̈
  Eigen::VectorXd q_first;
  std::mt19937 rng(seed_for(file));
  for (int k = 0; k < kStates; ++k) {
    const Eigen::VectorXd q = sd_test::random_configuration(model, rng);
    const Eigen::VectorXd qd = sd_test::random_vector(model.nv, rng, 1.0);
    const Eigen::VectorXd qdd = sd_test::random_vector(model.nv, rng, 1.0);
    const KDL::JntArray q_kdl = map.to_kdl(q);
    if (k == 0) q_first = q;
    q_spread = std::max(q_spread, (q - q_first).cwiseAbs().maxCoeff());

    // Inverse dynamics under gravity.
    ASSERT_GE(id_gravity.CartToJnt(q_kdl, map.to_kdl(qd), map.to_kdl(qdd), no_wrenches, tau_kdl), 0) << robot;
    const Eigen::VectorXd tau = sd::rnea(model, data, q, qd, qdd);
    rnea_worst.update(sd_test::relative_error(tau, map.from_kdl(tau_kdl)), k);

    // Gravity torques g(q) = ID(q, 0, 0).
    ASSERT_GE(id_gravity.CartToJnt(q_kdl, zero, zero, no_wrenches, tau_kdl), 0) << robot;
    const Eigen::VectorXd tau_g = sd::gravity_torques(model, data, q);
    gravity_worst.update(sd_test::relative_error(tau_g, map.from_kdl(tau_kdl)), k);

    // Mass matrix, column by column from KDL's tree inverse dynamics without gravity.
    ASSERT_TRUE(kdl_tree_mass_matrix(id_no_gravity, q_kdl, M_kdl)) << robot;
    const Eigen::MatrixXd M = sd::crba(model, data, q);
    mass_worst.update(sd_test::relative_error(M, map.from_kdl(M_kdl)), k);

    // crba fills both triangles: the matrix must be exactly symmetric.
    asymmetry = std::max(asymmetry, (M - M.transpose()).cwiseAbs().maxCoeff());
  }

  // Serial robots: also KDL's own mass matrix (ChainDynParam) on the chain that carries every link.
  Worst chain_worst;
  const auto chain = serial_chains().find(file);
  const bool serial = chain != serial_chains().end();
  if (serial) {
    compare_chain_mass_matrix(robot, read_text(path), chain->second.first, chain->second.second, seed_for(file) + 1u,
                              chain_worst);
    if (HasFatalFailure()) return;
  }

  std::printf("[kdl_oracle] %-16s nv=%2d  max rel. error over %d states: rnea %.3e  gravity %.3e  "
              "M(tree columns) %.3e  M(ChainDynParam) %s  max|M-M^T| %.1e\n",
              robot.c_str(), model.nv, kStates, rnea_worst.error, gravity_worst.error, mass_worst.error,
              serial ? sci(chain_worst.error).c_str() : "n/a      ", asymmetry);
  RecordProperty("max_rel_error_rnea", sci(rnea_worst.error));
  RecordProperty("max_rel_error_gravity", sci(gravity_worst.error));
  RecordProperty("max_rel_error_mass_matrix", sci(mass_worst.error));
  if (serial) RecordProperty("max_rel_error_mass_matrix_chain", sci(chain_worst.error));

  EXPECT_GT(q_spread, 0.1) << robot << ": the random configurations barely vary";
  EXPECT_TRUE(within_tolerance(robot, "RNEA torque", rnea_worst));
  EXPECT_TRUE(within_tolerance(robot, "gravity torque", gravity_worst));
  EXPECT_TRUE(within_tolerance(robot, "mass matrix (KDL tree ID columns)", mass_worst));
  if (serial) {
    EXPECT_TRUE(within_tolerance(robot, "mass matrix (KDL ChainDynParam)", chain_worst));
  }
  EXPECT_EQ(asymmetry, 0.0) << robot << ": crba mass matrix is not exactly symmetric, max |M - M^T| = " << asymmetry;
}

INSTANTIATE_TEST_SUITE_P(SharedRobots, KdlOracle, ::testing::ValuesIn(sd_test::robot_files()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param.substr(0, info.param.rfind('.'));
                           std::replace_if(
                               name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); },
                               '_');
                           return name;
                         });

// The Panda arm alone: both fingers (prismatic, 15 g each) hang off panda_hand, so no single KDL
// chain carries them. With the two finger links and joints removed from the URDF, the chain
// panda_link0 → panda_hand holds every remaining link and ChainDynParam gives the full 7×7 matrix.
TEST(KdlOracleChain, PandaArmMassMatrixAgreesWithChainDynParam) {
  std::string xml = read_text(sd_test::robot_path("panda.urdf"));
  ASSERT_TRUE(remove_element(xml, "joint", "panda_finger_joint1"));
  ASSERT_TRUE(remove_element(xml, "joint", "panda_finger_joint2"));
  ASSERT_TRUE(remove_element(xml, "link", "panda_leftfinger"));
  ASSERT_TRUE(remove_element(xml, "link", "panda_rightfinger"));
  ASSERT_EQ(sd::build_model_from_urdf_string(xml).nv, 7);

  Worst worst;
  compare_chain_mass_matrix("panda_arm", xml, "panda_link0", "panda_hand", seed_for("panda_arm"), worst);
  if (HasFatalFailure()) return;
  std::printf("[kdl_oracle] %-16s nv= 7  max rel. error over %d states: M(ChainDynParam) %.3e\n", "panda_arm",
              kStates, worst.error);
  RecordProperty("max_rel_error_mass_matrix_chain", sci(worst.error));
  EXPECT_TRUE(within_tolerance("panda_arm", "mass matrix (KDL ChainDynParam)", worst));
}

}  // namespace
