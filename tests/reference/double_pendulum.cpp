// Derivation (Lagrange; equivalent to eqs (2)-(6) of the paper for this chain).
//
// Absolute angles th = T q with T = [[1, 0], [1, 1]]; e(a) = (cos a, sin a),
// n(a) = (-sin a, cos a) = de/da.
// Centres of mass:  x1 = h + c1 e(th1),  x2 = h + l1 e(th1) + c2 e(th2).
// Kinetic energy, with D = th2 - th1 = q2:
//   T = 1/2 A th1'^2 + B cos(D) th1' th2' + 1/2 D2 th2'^2,
//   A = I1 + m1 c1^2 + m2 l1^2,  B = m2 l1 c2,  D2 = I2 + m2 c2^2.
// In absolute angles M_abs = [[A, B cos D], [B cos D, D2]] and Lagrange gives
//   d/dt dT/dth1' - dT/dth1 = A th1'' + B cos D th2'' - B sin D th2'^2,
//   d/dt dT/dth2' - dT/dth2 = B cos D th1'' + D2 th2'' + B sin D th1'^2,
// so F_abs = B sin D [-th2'^2, th1'^2].
// Since T is constant, M = T^T M_abs T and F = T^T F_abs:
//   M11 = A + 2 B cos q2 + D2,  M12 = M21 = B cos q2 + D2,  M22 = D2,
//   F1 = B sin q2 (th1'^2 - th2'^2),  F2 = B sin q2 th1'^2,
// with th1' = q1', th2' = q1' + q2'.
// Gravity: V = -m1 g.x1 - m2 g.x2, Q_abs = -dV/dth:
//   Q_abs1 = (m1 c1 + m2 l1) g.n(th1),  Q_abs2 = m2 c2 g.n(th2),
//   Q = T^T Q_abs: Q1 = Q_abs1 + Q_abs2, Q2 = Q_abs2.
#include "tests/reference/double_pendulum.h"

#include <cmath>

namespace mbfe::reference {

namespace {
Eigen::Vector2d e_of(double a) { return {std::cos(a), std::sin(a)}; }
Eigen::Vector2d n_of(double a) { return {-std::sin(a), std::cos(a)}; }
}  // namespace

Eigen::Matrix2d mass_matrix(const DoublePendulumParams& p, const Eigen::Vector2d& q) {
  const double A = p.I1 + p.m1 * p.c1 * p.c1 + p.m2 * p.l1 * p.l1;
  const double B = p.m2 * p.l1 * p.c2;
  const double D2 = p.I2 + p.m2 * p.c2 * p.c2;
  const double c = std::cos(q(1));
  Eigen::Matrix2d M;
  M(0, 0) = A + 2.0 * B * c + D2;
  M(0, 1) = B * c + D2;
  M(1, 0) = M(0, 1);
  M(1, 1) = D2;
  return M;
}

Eigen::Vector2d inertial_forces(const DoublePendulumParams& p, const Eigen::Vector2d& q,
                                const Eigen::Vector2d& qd) {
  const double B = p.m2 * p.l1 * p.c2;
  const double s = std::sin(q(1));
  const double w1 = qd(0);
  const double w2 = qd(0) + qd(1);
  return {B * s * (w1 * w1 - w2 * w2), B * s * w1 * w1};
}

Eigen::Vector2d generalized_forces(const DoublePendulumParams& p, const Eigen::Vector2d& q) {
  const double th1 = q(0);
  const double th2 = q(0) + q(1);
  const double qa1 = (p.m1 * p.c1 + p.m2 * p.l1) * p.gravity.dot(n_of(th1));
  const double qa2 = p.m2 * p.c2 * p.gravity.dot(n_of(th2));
  return {qa1 + qa2, qa2};
}

double potential_energy(const DoublePendulumParams& p, const Eigen::Vector2d& q) {
  const double th1 = q(0);
  const double th2 = q(0) + q(1);
  const Eigen::Vector2d r1 = p.c1 * e_of(th1);
  const Eigen::Vector2d r2 = p.l1 * e_of(th1) + p.c2 * e_of(th2);
  return -p.m1 * p.gravity.dot(r1) - p.m2 * p.gravity.dot(r2);
}

Eigen::Vector2d link2_point(const DoublePendulumParams& p, const Eigen::Vector2d& q, double x) {
  return p.hinge + p.l1 * e_of(q(0)) + x * e_of(q(0) + q(1));
}

}  // namespace mbfe::reference
