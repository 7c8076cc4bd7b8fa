// What the implicit second-order steppers (second_order_steppers.cpp) step: a
// nonlinear, possibly constrained system in its own second-order form,
//
//   M(q) q'' + F(t, q, q') + G(q)^T lambda = 0,     Phi(q) = 0,
//
// with y = [q; q'] as OdeSystem sees it. Every method of the family (backward
// Euler, trapezoid, BDF2, generalized-alpha) writes the new position and rate
// as affine functions of the new acceleration a,
//
//   q = q_pred + c_q a,     q' = v_pred + c_v a,
//
// so one Newton iteration on (a, lambda) serves them all. Its matrix is
//
//   [ M + c_v C_t + c_q K_t   G^T ]      C_t = dF/dq',  K_t = d(M a + F + G^T lambda)/dq
//   [ G                        0  ]
//
// with the constraint rows divided by c_q (Phi / c_q, whose derivative in a is
// G): the scaling that keeps the matrix's condition independent of the step
// (Bottasso, Bauchau and Cardona, 2007). The system forms and factors it; the
// stepper decides when (docs/implicit-integration.md).
#pragma once

#include <Eigen/Core>

#include "runtime/integrators/simulation_result.h"

namespace mbfe::runtime {

class SecondOrderSystem {
 public:
  virtual ~SecondOrderSystem() = default;

  /// Coordinates (n) and constraint rows (m).
  virtual int dof() const = 0;
  virtual int num_multipliers() const = 0;

  /// Residuals at (t, q, q', a, lambda): r (n) of the equations of motion and
  /// c = Phi(q) / c_q (m). Coordinates whose motion is prescribed have the
  /// residual a_i - a_prescribed(t) instead.
  virtual void residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                        const Eigen::VectorXd& a, const Eigen::VectorXd& lambda, double c_q,
                        Eigen::VectorXd& r, Eigen::VectorXd& c) = 0;

  /// Forms and factors the iteration matrix above at the given state.
  /// @throws std::runtime_error if it is singular.
  virtual void factorize(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                         const Eigen::VectorXd& a, const Eigen::VectorXd& lambda, double c_q,
                         double c_v) = 0;

  /// [da; dlambda] = matrix^-1 [r; c] with the last factorisation.
  virtual void solve(const Eigen::VectorXd& r, const Eigen::VectorXd& c, Eigen::VectorXd& da,
                     Eigen::VectorXd& dlambda) = 0;

  /// The accelerations and multipliers of the state (q, q') at t: the
  /// consistent start of a step sequence.
  virtual void accelerations(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                             Eigen::VectorXd& a, Eigen::VectorXd& lambda) = 0;
};

}  // namespace mbfe::runtime
