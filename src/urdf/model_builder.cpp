#include "spatial_dynamics/urdf/model_builder.hpp"

#include "spatial_dynamics/model/physical_inertia.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <utility>

#include <Eigen/Eigenvalues>
#include <console_bridge/console.h>
#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>

namespace spatial_dynamics {
namespace {

using Transform = PluckerTransform<double>;

/// Collects urdfdom's error log lines while it parses, so that a parse failure can say why.
class ParseErrorCollector : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) {
      if (!errors_.empty()) errors_ += "; ";
      errors_ += text;
    }
  }
  const std::string& errors() const { return errors_; }

 private:
  std::string errors_;
};

/// Routes console_bridge's log to a collector for as long as it lives.
class CollectorScope {
 public:
  explicit CollectorScope(ParseErrorCollector& collector) { console_bridge::useOutputHandler(&collector); }
  ~CollectorScope() { console_bridge::restorePreviousOutputHandler(); }
  CollectorScope(const CollectorScope&) = delete;
  CollectorScope& operator=(const CollectorScope&) = delete;
};

/// Where `text` stops being well-formed UTF-8 (RFC 3629) or holds a NUL byte; npos when it is fine.
/// XML is UTF-8 unless it says otherwise, and urdfdom's XML parser (TinyXML 2.6) skips a multi-byte
/// character's announced length without looking: a lead byte near the end makes it read past the
/// text (a heap over-read, found by fuzzing). Such text is rejected before it reaches the parser.
std::size_t first_invalid_utf8(const std::string& text) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  for (std::size_t k = 0; k < text.size();) {
    const unsigned char c = byte(k);
    int more = 0;
    unsigned char low = 0x80, high = 0xBF;  // the range of the first continuation byte
    if (c == 0) return k;
    if (c < 0x80) more = 0;
    else if (c >= 0xC2 && c <= 0xDF) more = 1;
    else if (c >= 0xE0 && c <= 0xEF) { more = 2; if (c == 0xE0) low = 0xA0; if (c == 0xED) high = 0x9F; }
    else if (c >= 0xF0 && c <= 0xF4) { more = 3; if (c == 0xF0) low = 0x90; if (c == 0xF4) high = 0x8F; }
    else return k;
    if (text.size() - k <= static_cast<std::size_t>(more)) return k;  // cut off by the end of the text
    for (int m = 1; m <= more; ++m) {
      const unsigned char n = byte(k + m);
      if (n < (m == 1 ? low : 0x80) || n > (m == 1 ? high : 0xBF)) return k;
    }
    k += 1 + more;
  }
  return std::string::npos;
}

Transform transform_from_pose(const urdf::Pose& pose) {
  const Eigen::Quaterniond rotation(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z);
  const Eigen::Vector3d position(pose.position.x, pose.position.y, pose.position.z);
  return Transform::FromPose(rotation.toRotationMatrix(), position);
}

/// Checks a link's <inertial> and returns its spatial inertia in link coordinates (eq. 25):
/// the tensor is given about the centre of mass in the inertial frame, so Ī_c = R Ī Rᵀ.
RigidInertia<double> link_inertia(const urdf::Link& link) {
  if (!link.inertial) return RigidInertia<double>::Zero();
  const urdf::Inertial& in = *link.inertial;
  Eigen::Matrix3d I;
  I << in.ixx, in.ixy, in.ixz,
       in.ixy, in.iyy, in.iyz,
       in.ixz, in.iyz, in.izz;
  const std::string problem = inertia_problem(in.mass, Eigen::Vector3d(in.origin.position.x, in.origin.position.y,
                                                                       in.origin.position.z), I);
  if (!problem.empty()) throw ModelError("link '" + link.name + "': " + problem);
  const Transform X = transform_from_pose(in.origin);
  const Eigen::Matrix3d R = X.rotation();
  return RigidInertia<double>::FromMassCenterInertia(in.mass, X.translation(), R * I * R.transpose());
}

class Builder {
 public:
  Builder(const urdf::ModelInterface& urdf, const ModelBuildOptions& options) : urdf_(urdf), options_(options) {}

  Model<double> build() {
    const urdf::LinkConstSharedPtr root = urdf_.getRoot();
    if (!root) throw ModelError("URDF has no root link");
    check_one_parent_per_link();
    if (options_.floating_base && urdf_.getJoint(options_.root_joint_name))
      throw ModelError("joint '" + options_.root_joint_name +
                       "': the URDF has a joint of this name, which is the floating base's root joint name (choose "
                       "another ModelBuildOptions::root_joint_name)");
    model_.name = urdf_.getName();
    model_.gravity = options_.gravity;
    model_.floating_base = options_.floating_base;
    add_body(-1, "", Transform::Identity(), Joint<double>());  // body 0: the fixed base
    if (options_.floating_base) {
      model_.body_names[0] = "universe";
      const int body = add_body(0, options_.root_joint_name, Transform::Identity(), free_joint());
      visit(*root, body, Transform::Identity());
    } else {
      visit(*root, 0, Transform::Identity());
    }
    check_every_link_reached(*root);
    resolve_mimics();
    model_.reset_actuator_terms();
    for (const auto& [body, dynamics] : pending_dynamics_) {
      const Joint<double>& j = model_.joints[body];
      std::fill_n(model_.damping.begin() + j.idx_v, j.nv, dynamics.damping);
      std::fill_n(model_.friction.begin() + j.idx_v, j.nv, dynamics.friction);
    }
    model_.finalize();
    return std::move(model_);
  }

 private:
  /// A moving joint's URDF <dynamics damping friction>, kept for its coordinates (each of them, for
  /// a joint of several); negative or non-finite values are errors naming the joint.
  void record_dynamics(const urdf::Joint& uj, int body) {
    if (!uj.dynamics) return;
    for (const auto& [what, value] : {std::pair<const char*, double>{"damping", uj.dynamics->damping},
                                      {"friction", uj.dynamics->friction}})
      if (!std::isfinite(value) || value < 0)
        throw ModelError("joint '" + uj.name + "': <dynamics " + what + "> is " + std::to_string(value) +
                         " (it must be finite and not negative)");
    pending_dynamics_.push_back({body, *uj.dynamics});
  }

  int add_body(int parent, const std::string& joint_name, const Transform& X_tree, Joint<double> joint) {
    const int body = model_.nbodies();
    if (parent >= 0) {
      joint.idx_q = model_.nq;
      joint.idx_v = model_.nv;
      model_.nq += joint.nq;
      model_.nv += joint.nv;
    }
    model_.parent.push_back(parent);
    model_.joints.push_back(joint);
    model_.X_tree.push_back(X_tree);
    model_.inertia.push_back(RigidInertia<double>::Zero());
    model_.body_names.emplace_back();
    model_.joint_names.push_back(joint_name);
    return body;
  }

  /// urdfdom accepts a link that is the child of two joints — and so joints that form a cycle
  /// (a link its own ancestor), which the recursion below would follow forever.
  void check_one_parent_per_link() const {
    std::map<std::string, std::string> parent_joint;  // child link → joint
    for (const auto& [name, joint] : urdf_.joints_) {
      const auto [known, fresh] = parent_joint.emplace(joint->child_link_name, name);
      if (!fresh)
        throw ModelError("link '" + joint->child_link_name + "': it is the child of two joints, '" + known->second +
                         "' and '" + name + "'");
    }
  }

  /// With one parent per link, a link the tree does not reach hangs from joints that form a cycle
  /// (urdfdom finds the root all the same).
  void check_every_link_reached(const urdf::Link& root) const {
    std::set<std::string> reached;
    for (const Frame<double>& frame : model_.frames) reached.insert(frame.name);
    for (const auto& [name, link] : urdf_.links_)
      if (!reached.count(name))
        throw ModelError("link '" + name + "': it is not connected to the root link '" + root.name +
                         "' (the joints above it form a cycle)");
  }

  /// Adds `link` (whose frame is ^LX_B relative to `body`) and everything below it. The work of
  /// each step is out of line (add_link, joint_frame, add_joint_body), so that a frame of this
  /// recursion stays small: a chain of a thousand links recurses a thousand deep.
  void visit(const urdf::Link& link, int body, const Transform& X_link_body) {
    add_link(link, body, X_link_body);
    for (const urdf::JointSharedPtr& joint : link.child_joints) {
      const urdf::LinkConstSharedPtr child = urdf_.getLink(joint->child_link_name);
      if (!child) throw ModelError("joint '" + joint->name + "': child link '" + joint->child_link_name + "' not found");
      const Transform X_joint_body = joint_frame(*joint, body, X_link_body);
      if (joint->type == urdf::Joint::FIXED) {
        visit(*child, body, X_joint_body);  // merged: the child link becomes a frame of this body
        continue;
      }
      visit_moving(*joint, *child, add_joint_body(*joint, body, X_joint_body));
    }
  }

  /// `link` as a frame of `body` at ^LX_B, and its inertia added to the body's: I_B += Xᵀ I_L X
  /// (eqs. 24, 26).
  __attribute__((noinline)) void add_link(const urdf::Link& link, int body, const Transform& X_link_body) {
    if (model_.body_names[body].empty()) model_.body_names[body] = link.name;
    model_.frames.push_back({link.name, body, X_link_body});
    model_.inertia[body] += X_link_body.applyInverse(link_inertia(link));
    if (!model_.inertia[body].allFinite())  // finite inputs, but an overflow (m r² with a huge r)
      throw ModelError("link '" + link.name + "': its inertia about the origin of link '" + model_.body_names[body] +
                       "' is not finite (the inertial or joint origins are too large)");
  }

  /// ^JX_B of `joint`, a child joint of a link at ^LX_B of `body`.
  __attribute__((noinline)) Transform joint_frame(const urdf::Joint& joint, int body, const Transform& X_link_body) const {
    const Transform X_joint_body = transform_from_pose(joint.parent_to_joint_origin_transform) * X_link_body;
    if (!X_joint_body.allFinite())
      throw ModelError("joint '" + joint.name + "': its origin relative to link '" + model_.body_names[body] +
                       "' is not finite (the joint origins are too large)");
    return X_joint_body;
  }

  /// The body that moving joint `joint` adds below `body`, its joint at ^JX_B.
  __attribute__((noinline)) int add_joint_body(const urdf::Joint& joint, int body, const Transform& X_joint_body) {
    switch (joint.type) {
      case urdf::Joint::REVOLUTE:
      case urdf::Joint::CONTINUOUS:
      case urdf::Joint::PRISMATIC:
        return add_body(body, joint.name, X_joint_body, movable_joint(joint));
      case urdf::Joint::FLOATING:
        if (joint.mimic) throw ModelError("joint '" + joint.name + "': a floating joint cannot mimic another joint");
        return add_body(body, joint.name, X_joint_body, free_joint());
      case urdf::Joint::PLANAR:
        return add_body(body, joint.name, X_joint_body, planar_joint(joint));
      default:
        throw ModelError("joint '" + joint.name + "': unknown joint type");
    }
  }

  /// The child link of moving joint `uj`, which made body `body`, and everything below it.
  void visit_moving(const urdf::Joint& uj, const urdf::Link& child, int body) {
    record_dynamics(uj, body);
    visit(child, body, Transform::Identity());
  }

  /// A free joint (model/joints/free.hpp): the floating root, or a URDF floating joint.
  static Joint<double> free_joint() {
    Joint<double> free;
    free.type = JointType::Free;
    free.axis_kind = AxisKind::General;
    free.axis.setZero();
    free.nq = 7;
    free.nv = 6;
    return free;
  }

  /// The joint's unit axis; a zero or non-finite one is an error naming the joint.
  static Eigen::Vector3d unit_axis(const urdf::Joint& uj) {
    const Eigen::Vector3d axis(uj.axis.x, uj.axis.y, uj.axis.z);
    if (!axis.allFinite()) throw ModelError("joint '" + uj.name + "': axis is not finite");
    const double norm = axis.norm();
    if (!(norm > 1e-12)) throw ModelError("joint '" + uj.name + "': axis is zero");
    return axis / norm;  // URDF axes are unit vectors; a non-unit one is normalised as urdfdom documents
  }

  /// A planar joint (model/joints/planar.hpp): the URDF axis is the plane's normal n; e₁ is the
  /// first of the joint frame's x, y, z axes most nearly perpendicular to n, made exactly so, and
  /// e₂ = n × e₁ (n = z gives e₁ = x, e₂ = y). URDF gives planar joints no per-coordinate limits.
  Joint<double> planar_joint(const urdf::Joint& uj) {
    if (uj.mimic) throw ModelError("joint '" + uj.name + "': a planar joint cannot mimic another joint");
    Joint<double> j;
    j.type = JointType::Planar;
    j.nq = 3;
    j.nv = 3;
    j.axis = unit_axis(uj);
    j.axis_kind = classify_axis(j.axis);
    int least = 0;
    for (int k = 1; k < 3; ++k)
      if (std::abs(j.axis[k]) < std::abs(j.axis[least])) least = k;
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(least);
    j.plane_x = (e - e.dot(j.axis) * j.axis).normalized();
    j.plane_y = j.axis.cross(j.plane_x);
    return j;
  }

  Joint<double> movable_joint(const urdf::Joint& uj) {
    Joint<double> j;
    j.type = uj.type == urdf::Joint::PRISMATIC ? JointType::Prismatic : JointType::Revolute;
    j.axis = unit_axis(uj);
    j.axis_kind = classify_axis(j.axis);
    if (uj.limits) {
      if (uj.type != urdf::Joint::CONTINUOUS) {
        j.limits.position_lower = uj.limits->lower;
        j.limits.position_upper = uj.limits->upper;
      }
      j.limits.velocity = uj.limits->velocity;
      j.limits.effort = uj.limits->effort;
    }
    if (uj.mimic) {
      j.mimic.multiplier = uj.mimic->multiplier;
      j.mimic.offset = uj.mimic->offset;
      pending_mimics_.push_back({model_.nbodies(), uj.mimic->joint_name});
    }
    return j;
  }

  void resolve_mimics() {
    for (const auto& [body, master] : pending_mimics_) {
      int master_body = -1;
      for (int i = 1; i < model_.nbodies(); ++i)
        if (model_.joint_names[i] == master && model_.joints[i].nv == 1) master_body = i;
      if (master_body < 0)
        throw ModelError("joint '" + model_.joint_names[body] + "': mimics '" + master +
                         "', which is not a revolute, continuous or prismatic joint of the model");
      model_.joints[body].mimic.master_body = master_body;
    }
  }

  const urdf::ModelInterface& urdf_;
  const ModelBuildOptions& options_;
  Model<double> model_;
  std::vector<std::pair<int, std::string>> pending_mimics_;
  std::vector<std::pair<int, urdf::JointDynamics>> pending_dynamics_;  // body, its joint's <dynamics>
};

}  // namespace

Model<double> build_model(const urdf::ModelInterface& urdf_model, const ModelBuildOptions& options) {
  return Builder(urdf_model, options).build();
}

Model<double> build_model_from_urdf_string(const std::string& urdf_xml, const ModelBuildOptions& options) {
  const std::size_t bad = first_invalid_utf8(urdf_xml);
  if (bad != std::string::npos) {
    std::ostringstream why;
    why << "malformed URDF: " << (urdf_xml[bad] == '\0' ? "a NUL byte" : "text that is not UTF-8") << " at byte " << bad
        << " (0x" << std::hex << static_cast<int>(static_cast<unsigned char>(urdf_xml[bad])) << ")";
    throw ModelError(why.str());
  }
  urdf::ModelInterfaceSharedPtr parsed;
  ParseErrorCollector collector;
  {
    // console_bridge's output handler is process-wide: parse one document at a time.
    static std::mutex parse_mutex;
    std::lock_guard<std::mutex> lock(parse_mutex);
    const CollectorScope scope(collector);
    parsed = urdf::parseURDF(urdf_xml);
  }
  // urdfdom logs some errors (an unreadable <inertial>, say) and still returns a model with the
  // element half-filled: any logged error rejects the document.
  if (!parsed || !collector.errors().empty())
    throw ModelError("malformed URDF: " + (collector.errors().empty() ? std::string("urdfdom could not parse it")
                                                                      : collector.errors()));
  return build_model(*parsed, options);
}

Model<double> build_model_from_urdf_file(const std::string& path, const ModelBuildOptions& options) {
  std::ifstream file(path);
  if (!file) throw ModelError("cannot read URDF file '" + path + "'");
  std::stringstream text;
  text << file.rdbuf();
  return build_model_from_urdf_string(text.str(), options);
}

}  // namespace spatial_dynamics
