// Actuator dynamics against MuJoCo 2.2.2 (Debian's libmujoco), which models armature (in M) and
// viscous damping (a passive force): inverse_dynamics_actuated against mj_inverse's qfrc_inverse
// and forward_dynamics_actuated against mj_forward's qacc, on 100 random states with random
// armature (0–0.5) and damping (0–2), friction zero (MuJoCo's friction loss is a constraint, not
// this law). MuJoCo reads the URDF itself (without geometry); contacts, limits and friction loss
// are off. Its URDF import keeps ur5's and solo12's inertias exact; it re-expresses panda's and
// talos' full inertia tensors in principal axes (4e-11 to 6e-8 before any armature), so there the
// actuated answers may differ from MuJoCo's by no more than twice what the rigid-body answers do.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "test_utils.hpp"
#include "urdf_text.hpp"  // bench/: the comparators' URDF without geometry

namespace {

namespace sd = spatial_dynamics;
using Eigen::VectorXd;

/// A fixed-base MuJoCo model of a bundled robot, its coordinates mapped to ours by joint name.
class MujocoRobot {
 public:
  explicit MujocoRobot(const sd::Model<double>& model, const std::string& file) : model_(model) {
    const std::string path = testing::TempDir() + "/mujoco_" + file;
    bench::write_file(path, bench::without_geometry(sd_test::robot_text(file)));
    char error[1000] = "";
    m_ = mj_loadXML(path.c_str(), nullptr, error, sizeof error);
    if (!m_) throw std::runtime_error(std::string("mj_loadXML: ") + error);
    d_ = mj_makeData(m_);
    m_->opt.disableflags |= mjDSBL_CONSTRAINT | mjDSBL_CONTACT | mjDSBL_LIMIT | mjDSBL_FRICTIONLOSS;
    for (int k = 0; k < 3; ++k) m_->opt.gravity[k] = model.gravity[k];
    if (m_->nv != model.nv) throw std::runtime_error("MuJoCo has " + std::to_string(m_->nv) + " DoFs");
    for (int i = 1; i < model.nbodies(); ++i) {
      const int id = mj_name2id(m_, mjOBJ_JOINT, model.joint_names[i].c_str());
      if (id < 0) throw std::runtime_error("joint '" + model.joint_names[i] + "' not in the MuJoCo model");
      qpos_.push_back(m_->jnt_qposadr[id]);
      dof_.push_back(m_->jnt_dofadr[id]);
    }
  }
  ~MujocoRobot() {
    mj_deleteData(d_);
    mj_deleteModel(m_);
  }

  /// MuJoCo's armature and damping per coordinate (its URDF import reads <dynamics> too, so every
  /// DoF's are set; friction loss zero).
  void set_actuators(const std::vector<double>& armature, const std::vector<double>& damping) {
    for (int i = 1; i < model_.nbodies(); ++i) {
      const int dof = dof_[i - 1], k = model_.joints[i].idx_v;
      m_->dof_armature[dof] = armature[k];
      m_->dof_damping[dof] = damping[k];
      m_->dof_frictionloss[dof] = 0;
    }
  }

  VectorXd inverse(const VectorXd& q, const VectorXd& qd, const VectorXd& qdd) {
    load(q, qd);
    for (int i = 1; i < model_.nbodies(); ++i) d_->qacc[dof_[i - 1]] = qdd[model_.joints[i].idx_v];
    mj_inverse(m_, d_);
    return ours(d_->qfrc_inverse);
  }
  VectorXd forward(const VectorXd& q, const VectorXd& qd, const VectorXd& tau) {
    load(q, qd);
    for (int i = 1; i < model_.nbodies(); ++i) d_->qfrc_applied[dof_[i - 1]] = tau[model_.joints[i].idx_v];
    mj_forward(m_, d_);
    return ours(d_->qacc);
  }

 private:
  void load(const VectorXd& q, const VectorXd& qd) {
    mju_zero(d_->qfrc_applied, m_->nv);
    for (int i = 1; i < model_.nbodies(); ++i) {
      d_->qpos[qpos_[i - 1]] = q[model_.joints[i].idx_q];
      d_->qvel[dof_[i - 1]] = qd[model_.joints[i].idx_v];
    }
  }
  VectorXd ours(const mjtNum* x) const {
    VectorXd out(model_.nv);
    for (int i = 1; i < model_.nbodies(); ++i) out[model_.joints[i].idx_v] = x[dof_[i - 1]];
    return out;
  }

  const sd::Model<double>& model_;
  mjModel* m_ = nullptr;
  mjData* d_ = nullptr;
  std::vector<int> qpos_, dof_;
};

/// The largest differences to MuJoCo over the states: relative, ‖x − x_mj‖ / ‖x_mj‖, and absolute.
struct Worst {
  double inverse = 0, forward = 0, inverse_absolute = 0, forward_absolute = 0;

  void add(const VectorXd& id, const VectorXd& id_mj, const VectorXd& fd, const VectorXd& fd_mj) {
    inverse = std::max(inverse, sd_test::relative_error(id, id_mj));
    forward = std::max(forward, sd_test::relative_error(fd, fd_mj));
    inverse_absolute = std::max(inverse_absolute, (id - id_mj).norm());
    forward_absolute = std::max(forward_absolute, (fd - fd_mj).norm());
  }
};

/// Worst differences to MuJoCo over 100 random states: with random armature and damping, and
/// (`rigid`) the rigid-body answers on the same states with MuJoCo's armature and damping zero.
void compare(const std::string& file, Worst& actuated, Worst& rigid) {
  const sd::Model<double> rigid_model = sd::build_model_from_urdf_file(sd_test::robot_path(file));
  sd::Model<double> model = rigid_model;
  model.friction.assign(model.nv, 0.0);
  MujocoRobot mujoco(model, file);
  std::mt19937 rng(1919);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  sd::Data<double> data(model), rigid_data(rigid_model);
  for (int s = 0; s < 100; ++s) {
    for (int k = 0; k < model.nv; ++k) {
      model.armature[k] = 0.5 * u(rng);
      model.damping[k] = 2.0 * u(rng);
    }
    model.finalize();
    const VectorXd q = sd_test::random_configuration(model, rng), qd = sd_test::random_vector(model.nv, rng),
                   qdd = sd_test::random_vector(model.nv, rng), tau = sd_test::random_vector(model.nv, rng, 20.0);
    mujoco.set_actuators(model.armature, model.damping);
    const VectorXd id = sd::inverse_dynamics_actuated(model, data, q, qd, qdd);
    const VectorXd fd = sd::forward_dynamics_actuated(model, data, q, qd, tau);
    actuated.add(id, mujoco.inverse(q, qd, qdd), fd, mujoco.forward(q, qd, tau));
    mujoco.set_actuators(std::vector<double>(model.nv, 0.0), std::vector<double>(model.nv, 0.0));
    const VectorXd id_rigid = sd::rnea(rigid_model, rigid_data, q, qd, qdd);
    const VectorXd fd_rigid = sd::aba(rigid_model, rigid_data, q, qd, tau);
    rigid.add(id_rigid, mujoco.inverse(q, qd, qdd), fd_rigid, mujoco.forward(q, qd, tau));
  }
  std::printf("%-21s relative  actuated: ID %.2e FD %.2e   rigid body: ID %.2e FD %.2e\n", file.c_str(),
              actuated.inverse, actuated.forward, rigid.inverse, rigid.forward);
  std::printf("%-21s absolute  actuated: ID %.2e FD %.2e   rigid body: ID %.2e FD %.2e\n", "", actuated.inverse_absolute,
              actuated.forward_absolute, rigid.inverse_absolute, rigid.forward_absolute);
}

TEST(MujocoOracle, ArmatureAndDampingWhereTheImportIsExact) {
  for (const std::string& file : {"ur5.urdf", "solo12.urdf"}) {
    Worst actuated, rigid;
    compare(file, actuated, rigid);
    EXPECT_LE(actuated.inverse, 1e-10) << file;
    EXPECT_LE(actuated.forward, 1e-10) << file;
  }
}

TEST(MujocoOracle, ArmatureAndDampingWithinTwiceTheRigidBodyDifference) {
  // The differences as norms of x − x_mj on the same states (q, q̇, q̈ or τ): armature makes the
  // accelerations of talos' light gripper links 10³ times smaller, so relative differences, divided
  // by a smaller ‖q̈‖, would compare the two cases on different scales. The double pendulum's import
  // is exact: there both differences are rounding, and the bound is at least 1e-12.
  for (const std::string& file : {"panda.urdf", "talos.urdf", "double_pendulum.urdf"}) {
    Worst actuated, rigid;
    compare(file, actuated, rigid);
    EXPECT_LE(actuated.inverse_absolute, std::max(2 * rigid.inverse_absolute, 1e-12)) << file;
    EXPECT_LE(actuated.forward_absolute, std::max(2 * rigid.forward_absolute, 1e-12)) << file;
  }
}

}  // namespace
