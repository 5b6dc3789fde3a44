// A rigid payload, and optionally the joints' damping and Coulomb friction, identified from measured
// joint efforts (doc/payload_identification.md):
//   τ_measured − τ_model = Y_P π_P (+ Y_a (damping, friction)) + noise,
// τ_model the model's inverse dynamics without the payload (with its actuator model, or with only
// its armature when friction is identified), Y_P the payload regressor (algorithms/regressor.hpp).
//  1. The samples' rows are stacked, the columns scaled (payload_column_scales) and reduced by a QR
//     factorisation to R z ≈ c (the same least-squares problem in p × p).
//  2. The SVD of R: directions whose singular value is below `singular_value_tolerance` times the
//     largest are ones the data cannot determine. They are held at the prior (the payload attached
//     now, or zero, and the model's damping and friction) by rows σ_max Vᵀ_null (x − x_prior); a
//     parameter with more than 1 % of its (scaled) unit vector in them is named unidentifiable.
//  3. π_P = π(θ) through the log-Cholesky parameterisation (log_cholesky.hpp): every iterate is a
//     physical body. Eigen's Levenberg–Marquardt solves from the unconstrained solution made physical.
//  4. Standard deviations from the residual and the regressor at the solution: cov x = σ̂² (AᵀA)⁺ on
//     the identifiable directions, σ̂² = ‖r‖² / (rows − rank); those of mass, centre of mass and the
//     inertia about it by the first-order (delta) method; NaN where a held parameter enters.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <unsupported/Eigen/LevenbergMarquardt>
#include <vector>

#include "spatial_dynamics/algorithms/actuator_dynamics.hpp"
#include "spatial_dynamics/algorithms/regressor.hpp"
#include "spatial_dynamics/algorithms/rnea.hpp"
#include "spatial_dynamics/estimation/log_cholesky.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/reduction/payload.hpp"

namespace spatial_dynamics {

/// Measured samples, one per column: positions (nq), velocities, accelerations and efforts (nv).
struct PayloadSamples {
  Eigen::MatrixXd position, velocity, acceleration, effort;
};

struct PayloadIdentificationOptions {
  bool identify_friction = false;     // also each coordinate's damping and Coulomb friction
  Payload prior;                      // held where the data cannot determine the payload
  double singular_value_tolerance = 1e-6;  // relative to the largest, on the column-scaled regressor
  double length_scale = 0.1;          // m: a payload's size, for comparing m, m c and I (payload_column_scales)
  int max_evaluations = 2000;         // of the Levenberg–Marquardt residual
  std::vector<int> measured;          // the coordinates whose efforts count (empty: all)
};

struct PayloadIdentification {
  Payload payload;          // mass, centre of mass in the frame, inertia about it in the frame's axes
  Payload stddev;           // the same fields' standard deviations (NaN where a held parameter enters)
  InertialParameters parameters, parameter_stddev;  // π about the frame origin, and its deviations
  std::vector<std::string> unidentifiable;          // parameters held at the prior (parameter_names)
  Eigen::VectorXd residual_rms;                     // per measured coordinate, N m or N
  double condition_number = 0;                      // of the column-scaled regressor, σ_max / σ_min
  Eigen::VectorXd damping, friction, damping_stddev, friction_stddev;  // with identify_friction, per measured coordinate
  int evaluations = 0;
};

/// The names of π's entries, then with friction "damping/<coordinate>" and "friction/<coordinate>"
/// for each measured coordinate.
inline std::vector<std::string> payload_parameter_names(const Model<double>& model, bool friction,
                                                        const std::vector<int>& measured) {
  std::vector<std::string> names = {"mass",       "first_moment.x", "first_moment.y", "first_moment.z",
                                    "inertia.xx", "inertia.xy",     "inertia.yy",     "inertia.xz",
                                    "inertia.yz", "inertia.zz"};
  if (!friction) return names;
  const std::vector<std::string> coordinates = model.velocityNames();
  for (const char* term : {"damping/", "friction/"})
    for (int k : measured) names.push_back(term + coordinates[k]);
  return names;
}

/// The column scales d of a stacked regressor A (z = d ⊙ x, A diag(1/d) the scaled one): the payload's
/// ten columns in common units — m c per length_scale L, Ī per L² — all divided by the largest of them,
/// so that they compare as the payload's physics does (a column that is zero but for rounding stays
/// negligible, as it would not if scaled to unit norm); every further column (damping, friction: an
/// input, exactly zero where its joint never moves) to unit norm. Zero columns get scale 1.
inline Eigen::VectorXd payload_column_scales(const Eigen::MatrixXd& A, double length_scale) {
  Eigen::VectorXd d(A.cols());
  double largest = 0;
  for (int j = 0; j < 10; ++j) {
    d[j] = std::pow(length_scale, j == 0 ? 0 : j < 4 ? 1 : 2);  // the unit of x_j in kg
    largest = std::max(largest, A.col(j).norm() * d[j]);
  }
  for (int j = 0; j < 10; ++j) d[j] = largest > 0 ? largest / d[j] : 1.0;
  for (Eigen::Index j = 10; j < A.cols(); ++j) {
    const double norm = A.col(j).norm();
    d[j] = norm > 0 ? norm : 1.0;
  }
  return d;
}

namespace detail {

/// Mass, centre of mass and inertia about it (geometry_msgs/Inertia's order: m, c_x, c_y, c_z, xx,
/// xy, xz, yy, yz, zz) of π, and their derivative with respect to π:
/// c = h / m,  Ī_c = Ī_O + (h hᵀ − h·h 1) / m  (eq. 25 solved for Ī_c).
inline Eigen::Matrix<double, 10, 1> payload_fields(const InertialParameters& pi, Eigen::Matrix<double, 10, 10>* jacobian) {
  auto fields = [](const InertialParameters& p) {
    const double m = p[0];
    const Eigen::Vector3d h = p.segment<3>(1);
    Eigen::Matrix3d I;
    I << p[4], p[5], p[7], p[5], p[6], p[8], p[7], p[8], p[9];
    const Eigen::Matrix3d Ic = I + (h * h.transpose() - h.squaredNorm() * Eigen::Matrix3d::Identity()) / m;
    Eigen::Matrix<double, 10, 1> f;
    f << m, h / m, Ic(0, 0), Ic(0, 1), Ic(0, 2), Ic(1, 1), Ic(1, 2), Ic(2, 2);
    return f;
  };
  if (jacobian) {  // exact: f is rational in π; dm and dh enter through m and h only (dual numbers by hand)
    const double m = pi[0];
    const Eigen::Vector3d h = pi.segment<3>(1);
    for (int k = 0; k < 10; ++k) {
      const double dm = k == 0 ? 1.0 : 0.0;
      const Eigen::Vector3d dh = (k >= 1 && k <= 3) ? Eigen::Vector3d(Eigen::Vector3d::Unit(k - 1)) : Eigen::Vector3d(Eigen::Vector3d::Zero());
      Eigen::Matrix3d dI = Eigen::Matrix3d::Zero();
      const int r[6] = {0, 0, 1, 0, 1, 2}, c[6] = {0, 1, 1, 2, 2, 2};
      if (k >= 4) dI(r[k - 4], c[k - 4]) = dI(c[k - 4], r[k - 4]) = 1.0;
      const Eigen::Matrix3d hh = h * h.transpose() - h.squaredNorm() * Eigen::Matrix3d::Identity();
      const Eigen::Matrix3d dhh = dh * h.transpose() + h * dh.transpose() - 2.0 * h.dot(dh) * Eigen::Matrix3d::Identity();
      const Eigen::Matrix3d dIc = dI + dhh / m - hh * dm / (m * m);
      const Eigen::Vector3d dc = dh / m - h * dm / (m * m);
      jacobian->col(k) << dm, dc, dIc(0, 0), dIc(0, 1), dIc(0, 2), dIc(1, 1), dIc(1, 2), dIc(2, 2);
    }
  }
  return fields(pi);
}

inline Payload payload_of_fields(const Eigen::Matrix<double, 10, 1>& f) {
  Payload p;
  p.mass = f[0];
  p.center_of_mass = f.segment<3>(1);
  p.inertia << f[4], f[5], f[6], f[5], f[7], f[8], f[6], f[8], f[9];
  return p;
}

/// The reduced problem R D x ≈ c with the held directions' rows σ_max Vᵀ_null D (x − x_prior), over
/// the solver's y = (θ, friction terms).
struct ReducedPayloadProblem : Eigen::DenseFunctor<double> {
  Eigen::MatrixXd R_scaled;  // R D (p × p)
  Eigen::VectorXd c;
  Eigen::MatrixXd hold;      // σ_max Vᵀ_null D (null × p)
  Eigen::VectorXd x_prior;

  ReducedPayloadProblem(const Eigen::MatrixXd& R_scaled_, const Eigen::VectorXd& c_, const Eigen::MatrixXd& hold_,
                        const Eigen::VectorXd& x_prior_)
      : Eigen::DenseFunctor<double>(static_cast<int>(R_scaled_.cols()), static_cast<int>(R_scaled_.rows() + hold_.rows())),
        R_scaled(R_scaled_), c(c_), hold(hold_), x_prior(x_prior_) {}

  /// x of the solver's variables y = (θ, friction terms), and ∂x/∂y.
  Eigen::VectorXd parameters(const Eigen::VectorXd& y, Eigen::MatrixXd* jacobian) const {
    Eigen::VectorXd x = y;
    Eigen::Matrix<double, 10, 10> dpi;
    x.head<10>() = parameters_of_log_cholesky(y.head<10>(), jacobian ? &dpi : nullptr);
    if (jacobian) {
      jacobian->setIdentity(y.size(), y.size());
      jacobian->topLeftCorner<10, 10>() = dpi;
    }
    return x;
  }
  int operator()(const Eigen::VectorXd& y, Eigen::VectorXd& residual) const {
    const Eigen::VectorXd x = parameters(y, nullptr);
    residual.resize(values());
    residual << R_scaled * x - c, hold * (x - x_prior);
    return 0;
  }
  int df(const Eigen::VectorXd& y, Eigen::MatrixXd& jacobian) const {
    Eigen::MatrixXd dx;
    parameters(y, &dx);
    jacobian.resize(values(), inputs());
    jacobian << R_scaled * dx, hold * dx;
    return 0;
  }
};

/// The measured coordinates: `measured` checked, or every coordinate.
inline std::vector<int> measured_coordinates(const Model<double>& model, const std::vector<int>& measured) {
  std::vector<int> out = measured;
  if (out.empty())
    for (int k = 0; k < model.nv; ++k) out.push_back(k);
  std::vector<char> seen(model.nv, 0);
  for (int k : out) {
    if (k < 0 || k >= model.nv || seen[k]) throw std::invalid_argument("measured: coordinate " + std::to_string(k) + " is out of range or repeated");
    seen[k] = 1;
  }
  return out;
}

inline void check_samples(const Model<double>& model, const PayloadSamples& s, int parameters, int measured) {
  const Eigen::Index n = s.position.cols();
  const std::pair<const char*, const Eigen::MatrixXd*> parts[] = {
      {"velocity", &s.velocity}, {"acceleration", &s.acceleration}, {"effort", &s.effort}};
  if (s.position.rows() != model.nq)
    throw std::invalid_argument("samples: position has " + std::to_string(s.position.rows()) + " rows for " +
                                std::to_string(model.nq) + " coordinates");
  for (const auto& [name, m] : parts)
    if (m->rows() != model.nv || m->cols() != n)
      throw std::invalid_argument(std::string("samples: ") + name + " is " + std::to_string(m->rows()) + " × " +
                                  std::to_string(m->cols()) + ", not " + std::to_string(model.nv) + " × " + std::to_string(n));
  if (n * measured < parameters)
    throw std::invalid_argument("samples: " + std::to_string(n) + " samples give " + std::to_string(n * measured) +
                                " equations, fewer than the " + std::to_string(parameters) + " parameters");
  const std::pair<const char*, const Eigen::MatrixXd*> all[] = {
      {"position", &s.position}, {"velocity", &s.velocity}, {"acceleration", &s.acceleration}, {"effort", &s.effort}};
  for (const auto& [name, m] : all)
    for (Eigen::Index k = 0; k < n; ++k)
      if (!m->col(k).allFinite()) throw std::invalid_argument(std::string("samples: ") + name + " of sample " + std::to_string(k) + " is not finite");
}

}  // namespace detail

/// Identifies the payload fixed to `frame` of `model` (which does not carry it) from the samples.
/// Throws std::invalid_argument naming the field for bad samples, std::out_of_range for an unknown
/// frame, std::runtime_error when the fit does not converge.
inline PayloadIdentification identify_payload(const Model<double>& model, Data<double>& data, const std::string& frame,
                                              const PayloadSamples& samples, const PayloadIdentificationOptions& options = {}) {
  if (!model.hasFrame(frame)) throw std::out_of_range("unknown frame '" + frame + "'");
  const std::vector<int> measured = detail::measured_coordinates(model, options.measured);
  const int nm = static_cast<int>(measured.size()), p = 10 + (options.identify_friction ? 2 * nm : 0);
  detail::check_samples(model, samples, p, nm);
  const Eigen::Index n = samples.position.cols(), rows = n * nm;

  // τ_measured − τ_model = A x, stacked
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(rows, p);
  Eigen::VectorXd b(rows);
  for (Eigen::Index s = 0; s < n; ++s) {
    const auto q = samples.position.col(s), qd = samples.velocity.col(s), qdd = samples.acceleration.col(s);
    payload_regressor(model, data, q, qd, qdd, frame);
    rnea(model, data, q, qd, qdd);
    if (!options.identify_friction) actuator_forces(model, data, qd);
    for (int r = 0; r < nm; ++r) {
      const int k = measured[r];
      const Eigen::Index row = s * nm + r;
      A.block<1, 10>(row, 0) = data.Y_payload.row(k);
      b[row] = samples.effort(k, s) - data.tau[k] - (options.identify_friction ? 0.0 : data.actuator_force[k]);
      if (!options.identify_friction) continue;
      A(row, 10 + r) = data.Y_actuator(k, 1);       // damping · q̇
      A(row, 10 + nm + r) = data.Y_actuator(k, 2);  // friction · ramp(q̇)
    }
  }

  // 1. columns scaled (z = D x), reduced by QR: ‖A x − b‖² = ‖R z − c‖² + const
  if (!(options.length_scale > 0) || !std::isfinite(options.length_scale))
    throw std::invalid_argument("length_scale: must be finite and above zero");
  const Eigen::VectorXd norms = payload_column_scales(A, options.length_scale);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(A * norms.cwiseInverse().asDiagonal());
  const Eigen::MatrixXd R = qr.matrixQR().topRows(p).triangularView<Eigen::Upper>();
  const Eigen::VectorXd Qtb = qr.householderQ().transpose() * b;
  const Eigen::VectorXd c = Qtb.head(p);

  // 2. identifiable directions
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  int rank = 0;
  while (rank < p && sigma[rank] >= options.singular_value_tolerance * sigma[0] && sigma[rank] > 0) ++rank;
  PayloadIdentification out;
  out.condition_number = sigma[p - 1] > 0 ? sigma[0] / sigma[p - 1] : std::numeric_limits<double>::infinity();
  const Eigen::MatrixXd V_id = svd.matrixV().leftCols(rank), V_null = svd.matrixV().rightCols(p - rank);
  const std::vector<std::string> names = payload_parameter_names(model, options.identify_friction, measured);
  std::vector<bool> held(p, false);
  for (int j = 0; j < p && rank < p; ++j)  // (a row of a matrix without columns is not formed)
    if (V_null.row(j).squaredNorm() > 0.01) {
      held[j] = true;
      out.unidentifiable.push_back(names[j]);
    }

  Eigen::VectorXd x_prior(p);
  x_prior.head<10>() = [&] {
    InertialParameters pi = InertialParameters::Zero();
    if (options.prior.mass > 0) payload_inertia(frame, options.prior).toParameters(pi.data());
    return pi;
  }();
  for (int r = 0; r < nm && options.identify_friction; ++r) {
    x_prior[10 + r] = model.damping[measured[r]];
    x_prior[10 + nm + r] = model.friction[measured[r]];
  }

  // 3. the unconstrained solution (held directions at the prior), made physical, refined physically
  const Eigen::VectorXd z_prior = norms.cwiseProduct(x_prior);
  const Eigen::VectorXd z_linear =
      z_prior + V_id * (svd.matrixU().leftCols(rank).transpose() * (c - R * z_prior)).cwiseQuotient(sigma.head(rank));
  const Eigen::VectorXd x_linear = z_linear.cwiseQuotient(norms);
  Eigen::VectorXd y = x_linear;
  y.head<10>() = log_cholesky_of_parameters(x_linear.head<10>());
  detail::ReducedPayloadProblem problem(R * norms.asDiagonal(), c, sigma[0] * V_null.transpose() * norms.asDiagonal(), x_prior);
  Eigen::LevenbergMarquardt<detail::ReducedPayloadProblem> solver(problem);
  solver.setMaxfev(options.max_evaluations);
  solver.setXtol(1e-14);
  solver.setFtol(1e-15);
  const Eigen::LevenbergMarquardtSpace::Status status = solver.minimize(y);
  out.evaluations = static_cast<int>(solver.nfev());
  const Eigen::VectorXd x = problem.parameters(y, nullptr);
  if (status == Eigen::LevenbergMarquardtSpace::ImproperInputParameters ||
      status == Eigen::LevenbergMarquardtSpace::TooManyFunctionEvaluation || !x.allFinite())
    throw std::runtime_error("the payload fit did not converge (" + std::to_string(out.evaluations) +
                             " evaluations; the samples may not excite the payload, or disagree with a rigid body)");

  // 4. residual and standard deviations
  const Eigen::VectorXd residual = b - A * x;
  out.residual_rms.resize(nm);
  for (int r = 0; r < nm; ++r)
    out.residual_rms[r] = std::sqrt(Eigen::Map<const Eigen::VectorXd, 0, Eigen::InnerStride<>>(residual.data() + r, n,
                                                                                              Eigen::InnerStride<>(nm)).squaredNorm() / n);
  const double variance = residual.squaredNorm() / std::max<double>(1.0, static_cast<double>(rows - rank));
  const Eigen::MatrixXd cov_z = variance * V_id * sigma.head(rank).cwiseAbs2().cwiseInverse().asDiagonal() * V_id.transpose();
  const Eigen::MatrixXd cov_x = norms.cwiseInverse().asDiagonal() * cov_z * norms.cwiseInverse().asDiagonal();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Eigen::VectorXd stddev = cov_x.diagonal().cwiseSqrt();
  for (int j = 0; j < p; ++j)
    if (held[j]) stddev[j] = nan;

  out.parameters = x.head<10>();
  out.parameter_stddev = stddev.head<10>();
  Eigen::Matrix<double, 10, 10> G;
  const Eigen::Matrix<double, 10, 1> fields = detail::payload_fields(out.parameters, &G);
  const Eigen::Matrix<double, 10, 10> cov_pi = cov_x.topLeftCorner<10, 10>();
  Eigen::Matrix<double, 10, 1> field_stddev = (G * cov_pi * G.transpose()).diagonal().cwiseSqrt();
  for (int f = 0; f < 10; ++f)
    for (int j = 0; j < 10; ++j)
      if (held[j] && G(f, j) != 0.0) field_stddev[f] = nan;
  out.payload = detail::payload_of_fields(fields);
  out.stddev = detail::payload_of_fields(field_stddev);
  // Physical by construction, but the fields are formed in double: with efforts that overflow them,
  // or a body so close to the edge that rounding leaves it outside, there is no answer to give.
  const std::string unphysical = inertia_problem(out.payload.mass, out.payload.center_of_mass, out.payload.inertia);
  if (!fields.allFinite() || !(out.payload.mass > 0) || !unphysical.empty())
    throw std::domain_error("the identified payload is not a body in double precision (" +
                            (unphysical.empty() ? std::string("mass or centre of mass not finite") : unphysical) +
                            "): the efforts or the motion are out of a rigid payload's range");
  if (options.identify_friction) {
    out.damping = x.segment(10, nm);
    out.friction = x.segment(10 + nm, nm);
    out.damping_stddev = stddev.segment(10, nm);
    out.friction_stddev = stddev.segment(10 + nm, nm);
  }
  return out;
}

}  // namespace spatial_dynamics
