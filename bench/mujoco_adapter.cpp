#include "mujoco_adapter.hpp"

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>

namespace bench {
namespace {

using spatial_dynamics::JointType;

class MujocoAdapter : public Adapter {
 public:
  MujocoAdapter(const spatial_dynamics::Model<double>& model, mjModel* m) : model_(model), m_(m), d_(mj_makeData(m)) {
    m_->opt.disableflags |= mjDSBL_CONSTRAINT | mjDSBL_CONTACT | mjDSBL_PASSIVE | mjDSBL_LIMIT | mjDSBL_FRICTIONLOSS;
    for (int i = 0; i < 3; ++i) m_->opt.gravity[i] = model.gravity[i];
    for (int i = 0; i < m_->nv; ++i) {
      m_->dof_damping[i] = 0;
      m_->dof_armature[i] = 0;
      m_->dof_frictionloss[i] = 0;
    }
    for (int i = 1; i < model.nbodies(); ++i) {
      const int jid = mj_name2id(m_, mjOBJ_JOINT, model.joint_names[i].c_str());
      if (jid < 0) throw std::runtime_error("joint '" + model.joint_names[i] + "' not found in the MuJoCo model");
      qpos_index_.push_back(m_->jnt_qposadr[jid]);
      dof_index_.push_back(m_->jnt_dofadr[jid]);
      const int bid = mj_name2id(m_, mjOBJ_BODY, model.body_names[i].c_str());
      if (bid < 0) throw std::runtime_error("link '" + model.body_names[i] + "' not found in the MuJoCo model");
      bodies_.push_back(bid);
    }
    M_.resize(m_->nv * m_->nv);
  }
  ~MujocoAdapter() override {
    mj_deleteData(d_);
    mj_deleteModel(m_);
  }

  std::string library() const override { return "mujoco"; }
  bool supports(Algorithm a) const override {
    return a == Algorithm::Rnea || a == Algorithm::CrbaCholesky || a == Algorithm::Crba || a == Algorithm::Gravity ||
           a == Algorithm::Fk;
  }
  std::string method(Algorithm a) const override {
    switch (a) {
      case Algorithm::Rnea: return "mj_inverse";
      case Algorithm::CrbaCholesky: return "mj_forward (CRB + sparse LDLᵀ)";
      case Algorithm::Crba: return "mj_kinematics + mj_comPos + mj_crb";
      case Algorithm::Gravity: return "mj_kinematics + mj_comPos + mj_comVel + mj_rne (q̇ = 0)";
      case Algorithm::Fk: return "mj_kinematics";
      default: return "";
    }
  }

  void prepare(const std::vector<State>& states) override {
    for (const State& s : states) {
      Prepared p;
      p.qpos.assign(m_->nq, 0.0);
      p.qvel.assign(m_->nv, 0.0);
      p.qacc.assign(m_->nv, 0.0);
      p.tau.assign(m_->nv, 0.0);
      for (int i = 1; i < model_.nbodies(); ++i) {
        const auto& j = model_.joints[i];
        const int qa = qpos_index_[i - 1], va = dof_index_[i - 1];
        if (j.type == JointType::Free) {
          const Eigen::Vector3d w = s.qd.segment<3>(j.idx_v), v = s.qd.segment<3>(j.idx_v + 3);
          const Eigen::Vector3d wd = s.qdd.segment<3>(j.idx_v), vd = s.qdd.segment<3>(j.idx_v + 3);
          const Eigen::Matrix3d R = rotation(s.q, j.idx_q);
          for (int k = 0; k < 3; ++k) p.qpos[qa + k] = s.q[j.idx_q + k];
          p.qpos[qa + 3] = s.q[j.idx_q + 6];  // w x y z
          for (int k = 0; k < 3; ++k) p.qpos[qa + 4 + k] = s.q[j.idx_q + 3 + k];
          const Eigen::Vector3d pd = R * v, pdd = R * (vd + w.cross(v));  // ṗ = R v, p̈ = R (v̇ + ω × v)
          const Eigen::Vector3d f = R * s.tau.segment<3>(j.idx_v + 3);      // force in world axes
          for (int k = 0; k < 3; ++k) {
            p.qvel[va + k] = pd[k];
            p.qvel[va + 3 + k] = w[k];
            p.qacc[va + k] = pdd[k];
            p.qacc[va + 3 + k] = wd[k];
            p.tau[va + k] = f[k];
            p.tau[va + 3 + k] = s.tau[j.idx_v + k];
          }
          p.R = R;
          p.w = w;
          p.v = v;
        } else {
          p.qpos[qa] = s.q[j.idx_q];
          p.qvel[va] = s.qd[j.idx_v];
          p.qacc[va] = s.qdd[j.idx_v];
          p.tau[va] = s.tau[j.idx_v];
        }
      }
      prepared_.push_back(std::move(p));
    }
  }

  void run(Algorithm a, int k) override {
    const Prepared& p = prepared_[k];
    last_ = k;
    mju_copy(d_->qpos, p.qpos.data(), m_->nq);
    switch (a) {
      case Algorithm::Rnea:
        mju_copy(d_->qvel, p.qvel.data(), m_->nv);
        mju_copy(d_->qacc, p.qacc.data(), m_->nv);
        mj_inverse(m_, d_);
        return;
      case Algorithm::CrbaCholesky:
        mju_copy(d_->qvel, p.qvel.data(), m_->nv);
        mju_copy(d_->qfrc_applied, p.tau.data(), m_->nv);
        mj_forward(m_, d_);
        return;
      case Algorithm::Crba:
        mj_kinematics(m_, d_);
        mj_comPos(m_, d_);
        mj_crb(m_, d_);
        return;
      case Algorithm::Gravity:
        mju_zero(d_->qvel, m_->nv);
        mj_kinematics(m_, d_);
        mj_comPos(m_, d_);
        mj_comVel(m_, d_);
        mj_rne(m_, d_, 0, d_->qfrc_bias);
        return;
      case Algorithm::Fk: mj_kinematics(m_, d_); return;
      default: return;
    }
  }

  Eigen::VectorXd result(Algorithm a) override {
    const int nv = model_.nv;
    const Prepared& p = prepared_[last_];
    if (a == Algorithm::Fk) {
      Eigen::VectorXd poses(12 * bodies_.size());
      for (std::size_t i = 0; i < bodies_.size(); ++i) {
        for (int c = 0; c < 9; ++c) poses[12 * i + c] = d_->xmat[9 * bodies_[i] + c];  // row-major
        for (int c = 0; c < 3; ++c) poses[12 * i + 9 + c] = d_->xpos[3 * bodies_[i] + c];
      }
      return poses;
    }
    if (a == Algorithm::Crba) {
      mj_fullM(m_, M_.data(), d_->qM);
      // M_ours = T⁻ᵀ M_mj T⁻¹ with q̇_mj = T⁻¹ q̇_ours: (ṗ; ω) = (R v; ω) on the free joint.
      Eigen::MatrixXd Tinv = Eigen::MatrixXd::Zero(nv, nv);
      for (int i = 1; i < model_.nbodies(); ++i) {
        const auto& j = model_.joints[i];
        const int va = dof_index_[i - 1];
        if (j.type == JointType::Free) {
          Tinv.block<3, 3>(va, j.idx_v + 3) = p.R;
          Tinv.block<3, 3>(va + 3, j.idx_v) = Eigen::Matrix3d::Identity();
        } else {
          Tinv(va, j.idx_v) = 1.0;
        }
      }
      const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Mmj(M_.data(), nv, nv);
      const Eigen::MatrixXd M = Tinv.transpose() * Mmj * Tinv;
      return Eigen::Map<const Eigen::VectorXd>(M.data(), M.size());
    }
    const mjtNum* x = a == Algorithm::Rnea ? d_->qfrc_inverse : a == Algorithm::Gravity ? d_->qfrc_bias : d_->qacc;
    Eigen::VectorXd out(nv);
    for (int i = 1; i < model_.nbodies(); ++i) {
      const auto& j = model_.joints[i];
      const int va = dof_index_[i - 1];
      if (j.type == JointType::Free) {
        const Eigen::Vector3d lin(x[va], x[va + 1], x[va + 2]), ang(x[va + 3], x[va + 4], x[va + 5]);
        if (a == Algorithm::CrbaCholesky) {  // v̇ = Rᵀ p̈ − ω × v
          out.segment<3>(j.idx_v + 3) = p.R.transpose() * lin - p.w.cross(p.v);
        } else {  // forces: f_body = Rᵀ f_world
          out.segment<3>(j.idx_v + 3) = p.R.transpose() * lin;
        }
        out.segment<3>(j.idx_v) = ang;
      } else {
        out[j.idx_v] = x[va];
      }
    }
    return out;
  }

 private:
  struct Prepared {
    std::vector<mjtNum> qpos, qvel, qacc, tau;
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    Eigen::Vector3d w = Eigen::Vector3d::Zero(), v = Eigen::Vector3d::Zero();
  };

  static Eigen::Matrix3d rotation(const Eigen::VectorXd& q, int idx) {
    return Eigen::Quaterniond(q[idx + 6], q[idx + 3], q[idx + 4], q[idx + 5]).toRotationMatrix();
  }

  const spatial_dynamics::Model<double>& model_;
  mjModel* m_;
  mjData* d_;
  std::vector<int> qpos_index_, dof_index_, bodies_;
  std::vector<Prepared> prepared_;
  std::vector<mjtNum> M_;
  int last_ = 0;
};

}  // namespace

std::unique_ptr<Adapter> make_mujoco_adapter(const spatial_dynamics::Model<double>& model, const std::string& urdf_path,
                                             std::string& why) {
  char error[1000] = "";
  mjModel* m = mj_loadXML(urdf_path.c_str(), nullptr, error, sizeof error);
  if (!m) {
    why = std::string("mj_loadXML: ") + error;
    return nullptr;
  }
  if (m->nv != model.nv) {
    why = "MuJoCo model has " + std::to_string(m->nv) + " DoFs, ours " + std::to_string(model.nv);
    mj_deleteModel(m);
    return nullptr;
  }
  try {
    return std::make_unique<MujocoAdapter>(model, m);
  } catch (const std::exception& e) {
    why = e.what();
    mj_deleteModel(m);  // the adapter was not built, so the model is still ours to free
    return nullptr;
  }
}

}  // namespace bench
