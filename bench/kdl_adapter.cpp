#include "kdl_adapter.hpp"

#include <kdl/chaindynparam.hpp>
#include <kdl/chainfdsolver_recursive_newton_euler.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>
#include <kdl/tree.hpp>
#include <kdl/treefksolverpos_recursive.hpp>
#include <kdl/treeidsolver_recursive_newton_euler.hpp>
#include <kdl_parser/kdl_parser.hpp>
#include <set>

namespace bench {
namespace {

using SegmentIt = KDL::SegmentMap::const_iterator;

/// Inertia of the segment behind `it` and of everything below it, in the segment's tip frame.
/// Only called on subtrees without movable joints, whose poses do not depend on q.
KDL::RigidBodyInertia subtree_inertia(SegmentIt it) {
  KDL::RigidBodyInertia I = GetTreeElementSegment(it->second).getInertia();
  for (SegmentIt child : GetTreeElementChildren(it->second))
    I = I + GetTreeElementSegment(child->second).pose(0.0) * subtree_inertia(child);
  return I;
}

/// Whether the tree's movable joints lie on one root-to-tip path; if so, `chain` is that path
/// (getChain(root, deepest movable segment)) with the inertia of every fixed side branch (and of
/// the fixed links beyond the tip) folded into the path segment it hangs from, so the chain has
/// the tree's dynamics. The fixed links hanging from the root carry no dynamics with a fixed base.
bool serial_chain(const KDL::Tree& tree, KDL::Chain& chain) {
  const KDL::SegmentMap& segments = tree.getSegments();
  const SegmentIt root = tree.getRootSegment();
  auto movable = [](SegmentIt it) { return GetTreeElementSegment(it->second).getJoint().getType() != KDL::Joint::None; };
  auto movable_depth = [&](SegmentIt it) {
    int d = 0;
    for (; it != root; it = GetTreeElementParent(it->second)) d += movable(it);
    return d;
  };
  SegmentIt tip = root;
  int tip_depth = 0, count = 0;
  for (SegmentIt it = segments.begin(); it != segments.end(); ++it) {
    if (!movable(it)) continue;
    ++count;
    const int d = movable_depth(it);
    if (d > tip_depth) tip = it, tip_depth = d;
  }
  if (tip_depth != count || count == 0) return false;  // some movable joint is off the deepest path
  std::set<std::string> on_path;
  for (SegmentIt it = tip; it != root; it = GetTreeElementParent(it->second)) on_path.insert(it->first);
  KDL::Chain path;
  if (!tree.getChain(root->first, tip->first, path)) return false;
  chain = KDL::Chain();
  for (const KDL::Segment& segment : path.segments) {
    const SegmentIt it = segments.find(segment.getName());
    KDL::RigidBodyInertia I = segment.getInertia();
    for (SegmentIt child : GetTreeElementChildren(it->second))
      if (!on_path.count(child->first)) I = I + GetTreeElementSegment(child->second).pose(0.0) * subtree_inertia(child);
    chain.addSegment(KDL::Segment(segment.getName(), segment.getJoint(), segment.getFrameToTip(), I));
  }
  return true;
}

class KdlAdapter : public Adapter {
 public:
  KdlAdapter(const spatial_dynamics::Model<double>& model, KDL::Tree tree)
      : model_(model), tree_(std::move(tree)), gravity_(model.gravity.x(), model.gravity.y(), model.gravity.z()) {
    is_chain_ = serial_chain(tree_, chain_);
    if (is_chain_) {
      int index = 0;
      for (const KDL::Segment& segment : chain_.segments)
        if (segment.getJoint().getType() != KDL::Joint::None) kdl_index_[segment.getJoint().getName()] = index++;
      id_chain_ = std::make_unique<KDL::ChainIdSolver_RNE>(chain_, gravity_);
      dyn_ = std::make_unique<KDL::ChainDynParam>(chain_, gravity_);
      fd_ = std::make_unique<KDL::ChainFdSolver_RNE>(chain_, gravity_);
      fk_chain_ = std::make_unique<KDL::ChainFkSolverPos_recursive>(chain_);
      wrenches_.assign(chain_.getNrOfSegments(), KDL::Wrench::Zero());
      frames_.resize(chain_.getNrOfSegments());
      for (unsigned s = 0; s < chain_.getNrOfSegments(); ++s) segment_index_[chain_.getSegment(s).getName()] = s;
    } else {
      for (const auto& entry : tree_.getSegments()) {
        const KDL::Joint& joint = GetTreeElementSegment(entry.second).getJoint();
        if (joint.getType() != KDL::Joint::None) kdl_index_[joint.getName()] = GetTreeElementQNr(entry.second);
      }
      id_tree_ = std::make_unique<KDL::TreeIdSolver_RNE>(tree_, gravity_);
      fk_tree_ = std::make_unique<KDL::TreeFkSolverPos_recursive>(tree_);
    }
    for (int i = 1; i < model.nbodies(); ++i) ours_to_kdl_.push_back(kdl_index_.at(model.joint_names[i]));
    const unsigned n = tree_.getNrOfJoints();
    out_.resize(n);
    M_.resize(n);
  }

  std::string library() const override { return "kdl"; }
  bool supports(Algorithm a) const override {
    switch (a) {
      case Algorithm::Rnea:
      case Algorithm::Gravity:
      case Algorithm::Fk: return true;
      case Algorithm::Crba:
      case Algorithm::CrbaCholesky: return is_chain_;
      default: return false;
    }
  }
  std::string method(Algorithm a) const override {
    switch (a) {
      case Algorithm::Rnea: return is_chain_ ? "ChainIdSolver_RNE" : "TreeIdSolver_RNE";
      case Algorithm::Gravity: return is_chain_ ? "ChainDynParam::JntToGravity" : "TreeIdSolver_RNE (q̇ = q̈ = 0)";
      case Algorithm::Crba: return "ChainDynParam::JntToMass";
      case Algorithm::CrbaCholesky: return "ChainFdSolver_RNE (JntToMass + LDLᵀ)";
      case Algorithm::Fk: return is_chain_ ? "ChainFkSolverPos_recursive (all segments)" : "TreeFkSolverPos_recursive (per body)";
      default: return "";
    }
  }

  void prepare(const std::vector<State>& states) override {
    for (const State& s : states) {
      states_q_.push_back(to_kdl(s.q));
      states_qd_.push_back(to_kdl(s.qd));
      states_qdd_.push_back(to_kdl(s.qdd));
      states_tau_.push_back(to_kdl(s.tau));
    }
  }

  void run(Algorithm a, int k) override {
    const KDL::JntArray& q = states_q_[k];
    switch (a) {
      case Algorithm::Rnea:
        if (is_chain_) id_chain_->CartToJnt(q, states_qd_[k], states_qdd_[k], wrenches_, out_);
        else id_tree_->CartToJnt(q, states_qd_[k], states_qdd_[k], no_wrenches_, out_);
        return;
      case Algorithm::Gravity:
        if (is_chain_) dyn_->JntToGravity(q, out_);
        else id_tree_->CartToJnt(q, zero_, zero_, no_wrenches_, out_);
        return;
      case Algorithm::Crba: dyn_->JntToMass(q, M_); return;
      case Algorithm::CrbaCholesky: fd_->CartToJnt(q, states_qd_[k], states_tau_[k], wrenches_, out_); return;
      case Algorithm::Fk:
        if (is_chain_) fk_chain_->JntToCart(q, frames_);
        else
          for (int i = 1; i < model_.nbodies(); ++i) fk_tree_->JntToCart(q, frames_tree_[i - 1], model_.body_names[i]);
        return;
      default: return;
    }
  }

  Eigen::VectorXd result(Algorithm a) override {
    const int nv = model_.nv;
    if (a == Algorithm::Crba) {
      Eigen::VectorXd M(nv * nv);
      for (int c = 0; c < nv; ++c)
        for (int r = 0; r < nv; ++r) M[c * nv + r] = M_(ours_to_kdl_[r], ours_to_kdl_[c]);
      return M;
    }
    if (a == Algorithm::Fk) {
      Eigen::VectorXd poses(12 * (model_.nbodies() - 1));
      for (int i = 1; i < model_.nbodies(); ++i) {
        const KDL::Frame& F = is_chain_ ? frames_[segment_index_.at(model_.body_names[i])] : frames_tree_[i - 1];
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) poses[12 * (i - 1) + 3 * r + c] = F.M(r, c);
        for (int c = 0; c < 3; ++c) poses[12 * (i - 1) + 9 + c] = F.p(c);
      }
      return poses;
    }
    Eigen::VectorXd x(nv);
    for (int i = 0; i < nv; ++i) x[i] = out_(ours_to_kdl_[i]);
    return x;
  }

 private:
  KDL::JntArray to_kdl(const Eigen::VectorXd& v) const {
    KDL::JntArray a(tree_.getNrOfJoints());
    for (int i = 0; i < static_cast<int>(ours_to_kdl_.size()); ++i) a(ours_to_kdl_[i]) = v[i];
    return a;
  }

  const spatial_dynamics::Model<double>& model_;
  KDL::Tree tree_;
  KDL::Chain chain_;
  KDL::Vector gravity_;
  bool is_chain_ = false;
  std::map<std::string, int> kdl_index_;
  std::map<std::string, unsigned> segment_index_;
  std::vector<int> ours_to_kdl_;
  std::unique_ptr<KDL::ChainIdSolver_RNE> id_chain_;
  std::unique_ptr<KDL::ChainDynParam> dyn_;
  std::unique_ptr<KDL::ChainFdSolver_RNE> fd_;
  std::unique_ptr<KDL::ChainFkSolverPos_recursive> fk_chain_;
  std::unique_ptr<KDL::TreeIdSolver_RNE> id_tree_;
  std::unique_ptr<KDL::TreeFkSolverPos_recursive> fk_tree_;
  KDL::Wrenches wrenches_;
  KDL::WrenchMap no_wrenches_;
  std::vector<KDL::Frame> frames_;
  std::vector<KDL::Frame> frames_tree_ = std::vector<KDL::Frame>(model_.nbodies());
  KDL::JntArray out_, zero_ = KDL::JntArray(tree_.getNrOfJoints());
  KDL::JntSpaceInertiaMatrix M_;
  std::vector<KDL::JntArray> states_q_, states_qd_, states_qdd_, states_tau_;
};

}  // namespace

std::unique_ptr<Adapter> make_kdl_adapter(const spatial_dynamics::Model<double>& model, const std::string& urdf_text,
                                          std::string& why) {
  if (model.floating_base) {
    why = "KDL has no free (6-DoF) joint";
    return nullptr;
  }
  KDL::Tree tree;
  if (!kdl_parser::treeFromString(urdf_text, tree)) {
    why = "kdl_parser could not parse the URDF";
    return nullptr;
  }
  if (static_cast<int>(tree.getNrOfJoints()) != model.nv) {
    why = "KDL tree has " + std::to_string(tree.getNrOfJoints()) + " joints, the model " + std::to_string(model.nv);
    return nullptr;
  }
  try {
    return std::make_unique<KdlAdapter>(model, std::move(tree));
  } catch (const std::exception& e) {
    why = std::string("joint mapping failed: ") + e.what();
    return nullptr;
  }
}

}  // namespace bench
