// Every buffer the algorithms need, allocated once from a Model (the model layer: doc/library.md). A Data
// belongs to one thread; algorithm calls write into it and never allocate.
#pragma once

#include <Eigen/Cholesky>
#include <type_traits>
#include <vector>

#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/number/packed3.hpp"
#include "spatial_dynamics/spatial/articulated_inertia.hpp"
#include "spatial_dynamics/spatial/number/double_double.hpp"
#include "spatial_dynamics/spatial/force_vector.hpp"
#include "spatial_dynamics/spatial/number/lanes.hpp"
#include "spatial_dynamics/spatial/motion_vector.hpp"
#include "spatial_dynamics/spatial/plucker_transform.hpp"
#include "spatial_dynamics/spatial/rigid_inertia.hpp"
#include "spatial_dynamics/spatial/number/wide_vector3.hpp"

namespace spatial_dynamics {

/// The coordinate axis (0–2) about which ^iX_λ(i) rotates, where the joint is revolute (not
/// coupled) about x, y or z and its tree transform does not rotate (E_tree = 1, so that E is the
/// joint's rx, ry or rz, RBDA Table 2.2); else −1.
template <class S>
int coordinate_axis_of_up_rotation(const Model<S>& model, int i) {
  const Joint<S>& j = model.joints[i];
  const bool revolute = j.type == JointType::Revolute && !j.coupled;
  if (revolute && j.axis_kind != AxisKind::General && model.X_tree[i].E == Matrix3<S>::Identity())
    return static_cast<int>(j.axis_kind);
  return -1;
}

template <class S>
struct Data {
  // Kinematics, per body.
  std::vector<PluckerTransform<S>> X_up;    // ^iX_λ(i) = X_J(q_i) X_tree(i)
  std::vector<PluckerTransform<S>> X_base;  // ^iX_0: base coordinates → body i coordinates
  std::vector<PluckerTransform<S>> X_frame_base;  // ^FX_0 for every model frame
  std::vector<MotionVector<S>> v;           // body velocities (body coordinates)
  std::vector<MotionVector<S>> a;           // body accelerations (bias-free in RNEA, c-free in ABA;
                                            // without gravity where the ABA splits it off; the ABA
                                            // forms none at a leaf)
  std::vector<MotionVector<S>> c;           // velocity-product accelerations v_i × S_i q̇_i (ABA)
  std::vector<ForceVector<S>> f;            // body forces (RNEA), bias forces pᴬ (ABA)
  // Joints with an angle (revolute, planar): the bodies they move, and sin and cos of each
  // angle (0 and 1 for other bodies), all computed together before the passes (joint_kernels.hpp).
  std::vector<int> angle_bodies;
  std::vector<S> joint_sin, joint_cos;

  // RNEA (rnea.hpp), per body in the layout its 3-vectors load fastest (packed for double):
  // v = (w ; v), a = (aw ; al), f = (n ; f) and the rows t0..t2 of ^iX_λ's E, and its r.
  struct RneaBody {
    Vector3Storage<S> w, v, aw, al, n, f, t0, t1, t2, r;
  };
  std::vector<RneaBody> rnea;

  // ABA.
  std::vector<ArticulatedInertia<S>> IA;    // articulated-body inertias
  std::vector<Matrix6<S>> U;                // Iᴬ S (first nv columns used)
  std::vector<Matrix6<S>> D_inv;            // (Sᵀ Iᴬ S)^-1 (top-left nv × nv block used)
  std::vector<ForceVector<S>> XtU_D_inv;    // ^iX_λᵀ U D⁻¹ (1-DoF joint, moving parent): q̈ = D⁻¹(u − Uᵀ c) − (Xᵀ U D⁻¹)ᵀ a_λ
  std::vector<Vector6<S>> u;                // τ − Sᵀ pᴬ (first nv entries used)
  // From the tree's shape: whether a body has children, and whether it is the first of its
  // parent's children that the inward pass reaches (the one of highest index). A leaf's Iᴬ = I is
  // stored by the outward pass; a parent's is started by its first child's step, as I_λ + Xᵀ Iᵃ X.
  std::vector<unsigned char> has_children, first_child;
  // The ABA's gravity split (algorithms/gravity_split.hpp), in WiderScalar<S>: per body the
  // gravitational acceleration in body coordinates and the gravity force (moment, force) of the
  // subtree rooted at the body; entry 0 holds the base's gravity. Then τ − τ_g(q) rounded to S.
  struct GravitySplitBody {
    WideVector3Storage<S> gravity, moment, force;
  };
  std::vector<GravitySplitBody> gravity_split;
  VectorX<S> tau_less_gravity;

  // CRBA (crba.hpp), per body in the layout its 3-vectors load fastest (packed for double): the
  // rows t0..t2 of ^iX_λ's E and its r; the composite inertia Iᶜ (columns I0..I2 of Ī_O, h = m c,
  // mass); for the carry in base coordinates the rows of ^iX_0's E and its r.
  struct CrbaBody {
    Vector3Storage<S> t0, t1, t2, r, I0, I1, I2, h, base_t0, base_t1, base_t2, base_r;
    S mass;
  };
  std::vector<CrbaBody> crba;
  // The carry in base coordinates over runs of revolute ancestors, L at a time (crba.hpp): each
  // body's origin and axis in base coordinates as six arrays (x, y, z of the origin, then of the
  // axis), each padded so that a block of lanes may read past the last body; and per body the
  // first body of its run: the bodies k ≤ i down to it each have parent k − 1, a revolute joint
  // of their own and coordinate idx_v of body k − 1 plus one.
  std::vector<S> base_origin_and_axis;
  std::vector<int> revolute_run_start;
  // Per body, the coordinate axis (0–2) of a revolute joint whose tree transform does not rotate
  // (E_tree = 1, so that ^iX_λ's E is the joint's rx, ry or rz, RBDA Table 2.2), else −1: the ABA's
  // products with E then take the rotation's structure (plucker_transform.hpp's RotationAboutAxis).
  std::vector<int> up_rotation_axis;
  // Per body of a revolute joint about a general axis, for double (the packed passes,
  // vector3_form.hpp): ^iX_λ's E = B0 + c B1 + s B2 by the columns of B0..B2 (axis_operations.hpp's
  // revolute_rotation_terms, rounded once from double-double), where rotating E_tree's columns
  // about the axis would take about four times the instructions. Empty for other scalars.
  struct RotationTerms {
    Packed3Storage B0[3], B1[3], B2[3];
  };
  std::vector<RotationTerms> up_rotation_terms;
  // Whether crba carries the columns to the ancestors in base coordinates: when the bodies have
  // four or more moving ancestors on average, in runs of two or more, where that is cheaper than
  // one transform per pair.
  bool crba_in_base_coordinates = false;

  // Results.
  VectorX<S> tau;     // rnea output
  VectorX<S> qdd;     // aba output
  MatrixX<S> M;       // crba output (both triangles)
  Matrix6X<S> J;      // frame_jacobian output

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
        X_frame_base(model.frames.size()),
        v(model.nbodies(), MotionVector<S>::Zero()),
        a(model.nbodies(), MotionVector<S>::Zero()),
        c(model.nbodies(), MotionVector<S>::Zero()),
        f(model.nbodies(), ForceVector<S>::Zero()),
        joint_sin(model.nbodies(), S(0)),
        joint_cos(model.nbodies(), S(1)),
        rnea(model.nbodies()),
        IA(model.nbodies()),
        U(model.nbodies(), Matrix6<S>::Zero()),
        D_inv(model.nbodies(), Matrix6<S>::Zero()),
        XtU_D_inv(model.nbodies(), ForceVector<S>::Zero()),
        u(model.nbodies(), Vector6<S>::Zero()),
        has_children(model.nbodies(), 0),
        first_child(model.nbodies(), 0),
        gravity_split(model.nbodies()),
        tau_less_gravity(VectorX<S>::Zero(model.nv)),
        crba(model.nbodies()),
        base_origin_and_axis(6 * (model.nbodies() + kWidestLanes<S>), S(0)),
        revolute_run_start(model.nbodies(), 0),
        up_rotation_axis(model.nbodies(), -1),
        up_rotation_terms(std::is_same<S, double>::value ? model.nbodies() : 0),
        tau(VectorX<S>::Zero(model.nv)),
        qdd(VectorX<S>::Zero(model.nv)),
        M(MatrixX<S>::Zero(model.nv, model.nv)),
        J(Matrix6X<S>::Zero(6, model.nv)),
        zero_v(VectorX<S>::Zero(model.nv)),
        actuator_force(VectorX<S>::Zero(model.nv)),
        actuator_effort(VectorX<S>::Zero(model.nv)),
        effort_less_actuator_force(VectorX<S>::Zero(model.nv)),
        llt(model.nv) {
    for (int i = 1; i < model.nbodies(); ++i)
      if (angle_coordinate(model.joints[i]) >= 0) angle_bodies.push_back(i);
    for (int i = model.nbodies() - 1; i >= 1; --i) {
      first_child[i] = !has_children[model.parent[i]];
      has_children[model.parent[i]] = 1;
    }
    for (int i = 1; i < model.nbodies(); ++i) {
      const Joint<S>& j = model.joints[i];
      const bool revolute = j.type == JointType::Revolute && !j.coupled;
      const bool extends = revolute && i > 1 && model.parent[i] == i - 1 && revolute_run_start[i - 1] > 0 &&
                           j.idx_v == model.joints[i - 1].idx_v + 1;
      revolute_run_start[i] = extends ? revolute_run_start[i - 1] : (revolute ? i : 0);
      up_rotation_axis[i] = coordinate_axis_of_up_rotation(model, i);
      if constexpr (std::is_same<S, double>::value)
        if (j.type == JointType::Revolute && j.axis_kind == AxisKind::General)
          store_rotation_terms(detail::revolute_rotation_terms(j.axis, model.X_tree[i].E), i);
    }
    // Base coordinates pay off from 4 moving ancestors per body on average, where those form runs
    // of two or more bodies on average (the runs are carried several at a time, crba_base_carry.hpp;
    // a random tree's short runs measured faster one transform per pair: 2.0 against 2.8 µs on 50
    // bodies, a 16-body chain 0.80 against 1.13 µs).
    long ancestor_pairs = 0, ancestor_runs = 0;
    for (int i = 1; i < model.nbodies(); ++i)
      for (int j = model.parent[i]; j > 0;) {
        const int first = revolute_run_start[j] > 0 ? revolute_run_start[j] : j;
        ancestor_pairs += j - first + 1;
        ++ancestor_runs;
        j = model.parent[first];
      }
    crba_in_base_coordinates = ancestor_pairs >= 4L * (model.nbodies() - 1) && 2 * ancestor_runs <= ancestor_pairs;
  }

 private:
  void store_rotation_terms(const detail::RevoluteRotationTerms& terms, int i) {
    Packed3Storage* columns[3] = {up_rotation_terms[i].B0, up_rotation_terms[i].B1, up_rotation_terms[i].B2};
    for (int t = 0; t < 3; ++t)
      for (int k = 0; k < 3; ++k) {
        for (int m = 0; m < 3; ++m) columns[t][k].lane[m] = static_cast<double>(terms.B[t][k][m]);
        columns[t][k].lane[3] = 0.0;
      }
  }
};

}  // namespace spatial_dynamics
