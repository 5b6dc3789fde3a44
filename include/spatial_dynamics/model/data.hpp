// Every buffer the algorithms need, allocated once from a Model (DESIGN.md, layer 2). A Data
// belongs to one thread; algorithm calls write into it and never allocate.
#pragma once

#include <Eigen/Cholesky>
#include <type_traits>
#include <vector>

#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/articulated_inertia.hpp"
#include "spatial_dynamics/spatial/force_vector.hpp"
#include "spatial_dynamics/spatial/motion_vector.hpp"
#include "spatial_dynamics/spatial/packed3.hpp"
#include "spatial_dynamics/spatial/plucker_transform.hpp"
#include "spatial_dynamics/spatial/rigid_inertia.hpp"

namespace spatial_dynamics {

template <class S>
struct Data {
  // Kinematics, per body.
  std::vector<PluckerTransform<S>> X_up;    // ^iX_λ(i) = X_J(q_i) X_tree(i)
  std::vector<PluckerTransform<S>> X_base;  // ^iX_0: base coordinates → body i coordinates
  std::vector<PluckerTransform<S>> X_frame_base;  // ^FX_0 for every model frame
  std::vector<MotionVector<S>> v;           // body velocities (body coordinates)
  std::vector<MotionVector<S>> a;           // body accelerations (bias-free in RNEA, c-free in ABA)
  std::vector<MotionVector<S>> c;           // velocity-product accelerations v_i × S_i q̇_i (ABA)
  std::vector<ForceVector<S>> f;            // body forces (RNEA), bias forces pᴬ (ABA)
  // Revolute joints: the bodies they move, and sin and cos of each one's angle (entries of other
  // bodies unused), all computed together before the passes (joint_kernels.hpp).
  std::vector<int> revolute_bodies;
  std::vector<S> joint_sin, joint_cos;
  // The packed RNEA's per-body state (algorithms/rnea_packed.hpp; double only, empty otherwise):
  // velocity, acceleration, force, the rows of ^iX_λ's rotation and its translation.
  struct PackedRneaBody {
    Packed3Storage w, v, aw, al, n, f, t0, t1, t2, r;
  };
  std::vector<PackedRneaBody> packed_rnea;

  // ABA.
  std::vector<ArticulatedInertia<S>> IA;    // articulated-body inertias
  std::vector<Matrix6<S>> U;                // Iᴬ S (first nv columns used)
  std::vector<Matrix6<S>> D_inv;            // (Sᵀ Iᴬ S)^-1 (top-left nv × nv block used)
  std::vector<Vector6<S>> u;                // τ − Sᵀ pᴬ (first nv entries used)

  // CRBA.
  // The packed CRBA's per-body state (algorithms/crba_packed.hpp; double only, empty otherwise):
  // the rows of ^iX_λ's rotation, its translation, and the composite inertia.
  struct PackedCrbaBody {
    Packed3Storage t0, t1, t2, r, I0, I1, I2, h;
    double mass;
  };
  std::vector<PackedCrbaBody> packed_crba;
  std::vector<RigidInertia<S>> Ic;          // composite inertias
  std::vector<Vector3<S>> axis_base;        // each 1-DoF joint's axis in base coordinates
  // Whether crba carries the columns to the ancestors in base coordinates: when the bodies have
  // four (twelve on the packed path) or more moving ancestors on average, where that is cheaper
  // than one transform per pair.
  bool crba_in_base_coordinates = false;

  // Results.
  VectorX<S> tau;     // rnea output
  VectorX<S> qdd;     // aba output
  MatrixX<S> M;       // crba output (both triangles)
  Matrix6X<S> J;      // frame_jacobian output

  // Zero inputs for the RNEA special cases (gravity torques, nonlinear effects).
  VectorX<S> zero_v;

  // Cholesky factor for forward dynamics through the mass matrix (sized once).
  Eigen::LLT<MatrixX<S>> llt;

  explicit Data(const Model<S>& model)
      : X_up(model.nbodies()),
        X_base(model.nbodies()),
        X_frame_base(model.frames.size()),
        v(model.nbodies(), MotionVector<S>::Zero()),
        a(model.nbodies(), MotionVector<S>::Zero()),
        c(model.nbodies(), MotionVector<S>::Zero()),
        f(model.nbodies(), ForceVector<S>::Zero()),
        joint_sin(model.nbodies(), S(0)),
        joint_cos(model.nbodies(), S(1)),
        packed_rnea(std::is_same<S, double>::value ? model.nbodies() : 0),
        IA(model.nbodies()),
        U(model.nbodies(), Matrix6<S>::Zero()),
        D_inv(model.nbodies(), Matrix6<S>::Zero()),
        u(model.nbodies(), Vector6<S>::Zero()),
        packed_crba(std::is_same<S, double>::value ? model.nbodies() : 0),
        Ic(model.nbodies()),
        axis_base(model.nbodies(), Vector3<S>::Zero()),
        tau(VectorX<S>::Zero(model.nv)),
        qdd(VectorX<S>::Zero(model.nv)),
        M(MatrixX<S>::Zero(model.nv, model.nv)),
        J(Matrix6X<S>::Zero(6, model.nv)),
        zero_v(VectorX<S>::Zero(model.nv)),
        llt(model.nv) {
    for (int i = 1; i < model.nbodies(); ++i)
      if (model.joints[i].type == JointType::Revolute) revolute_bodies.push_back(i);
    long ancestor_pairs = 0;
    for (int i = 1; i < model.nbodies(); ++i)
      for (int j = model.parent[i]; j > 0; j = model.parent[j]) ++ancestor_pairs;
    // Base coordinates pay off from 4 moving ancestors per body on average with the scalar carry,
    // from 12 with the packed one (crba_packed.hpp, taken by the models the packed RNEA takes):
    // per pair it is two rotations and a cross product in registers, against a cross and a dot
    // product in base coordinates, but along one dependency chain (measured crossover: chains of
    // 20 to 25 bodies).
    long per_body = 4;
#ifdef SD_PACKED3
    if (std::is_same<S, double>::value && !model.floating_base && !model.has_coupled_joints) per_body = 12;
#endif
    crba_in_base_coordinates = ancestor_pairs >= per_body * (model.nbodies() - 1);
  }
};

}  // namespace spatial_dynamics
