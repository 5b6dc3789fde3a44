// Every buffer the algorithms need, allocated once from a Model (the model layer: doc/library.md). A Data
// belongs to one thread; algorithm calls write into it and never allocate.
#pragma once

#include <Eigen/Cholesky>
#include <array>
#include <vector>

#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/articulated_inertia.hpp"
#include "spatial_dynamics/spatial/number/double_double.hpp"
#include "spatial_dynamics/spatial/force_vector.hpp"
#include "spatial_dynamics/spatial/motion_vector.hpp"
#include "spatial_dynamics/spatial/plucker_transform.hpp"
#include "spatial_dynamics/spatial/rigid_inertia.hpp"

namespace spatial_dynamics {

template <class S>
struct Data {
  // Kinematics, per body.
  std::vector<PluckerTransform<S>> X_up;    // ^iX_λ(i) = X_J(q_i) X_tree(i)
  std::vector<PluckerTransform<S>> X_base;  // ^iX_0: base coordinates → body i coordinates
  std::vector<PluckerTransform<S>> X_root;  // ^iX_r, r the root body of i's tree (the regressors)
  std::vector<PluckerTransform<S>> X_frame_base;  // ^FX_0 for every model frame
  std::vector<MotionVector<S>> v;           // body velocities (body coordinates)
  std::vector<MotionVector<S>> a;           // body accelerations, less the base's −a_g (RNEA, ABA;
                                            // without gravity where the ABA splits it off)
  std::vector<MotionVector<S>> c;           // velocity-product accelerations c_J + v_i × S_i q̇_i (ABA)
  std::vector<ForceVector<S>> f;            // body forces (RNEA; momentum_observer_terms: gravity's),
                                            // bias forces pᴬ (ABA)
  std::vector<ForceVector<S>> h;            // subtree momenta Σ I v (generalized_momentum)
  std::vector<RigidInertia<S>> Ic;          // composite inertias Iᶜ in base axes (CRBA: about the body's
                                            // origin; coriolis_matrix: about the base origin)
  std::vector<std::array<MotionVector<S>, 6>> S_base;  // the columns of S in base axes (first nv used;
                                                       // about the same point as Iᶜ)
  std::vector<std::array<MotionVector<S>, 6>> S_root;  // the columns of S in root coordinates (X_root)
  // Coriolis matrix (coriolis.hpp), in base coordinates about the base origin: body velocities,
  // the columns of Ṡ, and per subtree İᶜ = Σ İ and the momentum hᶜ = Σ I v.
  std::vector<MotionVector<S>> v_base;
  std::vector<std::array<MotionVector<S>, 6>> S_rate_base;
  std::vector<RigidInertia<S>> Ic_rate;
  std::vector<ForceVector<S>> hc_base;
  // Joints with an angle (revolute, planar): the bodies they move, and sin and cos of each
  // angle (0 and 1 for other bodies), all computed together before the passes (model/joints/body_joint.hpp).
  std::vector<int> angle_bodies;
  std::vector<S> joint_sin, joint_cos;

  // ABA.
  std::vector<ArticulatedInertia<S>> IA;    // articulated-body inertias
  std::vector<std::array<ForceVector<S>, 6>> U;  // the columns of U = Iᴬ S (first nv used)
  std::vector<Matrix6<S>> D_inv;            // (Sᵀ Iᴬ S)^-1 (top-left nv × nv block used)
  std::vector<Vector6<S>> u;                // τ − Sᵀ pᴬ (first nv entries used)
  // The ABA's gravity split (algorithms/gravity_split.hpp), in WiderScalar<S>: per body the
  // gravitational acceleration in body coordinates and the gravity force (moment, force) of the
  // subtree rooted at the body; entry 0 holds the base's gravity. Then τ − τ_g(q) rounded to S.
  struct GravitySplitBody {
    Vec3<WiderScalar<S>> gravity;
    ForceVector<WiderScalar<S>> force;
  };
  std::vector<GravitySplitBody> gravity_split;
  VectorX<S> tau_less_gravity;

  // Results.
  VectorX<S> tau;     // rnea output
  VectorX<S> qdd;     // aba output
  MatrixX<S> M;       // crba output (both triangles)
  Matrix6X<S> J;      // frame_jacobian output
  Matrix6X<S> A_G;    // centroidal_momentum_matrix output: h_G = A_G q̇
  MatrixX<S> J_com;   // center_of_mass_jacobian output (3 × nv): ċ = J_com q̇
  MatrixX<S> C;       // coriolis_matrix output
  VectorX<S> momentum;                     // generalized_momentum output, p = M q̇
  VectorX<S> coriolis_transpose_velocity;  // coriolis_transpose_times_velocity output, Cᵀ q̇
  RowMajorMatrixX<S> Y;  // joint_torque_regressor output (nv × 10 N), τ = Y π + armature ⊙ q̈; by row, so
                         // that a body's ten entries of a joint's row are adjacent
  MatrixX<S> Y_payload;  // payload_regressor output (nv × 10): a payload's π to its joint forces
  MatrixX<S> Y_actuator;  // payload_regressor's actuator columns (nv × 3): row k (q̈_k, q̇_k, ramp_k)

  // Zero inputs for the RNEA special cases (gravity torques, nonlinear effects).
  VectorX<S> zero_v;

  // Actuator dynamics (actuator_dynamics.hpp): damping and friction forces at q̇, with the rotor
  // inertia's armature ⊙ q̈ the actuators' effort, and τ less the forces for forward dynamics.
  VectorX<S> actuator_force, actuator_effort, effort_less_actuator_force;

  // Cholesky factor for forward dynamics through the mass matrix (sized once).
  Eigen::LLT<MatrixX<S>> llt;

  explicit Data(const Model<S>& model)
      : X_up(model.nbodies()),
        X_base(model.nbodies()),
        X_root(model.nbodies()),
        X_frame_base(model.frames.size()),
        v(model.nbodies(), MotionVector<S>::Zero()),
        a(model.nbodies(), MotionVector<S>::Zero()),
        c(model.nbodies(), MotionVector<S>::Zero()),
        f(model.nbodies(), ForceVector<S>::Zero()),
        h(model.nbodies(), ForceVector<S>::Zero()),
        Ic(model.nbodies()),
        S_base(model.nbodies()),
        S_root(model.nbodies()),
        v_base(model.nbodies(), MotionVector<S>::Zero()),
        S_rate_base(model.nbodies()),
        Ic_rate(model.nbodies()),
        hc_base(model.nbodies(), ForceVector<S>::Zero()),
        joint_sin(model.nbodies(), S(0)),
        joint_cos(model.nbodies(), S(1)),
        IA(model.nbodies()),
        U(model.nbodies()),
        D_inv(model.nbodies(), Matrix6<S>::Zero()),
        u(model.nbodies(), Vector6<S>::Zero()),
        gravity_split(model.nbodies()),
        tau_less_gravity(VectorX<S>::Zero(model.nv)),
        tau(VectorX<S>::Zero(model.nv)),
        qdd(VectorX<S>::Zero(model.nv)),
        M(MatrixX<S>::Zero(model.nv, model.nv)),
        J(Matrix6X<S>::Zero(6, model.nv)),
        A_G(Matrix6X<S>::Zero(6, model.nv)),
        J_com(MatrixX<S>::Zero(3, model.nv)),
        C(MatrixX<S>::Zero(model.nv, model.nv)),
        momentum(VectorX<S>::Zero(model.nv)),
        coriolis_transpose_velocity(VectorX<S>::Zero(model.nv)),
        Y(RowMajorMatrixX<S>::Zero(model.nv, 10 * (model.nbodies() - 1))),
        Y_payload(MatrixX<S>::Zero(model.nv, 10)),
        Y_actuator(MatrixX<S>::Zero(model.nv, 3)),
        zero_v(VectorX<S>::Zero(model.nv)),
        actuator_force(VectorX<S>::Zero(model.nv)),
        actuator_effort(VectorX<S>::Zero(model.nv)),
        effort_less_actuator_force(VectorX<S>::Zero(model.nv)),
        llt(model.nv) {
    for (int i = 1; i < model.nbodies(); ++i)
      if (angle_coordinate(model.joints[i]) >= 0) angle_bodies.push_back(i);
  }
};

}  // namespace spatial_dynamics
