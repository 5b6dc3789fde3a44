// The independent float128 solution of contact dynamics, for the tests (test_contact_dynamics, the
// floating-base node test): frame poses from the reference's 6×6 transforms (reference/joint_model.hpp),
// J_c and J̇_c q̇ by central differences of the contact frames' poses along q(t) = q ⊕ t q̇ (a free
// joint's screw motion at constant body twist, so q̈ = 0 along it), and dense pseudo-inverses.
#pragma once

#include <vector>

#include "spatial_dynamics/model/contact_set.hpp"
#include "spatial_dynamics/reference/high_precision.hpp"
#include "spatial_dynamics/reference/joint_model.hpp"
#include "spatial_dynamics/reference/pseudo_inverse.hpp"
#include "configuration_path.hpp"

namespace sd_test {

namespace contact_oracle_types {
namespace sd = spatial_dynamics;
namespace ref = spatial_dynamics::reference;
using Quad = sd::Quad;
using VecQ = ref::VecX<Quad>;
using MatQ = ref::MatX<Quad>;
using Vec3Q = ref::Vec3<Quad>;
using Mat3Q = ref::Mat3<Quad>;
using Mat6Q = ref::Mat6<Quad>;
}  // namespace contact_oracle_types
using namespace contact_oracle_types;

/// ^iX_0 of every body (6×6, motion), from the reference's ^iX_λ.
inline std::vector<Mat6Q> body_transforms(const sd::Model<Quad>& model, const VecQ& q) {
  std::vector<Mat6Q> X_up = ref::up_transforms(model, q), X_0(model.nbodies(), Mat6Q::Identity());
  for (int i = 1; i < model.nbodies(); ++i) X_0[i] = X_up[i] * X_0[model.parent[i]];
  return X_0;
}

/// ^FX_0 of a model frame.
inline Mat6Q frame_transform(const sd::Model<Quad>& model, const std::vector<Mat6Q>& X_0, int frame) {
  const sd::Frame<Quad>& f = model.frames[frame];
  return ref::plucker(f.X_frame_body.E.eigen(), f.X_frame_body.r.eigen()) * X_0[f.body];
}

/// From ^BX_0 = [E 0; −E r× E]: B's axes in base coordinates (R = Eᵀ) and its origin r.
inline void pose_of(const Mat6Q& X, Mat3Q& R, Vec3Q& r) {
  const Mat3Q E = X.topLeftCorner<3, 3>();
  R = E.transpose();
  const Mat3Q r_cross = -R * X.bottomLeftCorner<3, 3>();
  r = Vec3Q(r_cross(2, 1), r_cross(0, 2), r_cross(1, 0));
}

/// The velocity (ω; v) of B in B's axes from ^BX_0 at t ± h: (v×) = −Ẋ X⁻¹ (RBDA eq. 2.41's derivative).
inline ref::Vec6<Quad> velocity_from(const Mat6Q& X_minus, const Mat6Q& X, const Mat6Q& X_plus, const Quad& h) {
  const Mat6Q V = -((X_plus - X_minus) / (2 * h)) * X.inverse();
  ref::Vec6<Quad> out;
  out << V(2, 1), V(0, 2), V(1, 0), V(5, 1), V(3, 2), V(4, 0);
  return out;
}

inline constexpr double kStep = 1e-9;  // central differences in float128: O(h²) = 1e-18, rounding 1e-34 / h

/// J_c (contact axes) and J̇_c q̇ by central differences of the contact frames' poses.
inline void contact_jacobian_by_differences(const sd::Model<Quad>& model, const sd::ContactSet<double>& contacts, const VecQ& q,
                                     const VecQ& qd, MatQ& J, VecQ& Jdot_qd) {
  const Quad h(kStep);
  J = MatQ::Zero(contacts.rows, model.nv);
  Jdot_qd = VecQ::Zero(contacts.rows);
  const std::vector<Mat6Q> X0 = body_transforms(model, q);
  for (int k = 0; k < model.nv; ++k) {
    const VecQ e = VecQ::Unit(model.nv, k);
    const std::vector<Mat6Q> Xm = body_transforms(model, advance(model, q, e, -h)), Xp = body_transforms(model, advance(model, q, e, h));
    for (const sd::Contact<double>& c : contacts.contacts) {
      const ref::Vec6<Quad> column = velocity_from(frame_transform(model, Xm, c.frame), frame_transform(model, X0, c.frame),
                                                   frame_transform(model, Xp, c.frame), h);
      const int n = sd::contact_rows(c.kind);
      J.block(c.row, k, n, 1) = column.tail(n);
    }
  }
  // Along q ⊕ t q̇ (q̈ = 0): the origin's acceleration (second difference of its position) and the angular
  // acceleration (difference of the angular velocity), in the frame's axes at t = 0.
  for (const sd::Contact<double>& c : contacts.contacts) {
    Mat3Q R[5];
    Vec3Q p[5];
    for (int s = -2; s <= 2; ++s)
      pose_of(frame_transform(model, body_transforms(model, advance(model, q, qd, Quad(s) * h)), c.frame), R[s + 2], p[s + 2]);
    const Vec3Q a = (p[3] - 2 * p[2] + p[1]) / (h * h);
    auto omega = [&](int s) {  // ω in base axes at t = s h from R at (s ± 1) h
      const Mat3Q W = ((R[s + 3] - R[s + 1]) / (2 * h)) * R[s + 2].transpose();
      return Vec3Q(W(2, 1), W(0, 2), W(1, 0));
    };
    const Vec3Q alpha = (omega(1) - omega(-1)) / (2 * h);
    ref::Vec6<Quad> classical;
    classical << R[2].transpose() * alpha, R[2].transpose() * a;
    const int n = sd::contact_rows(c.kind);
    Jdot_qd.segment(c.row, n) = classical.tail(n);
  }
}

/// m = Σ m_i.
inline Quad total_mass(const sd::Model<Quad>& model) {
  Quad mass(0);
  for (int i = 1; i < model.nbodies(); ++i) mass += model.inertia[i].mass;
  return mass;
}

/// The centre of mass Σ m_i (p_i + R_i c_i) / m in base coordinates, from the bodies' ^iX_0.
inline Vec3Q center_of_mass(const sd::Model<Quad>& model, const std::vector<Mat6Q>& X0) {
  Vec3Q sum = Vec3Q::Zero();
  for (int i = 1; i < model.nbodies(); ++i) {
    Mat3Q R;
    Vec3Q p;
    pose_of(X0[i], R, p);
    sum += model.inertia[i].mass * p + R * model.inertia[i].first_moment.eigen();
  }
  return Vec3Q(sum / total_mass(model));
}

/// pinv(A) b, the rank decided at 1e-12 relative (above the differences' rounding).
inline VecQ pseudo_inverse_solve(const MatQ& A, const VecQ& b) { return ref::pseudo_inverse_solve(A, b, Quad(1e-12)); }

}  // namespace sd_test
