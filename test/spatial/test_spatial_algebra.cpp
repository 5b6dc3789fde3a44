// Unit tests of the spatial algebra against Featherstone 2010's identities, 6×6 matrix forms and
// 3-D vector formulas computed independently in the tests.
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "spatial_dynamics/spatial.hpp"
#include "test_utils.hpp"

namespace sd = spatial_dynamics;
using sd::ForceVector;
using sd::MotionVector;
using sd::PluckerTransform;
using sd::RigidInertia;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

namespace {

constexpr int kTrials = 200;

struct Random {
  std::mt19937 rng{20261122};
  std::uniform_real_distribution<double> u{-1.0, 1.0};

  double scalar() { return u(rng); }
  Vector3d vec3() { return Vector3d(u(rng), u(rng), u(rng)); }
  MotionVector<double> motion() { return {vec3(), vec3()}; }
  ForceVector<double> force() { return {vec3(), vec3()}; }
  Matrix3d rotation() {
    Eigen::Quaterniond q(u(rng), u(rng), u(rng), u(rng));
    return q.normalized().toRotationMatrix();
  }
  PluckerTransform<double> transform() { return {rotation(), vec3()}; }
  /// A physically valid rotational inertia about the centre of mass: a box, rotated.
  Matrix3d inertia_about_com(double mass) {
    const Vector3d d = vec3().cwiseAbs() + Vector3d::Constant(0.05);
    const Vector3d moments(mass / 12 * (d.y() * d.y() + d.z() * d.z()), mass / 12 * (d.x() * d.x() + d.z() * d.z()),
                           mass / 12 * (d.x() * d.x() + d.y() * d.y()));
    const Matrix3d R = rotation();
    return R * moments.asDiagonal() * R.transpose();
  }
  RigidInertia<double> inertia() {
    const double m = 0.1 + std::abs(scalar()) * 5;
    return RigidInertia<double>::FromMassCenterInertia(m, vec3(), inertia_about_com(m));
  }
};

Vector6d vec(const MotionVector<double>& m) { return m.toVector(); }
Vector6d vec(const ForceVector<double>& f) { return f.toVector(); }

double rel(const Vector6d& x, const Vector6d& ref) { return sd_test::relative_error(x, ref); }
double rel(const Matrix6d& x, const Matrix6d& ref) { return sd_test::relative_error(x, ref); }

/// ^0X_B at time t for a body moving with constant spatial velocity v (fixed coordinates) whose
/// frame coincides with the fixed frame at t = 0: the twist exponential of (ω, v_O).
PluckerTransform<double> screw_motion_base_to_body(const MotionVector<double>& v, double t) {
  const Vector3d& w = v.angular;
  const double theta = w.norm() * t;
  const Matrix3d R = Eigen::AngleAxisd(theta, w.normalized()).toRotationMatrix();
  const Vector3d d = (Matrix3d::Identity() - R) * w.cross(v.linear.eigen()) / w.squaredNorm() +
                     w * w.dot(v.linear.eigen()) / w.squaredNorm() * t;
  return PluckerTransform<double>::FromPose(R, d);  // ^BX_0 from the pose of B in 0
}

}  // namespace

// The seed's two-body example: bodies B1 and B2 rigidly joined and pushed by a force f (given
// as n_O and f about the origin O). 3-D route: composite mass, centre of mass and rotational
// inertia by the parallel-axis theorem, then Newton and Euler about the centre of mass, then the
// spatial acceleration at O. Spatial route: a = (I1 + I2)^-1 (f − v ×* (I1 + I2) v).
TEST(SpatialAlgebra, TwoBodyExampleThreeDAgreesWithSpatial) {
  Random r;
  double worst = 0;
  for (int trial = 0; trial < kTrials; ++trial) {
    const double m1 = 0.5 + std::abs(r.scalar()), m2 = 0.5 + std::abs(r.scalar());
    const Vector3d c1 = r.vec3(), c2 = r.vec3();
    const Matrix3d J1 = r.inertia_about_com(m1), J2 = r.inertia_about_com(m2);
    const MotionVector<double> v = r.motion();
    const ForceVector<double> f = r.force();

    // 3-D vectors.
    const double m = m1 + m2;
    const Vector3d c = (m1 * c1 + m2 * c2) / m;
    auto parallel_axis = [](double mass, const Vector3d& d) {
      return mass * (d.squaredNorm() * Matrix3d::Identity() - d * d.transpose());
    };
    const Matrix3d Jc = J1 + parallel_axis(m1, c1 - c) + J2 + parallel_axis(m2, c2 - c);
    const Vector3d& w = v.angular;
    const Vector3d c_dot = v.linear + w.cross(c);                           // velocity of the centre of mass
    const Vector3d n_c = f.angular.eigen() - c.cross(f.linear.eigen());                      // moment about the centre of mass
    const Vector3d w_dot = Jc.ldlt().solve(n_c - w.cross(Jc * w));           // Euler
    const Vector3d c_ddot = f.linear / m;                                    // Newton
    const Vector3d a_O = c_ddot - w_dot.cross(c) - w.cross(c_dot);           // spatial linear acceleration at O
    Vector6d a_3d;
    a_3d << w_dot, a_O;

    // Spatial vectors.
    const RigidInertia<double> I = RigidInertia<double>::FromMassCenterInertia(m1, c1, J1) +
                                   RigidInertia<double>::FromMassCenterInertia(m2, c2, J2);
    const Vector6d a_6d = I.toMatrix().ldlt().solve(vec(f - sd::cross(v, I * v)));

    worst = std::max(worst, rel(a_6d, a_3d));
  }
  EXPECT_LE(worst, 1e-12);
}

TEST(SpatialAlgebra, ScalarProductIsInvariantUnderTransform) {  // eq. (3): (X m)·(X* f) = m·f
  Random r;
  for (int trial = 0; trial < kTrials; ++trial) {
    const PluckerTransform<double> X = r.transform();
    const MotionVector<double> m = r.motion();
    const ForceVector<double> f = r.force();
    const double before = sd::dot(m, f);
    EXPECT_NEAR(sd::dot(X.apply(m), X.apply(f)), before, 1e-13 * (1 + std::abs(before)));
    // X*ᵀ X = 1 as matrices.
    EXPECT_LE((X.toForceMatrix().transpose() * X.toMotionMatrix() - Matrix6d::Identity()).norm(), 1e-14);
  }
}

TEST(SpatialAlgebra, TransformMatchesEquations11And12) {
  Random r;
  for (int trial = 0; trial < kTrials; ++trial) {
    const Matrix3d E = r.rotation();
    const Vector3d p = r.vec3();
    const PluckerTransform<double> X(E, p);
    // eq. (11) written out with 3×3 blocks.
    Matrix6d X_motion = Matrix6d::Zero();
    X_motion.topLeftCorner<3, 3>() = E;
    X_motion.bottomLeftCorner<3, 3>() = -E * sd::skew(p);
    X_motion.bottomRightCorner<3, 3>() = E;
    EXPECT_LE(rel(X.toMotionMatrix(), X_motion), 1e-15);
    // eq. (2): X* = X^-T.
    EXPECT_LE(rel(X.toForceMatrix(), X_motion.inverse().transpose()), 1e-13);

    const MotionVector<double> m = r.motion();
    const ForceVector<double> f = r.force();
    EXPECT_LE(rel(vec(X.apply(m)), X_motion * vec(m)), 1e-14);
    EXPECT_LE(rel(vec(X.apply(f)), X.toForceMatrix() * vec(f)), 1e-14);
    EXPECT_LE(rel(vec(X.applyInverse(m)), X_motion.inverse() * vec(m)), 1e-13);
    EXPECT_LE(rel(vec(X.applyInverse(f)), X_motion.transpose() * vec(f)), 1e-14);
    EXPECT_LE(rel(X.inverse().toMotionMatrix(), X_motion.inverse()), 1e-13);

    const PluckerTransform<double> Y = r.transform();
    EXPECT_LE(rel((Y * X).toMotionMatrix(), Y.toMotionMatrix() * X_motion), 1e-14);
  }
}

TEST(SpatialAlgebra, TransformFromPoseMovesPointsAsExpected) {
  // A frame B at position p with axes R in A: a pure linear velocity field's value at B's origin
  // is the same vector rotated into B; a rotation about A's origin gives v_B = Rᵀ(ω × p).
  Random r;
  const Matrix3d R = r.rotation();
  const Vector3d p = r.vec3();
  const auto X = PluckerTransform<double>::FromPose(R, p);
  const Vector3d w = r.vec3();
  const MotionVector<double> in_B = X.apply(MotionVector<double>(w, Vector3d::Zero()));
  EXPECT_LE((in_B.angular - R.transpose() * w).norm(), 1e-15);
  EXPECT_LE((in_B.linear - R.transpose() * w.cross(p)).norm(), 1e-15);
}

TEST(SpatialAlgebra, CrossProducts) {
  Random r;
  for (int trial = 0; trial < kTrials; ++trial) {
    const MotionVector<double> v = r.motion(), m = r.motion();
    const ForceVector<double> f = r.force();
    EXPECT_EQ(vec(sd::cross(v, v)), Vector6d::Zero());                                   // v × v = 0
    EXPECT_LE(rel(vec(sd::cross(v, m)), sd::motion_cross_matrix(v) * vec(m)), 1e-15);     // eq. (17)
    EXPECT_LE(rel(vec(sd::cross(v, f)), sd::force_cross_matrix(v) * vec(f)), 1e-15);      // eq. (18)
    EXPECT_EQ(sd::force_cross_matrix(v), Matrix6d(-sd::motion_cross_matrix(v).transpose()));  // v×* = −(v×)ᵀ
    // (v×)(6×6) equals the block form [ω× 0; v× ω×] built from 3-D cross products.
    for (int k = 0; k < 6; ++k) {
      Vector6d e = Vector6d::Zero();
      e[k] = 1;
      const MotionVector<double> ek(e);
      Vector6d expected;
      expected << v.angular.cross(ek.angular).eigen(), (v.angular.cross(ek.linear) + v.linear.cross(ek.angular)).eigen();
      EXPECT_LE((sd::motion_cross_matrix(v).col(k) - expected).norm(), 1e-15);
    }
  }
}

TEST(SpatialAlgebra, RigidInertiaMatchesEquation25AndThreeDFormulas) {
  Random r;
  for (int trial = 0; trial < kTrials; ++trial) {
    const double m = 0.1 + std::abs(r.scalar());
    const Vector3d c = r.vec3();
    const Matrix3d Jc = r.inertia_about_com(m);
    const RigidInertia<double> I = RigidInertia<double>::FromMassCenterInertia(m, c, Jc);
    // eq. (25) as a matrix.
    Matrix6d expected;
    expected << Jc + m * sd::skew(c) * sd::skew(c).transpose(), m * sd::skew(c), m * sd::skew(c).transpose(),
        m * Matrix3d::Identity();
    EXPECT_LE(rel(I.toMatrix(), expected), 1e-15);
    EXPECT_LE((I.centerOfMass() - c).norm(), 1e-14);
    EXPECT_LE((I.inertiaAboutCenterOfMass() - Jc).norm(), 1e-14);

    const MotionVector<double> v = r.motion();
    const Vector3d c_dot = v.linear + v.angular.cross(c);
    // Momentum (eq. 23): angular momentum about O = Ī_c ω + c × m ċ; linear = m ċ.
    const ForceVector<double> h = sd::momentum(I, v);
    EXPECT_LE((h.angular.eigen() - (Jc * v.angular.eigen() + c.cross(m * c_dot))).norm(), 1e-14);
    EXPECT_LE((h.linear - m * c_dot).norm(), 1e-14);
    // Kinetic energy (eq. 28) = ½ m |ċ|² + ½ ωᵀ Ī_c ω.
    const double T = 0.5 * m * c_dot.squaredNorm() + 0.5 * v.angular.eigen().dot(Jc * v.angular.eigen());
    EXPECT_NEAR(sd::kinetic_energy(I, v), T, 1e-14 * T);
    // Gravity: f_g = I a_g = (c × m g ; m g).
    const Vector3d g(0, 0, -9.81);
    const ForceVector<double> fg = sd::gravity_force(I, g);
    EXPECT_LE((fg.angular - c.cross(m * g)).norm(), 1e-13);
    EXPECT_LE((fg.linear - m * g).norm(), 1e-14);
  }
}

TEST(SpatialAlgebra, CompositeInertiaIsTheSum) {  // eq. (24)
  Random r;
  for (int trial = 0; trial < kTrials; ++trial) {
    const RigidInertia<double> I1 = r.inertia(), I2 = r.inertia();
    EXPECT_LE(rel((I1 + I2).toMatrix(), I1.toMatrix() + I2.toMatrix()), 1e-15);
    // Composite mass and centre of mass as the 3-D formulas give them.
    const RigidInertia<double> sum = I1 + I2;
    EXPECT_DOUBLE_EQ(sum.mass, I1.mass + I2.mass);
    const Vector3d c = (I1.mass * I1.centerOfMass() + I2.mass * I2.centerOfMass()) / (I1.mass + I2.mass);
    EXPECT_LE((sum.centerOfMass() - c).norm(), 1e-14);
    // Transforming a sum is the sum of the transforms (eq. 26 is linear).
    const PluckerTransform<double> X = r.transform();
    EXPECT_LE(rel(X.apply(sum).toMatrix(), X.apply(I1).toMatrix() + X.apply(I2).toMatrix()), 1e-14);
  }
}

TEST(SpatialAlgebra, InertiaTransformMatchesEquation26) {  // I_B = X* I_A X^-1
  Random r;
  for (int trial = 0; trial < kTrials; ++trial) {
    const PluckerTransform<double> X = r.transform();
    const RigidInertia<double> I = r.inertia();
    const Matrix6d expected = X.toForceMatrix() * I.toMatrix() * X.toMotionMatrix().inverse();
    EXPECT_LE(rel(X.apply(I).toMatrix(), expected), 1e-13);
    EXPECT_LE(rel(X.applyInverse(I).toMatrix(), X.toMotionMatrix().transpose() * I.toMatrix() * X.toMotionMatrix()),
              1e-13);
    EXPECT_LE(rel(X.applyInverse(X.apply(I)).toMatrix(), I.toMatrix()), 1e-13);
    // The accumulating form: out += Xᵀ I X, onto another body's inertia.
    RigidInertia<double> base = r.inertia();
    base.rotational_inertia = (base.rotational_inertia + base.rotational_inertia.transpose()) * 0.5;
    RigidInertia<double> sum = base;
    X.applyInverseAdd(I, sum);
    EXPECT_LE(rel(sum.toMatrix(), base.toMatrix() + X.toMotionMatrix().transpose() * I.toMatrix() * X.toMotionMatrix()),
              1e-13);
    EXPECT_EQ(sum.rotational_inertia, sum.rotational_inertia.transpose());  // symmetric stays exactly symmetric
    // A massless body with rotational inertia only transforms without dividing by its mass.
    const RigidInertia<double> rotor(0.0, Vector3d::Zero(), Matrix3d::Identity());
    EXPECT_TRUE(X.apply(rotor).toMatrix().allFinite());
    // Articulated inertia: Xᵀ Iᴬ X for a general symmetric 6×6 matrix.
    Matrix6d A = Matrix6d::Random();
    A = (A * A.transpose()).eval();
    const sd::ArticulatedInertia<double> IA(A);
    EXPECT_LE(rel(X.applyInverse(IA).matrix(), X.toMotionMatrix().transpose() * A * X.toMotionMatrix()), 1e-13);
    const MotionVector<double> v = r.motion();
    EXPECT_LE(rel(vec(IA * v), A * vec(v)), 1e-14);
  }
}

// eq. (27): a body moving with velocity v has, in fixed coordinates, d/dt I = v×* I − I v×.
// Checked by central differences of I(t) along the exact screw motion of the body.
TEST(SpatialAlgebra, InertiaTimeDerivativeByFiniteDifferences) {
  Random r;
  const double h = 1e-5;
  for (int trial = 0; trial < 50; ++trial) {
    const RigidInertia<double> I = r.inertia();
    const MotionVector<double> v = r.motion();
    const Matrix6d I_plus = screw_motion_base_to_body(v, h).applyInverse(I).toMatrix();
    const Matrix6d I_minus = screw_motion_base_to_body(v, -h).applyInverse(I).toMatrix();
    const Matrix6d numeric = (I_plus - I_minus) / (2 * h);
    EXPECT_LE(rel(sd::inertia_time_derivative(I, v), numeric), 1e-8);
  }
}

// RigidInertia::rate(v), İ in eq. (25)'s ten-parameter form with m = 0, against eq. (27) on 6×6
// matrices, v×* I − I v×, and a sum of rates is the rate of the sum (the Coriolis matrix's İᶜ).
TEST(SpatialAlgebra, InertiaRateIsEq27InTenParameters) {
  Random r;
  for (int trial = 0; trial < 50; ++trial) {
    const RigidInertia<double> I = r.inertia(), J = r.inertia();
    const MotionVector<double> v = r.motion();
    const RigidInertia<double> rate = I.rate(v);
    EXPECT_EQ(rate.mass, 0.0);
    EXPECT_LE(rel(rate.toMatrix(), sd::inertia_time_derivative(I, v)), 1e-14);
    EXPECT_LE(rel((I + J).rate(v).toMatrix(), (I.rate(v) + J.rate(v)).toMatrix()), 1e-14);
  }
}

// eq. (29): f = d/dt (I v) = I a + v ×* I v, by central differences of the momentum of a body
// whose velocity changes as v + t a while it moves.
TEST(SpatialAlgebra, EquationOfMotionByFiniteDifferences) {
  Random r;
  const double h = 1e-5;
  for (int trial = 0; trial < 50; ++trial) {
    const RigidInertia<double> I = r.inertia();
    const MotionVector<double> v = r.motion(), a = r.motion();
    auto momentum_at = [&](double t) {
      const RigidInertia<double> I_t = screw_motion_base_to_body(v, t).applyInverse(I);
      return vec(sd::momentum(I_t, v + a * t));
    };
    const Vector6d numeric = (momentum_at(h) - momentum_at(-h)) / (2 * h);
    EXPECT_LE(rel(vec(sd::equation_of_motion(I, v, a)), numeric), 1e-8);
  }
}

TEST(SpatialAlgebra, WorksInOtherScalarTypes) {
  Random r;
  const PluckerTransform<double> X = r.transform();
  const MotionVector<double> m = r.motion();
  const PluckerTransform<float> Xf = X.cast<float>();
  const MotionVector<float> mf = m.cast<float>();
  const Eigen::Matrix<float, 6, 1> in_float = Xf.apply(mf).toVector();
  EXPECT_LE(sd_test::relative_error(in_float.cast<double>(), vec(X.apply(m))), 1e-6);
  const PluckerTransform<long double> Xl = X.cast<long double>();
  const Eigen::Matrix<long double, 6, 1> in_long = Xl.apply(m.cast<long double>()).toVector();
  EXPECT_LE(sd_test::relative_error(in_long.cast<double>(), vec(X.apply(m))), 1e-15);
}

// The 3-vector and 3×3 matrix the spatial types are made of, against Eigen's operations on the
// same operands (the AVX2+FMA build's fused products may round differently: 4 ε relative).
TEST(Vec3AndMat3, OperationsMatchEigen) {
  Random r;
  const auto close = [](const Vector3d& got, const Vector3d& want) {
    return (got - want).norm() <= 4 * std::numeric_limits<double>::epsilon() * (1 + want.norm());
  };
  for (int t = 0; t < kTrials; ++t) {
    const Vector3d a = r.vec3(), b = r.vec3();
    const Matrix3d A = r.rotation() * 3.0 + Matrix3d::Constant(r.scalar()), B = r.rotation();
    const double k = r.scalar();
    const sd::Vec3<double> va(a), vb(b);
    const sd::Mat3<double> mA(A), mB(B);
    EXPECT_TRUE(va.eigen() == a && mA.eigen() == A);  // conversions are exact
    EXPECT_TRUE(close(va + vb, a + b) && close(va - vb, a - b) && close(-va, -a) && close(va * k, a * k));
    EXPECT_TRUE(close(sd::cross(va, vb), a.cross(b)) && close(va.cross(vb), a.cross(b)));
    EXPECT_NEAR(sd::dot(va, vb), a.dot(b), 4e-16);
    EXPECT_TRUE(close(mA * vb, A * b) && close(mA.transposeTimes(vb), A.transpose() * b));
    EXPECT_LE(((mA * mB).eigen() - A * B).norm(), 1e-14);
    EXPECT_LE(((mA.transposeTimes(mB)).eigen() - A.transpose() * B).norm(), 1e-14);
    EXPECT_TRUE(mA.transpose().eigen() == A.transpose());
    EXPECT_TRUE(sd::Mat3<double>::Skew(va).eigen() == sd::skew(a));
    for (int c = 0; c < 3; ++c)
      for (int row = 0; row < 3; ++row) EXPECT_EQ(mA(row, c), A(row, c));
    // The pad lane of a double Vec3 stays zero through the operations (it never reaches x, y, z).
    const sd::Vec3<double> combined = sd::cross(va, vb) + mA * va - vb * k;
    EXPECT_EQ(combined.lanes.x[3], 0.0);
  }
  sd::Vec3<double> written;
  written[1] = 2.5;  // a coordinate written through a reference, read back by a packed operation
  EXPECT_TRUE((written + sd::Vec3<double>::UnitX()).eigen() == Vector3d(1.0, 2.5, 0.0));
}
