// The generated solver of models/double_pendulum.yaml against the hand-coded
// reference (tests/reference/double_pendulum.cpp), plus a self-check of the
// reference (its F and Q against Lagrange's equations by finite differences).
#include "tests/reference/double_pendulum.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include <cmath>
#include <functional>
#include <random>

#include "runtime/abi/mbfe_model_abi.h"

#ifdef MBFE_HAVE_GENERATED_DOUBLE_PENDULUM
#include "frontend/parse_model.h"
extern "C" const mbfe_model_v1* mbfe_model_double_pendulum(void);
#endif

namespace mbfe::reference {
namespace {

using Vec2 = Eigen::Vector2d;

// The reference itself: F_i = sum_jk (dM_ij/dq_k - 1/2 dM_jk/dq_i) qd_j qd_k and
// Q = -dV/dq, derivatives by central differences.
TEST(DoublePendulumReference, MatchesLagrangeByFiniteDifferences) {
  // Central differences with step 1e-5 on O(1) functions: truncation ~1e-10,
  // round-off ~1e-16 / 1e-5 = 1e-11.
  constexpr double kFdTol = 1e-8;
  DoublePendulumParams p;
  p.m1 = 1.3; p.m2 = 0.7; p.l1 = 0.9; p.c1 = 0.4; p.c2 = 0.6; p.I1 = 0.05; p.I2 = 0.11;
  p.gravity = {0.8, -9.81};
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> ang(-M_PI, M_PI), rate(-3.0, 3.0);
  const double h = 1e-5;
  for (int trial = 0; trial < 50; ++trial) {
    const Vec2 q(ang(rng), ang(rng)), qd(rate(rng), rate(rng));
    std::array<Eigen::Matrix2d, 2> dM;
    Vec2 dV;
    for (int k = 0; k < 2; ++k) {
      const Vec2 e = Vec2::Unit(k) * h;
      dM[k] = (mass_matrix(p, q + e) - mass_matrix(p, q - e)) / (2 * h);
      dV(k) = (potential_energy(p, q + e) - potential_energy(p, q - e)) / (2 * h);
    }
    Vec2 f = Vec2::Zero();
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        for (int k = 0; k < 2; ++k) f(i) += (dM[k](i, j) - 0.5 * dM[i](j, k)) * qd(j) * qd(k);
    EXPECT_LT((inertial_forces(p, q, qd) - f).norm(), kFdTol * (1.0 + f.norm()));
    EXPECT_LT((generalized_forces(p, q) + dV).norm(), kFdTol * (1.0 + dV.norm()));
    // M symmetric positive definite.
    const Eigen::Matrix2d M = mass_matrix(p, q);
    EXPECT_EQ(M(0, 1), M(1, 0));
    EXPECT_GT(M.determinant(), 0.0);
  }
}

#ifdef MBFE_HAVE_GENERATED_DOUBLE_PENDULUM

using Deriv = std::function<Vec2(const Vec2& q, const Vec2& qd)>;  // qdd(q, qd)

// Classical RK4 on y = [q; qd], h fixed.
void rk4(const Deriv& qdd, double h, int steps, Vec2& q, Vec2& qd) {
  for (int i = 0; i < steps; ++i) {
    const Vec2 k1q = qd, k1v = qdd(q, qd);
    const Vec2 k2q = qd + 0.5 * h * k1v, k2v = qdd(q + 0.5 * h * k1q, qd + 0.5 * h * k1v);
    const Vec2 k3q = qd + 0.5 * h * k2v, k3v = qdd(q + 0.5 * h * k2q, qd + 0.5 * h * k2v);
    const Vec2 k4q = qd + h * k3v, k4v = qdd(q + h * k3q, qd + h * k3v);
    q += h / 6.0 * (k1q + 2.0 * k2q + 2.0 * k3q + k4q);
    qd += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
  }
}

// Both sides evaluate the same closed forms in double precision with a
// different order of operations; a few ulps of the largest entry.
constexpr double kRelTol = 1e-12;
// 1000 RK4 steps of the same ODE; per-step differences of ~1e-15 grow by the
// pendulum's (chaotic at this energy only mildly) sensitivity over 1 s.
constexpr double kTrajTol = 1e-9;

DoublePendulumParams params_from_model_file() {
  const ir::Model m =
      frontend::load_model_file(std::string(MBFE_SOURCE_DIR) + "/models/double_pendulum.yaml");
  EXPECT_EQ(m.bodies.size(), 2u);
  const ir::Body& b1 = m.bodies.at(0);
  const ir::Body& b2 = m.bodies.at(1);
  // The reference assumes revolute joints, link 1 hinged at the origin, link 2 at
  // [l1, 0] of link 1, centres of mass on the links' x axes.
  EXPECT_EQ(b1.joint.type, ir::JointType::kRevolute);
  EXPECT_EQ(b2.joint.type, ir::JointType::kRevolute);
  EXPECT_EQ(b2.parent, 0);
  EXPECT_EQ(b2.joint.at[1], 0.0);
  EXPECT_EQ(b1.com[1], 0.0);
  EXPECT_EQ(b2.com[1], 0.0);
  DoublePendulumParams p;
  p.hinge = {b1.joint.at[0], b1.joint.at[1]};
  p.m1 = b1.mass; p.m2 = b2.mass;
  p.I1 = b1.inertia; p.I2 = b2.inertia;
  p.c1 = b1.com[0]; p.c2 = b2.com[0];
  p.l1 = b2.joint.at[0];
  p.gravity = {m.gravity[0], m.gravity[1]};
  return p;
}

struct Generated {
  const mbfe_model_v1& m = *mbfe_model_double_pendulum();
  Eigen::Matrix2d M(const Vec2& q) const {
    double a[4];
    m.mass_matrix(q.data(), a);
    Eigen::Matrix2d out;
    out << a[0], a[1], a[2], a[3];
    return out;
  }
  Vec2 F(const Vec2& q, const Vec2& qd) const {
    Vec2 f;
    m.inertial_forces(q.data(), qd.data(), f.data());
    return f;
  }
  Vec2 Q(const Vec2& q, const Vec2& qd, double t) const {
    Vec2 f;
    m.generalized_forces(q.data(), qd.data(), t, f.data());
    return f;
  }
};

double rel_err(const Eigen::MatrixXd& got, const Eigen::MatrixXd& want) {
  // Relative to the largest entry: single entries cross zero (sin q2 = 0).
  const double scale = std::max(want.cwiseAbs().maxCoeff(), 1e-300);
  return (got - want).cwiseAbs().maxCoeff() / scale;
}

TEST(DoublePendulumGenerated, MatchesReferenceAtRandomStates) {
  const Generated gen;
  ASSERT_EQ(gen.m.num_coordinates, 2);
  const DoublePendulumParams p = params_from_model_file();
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> ang(-2 * M_PI, 2 * M_PI), rate(-10.0, 10.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec2 q(ang(rng), ang(rng)), qd(rate(rng), rate(rng));
    const double t = 0.01 * trial;
    EXPECT_LT(rel_err(gen.M(q), mass_matrix(p, q)), kRelTol) << "M at trial " << trial;
    EXPECT_LT(rel_err(gen.F(q, qd), inertial_forces(p, q, qd)), kRelTol)
        << "F at trial " << trial;
    EXPECT_LT(rel_err(gen.Q(q, qd, t), generalized_forces(p, q)), kRelTol)
        << "Q at trial " << trial;
  }
}

TEST(DoublePendulumGenerated, Rk4TrajectoryMatchesReference) {
  const Generated gen;
  const DoublePendulumParams p = params_from_model_file();
  const Vec2 q0(0.3, -0.4), qd0(0.5, 1.0);
  Vec2 qa = q0, va = qd0, qb = q0, vb = qd0;
  rk4([&](const Vec2& q, const Vec2& qd) -> Vec2 {
        return gen.M(q).ldlt().solve(gen.Q(q, qd, 0.0) - gen.F(q, qd));
      },
      1e-3, 1000, qa, va);
  rk4([&](const Vec2& q, const Vec2& qd) -> Vec2 {
        return mass_matrix(p, q).ldlt().solve(generalized_forces(p, q) - inertial_forces(p, q, qd));
      },
      1e-3, 1000, qb, vb);
  EXPECT_LT((qa - qb).cwiseAbs().maxCoeff(), kTrajTol);
  EXPECT_LT((va - vb).cwiseAbs().maxCoeff(), kTrajTol);
  // The trajectory actually moved (the comparison is not vacuous).
  EXPECT_GT((qb - q0).norm(), 0.1);
}

#endif  // MBFE_HAVE_GENERATED_DOUBLE_PENDULUM

}  // namespace
}  // namespace mbfe::reference
