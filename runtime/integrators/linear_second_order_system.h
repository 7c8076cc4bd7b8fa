// A linear second-order system M q'' + C q' + K q = P(t) (a beam, original
// or adjusted), presented to the first-order integrators as y = [q; q'], with
// the exact solve of the implicit stage (one Newton iteration is exact).
#pragma once

#include <Eigen/Core>

#include "runtime/integrators/ode_system.h"

namespace mbfe::runtime {

/// A linear second-order system M q'' + C q' + K q = P(t), presented to the
/// first-order integrators as y = [q; q'] (size() == 2 dof()).
class LinearSecondOrderSystem : public OdeSystem {
 public:
  /// Number of coordinates q.
  virtual int dof() const = 0;
  /// out = P(t) (N).
  virtual void load(double t, Eigen::VectorXd& out) = 0;
  /// out = M x, C x, K x.
  virtual void mult_m(const Eigen::VectorXd& x, Eigen::VectorXd& out) = 0;
  virtual void mult_c(const Eigen::VectorXd& x, Eigen::VectorXd& out) = 0;
  virtual void mult_k(const Eigen::VectorXd& x, Eigen::VectorXd& out) = 0;
  /// Solves (a M + b C + c K) x = r. Implementations factorise once per
  /// distinct (a, b, c) and reuse the factor. @throws std::runtime_error if singular.
  virtual void solve_combination(double a, double b, double c, const Eigen::VectorXd& r,
                                 Eigen::VectorXd& x) = 0;

  int size() const override { return 2 * dof(); }
  /// Default: ydot = [v; M^-1 (P - C v - K q)] through the members above.
  void rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) override;
  /// Exact: (I - c J) x = b with J = [0 I; -M^-1 K -M^-1 C] reduces to
  /// (M + c C + c^2 K) x_v = M b_v - c K b_q, x_q = b_q + c x_v.
  void solve_shifted(double t, const Eigen::VectorXd& y, double c, const Eigen::VectorXd& b,
                     Eigen::VectorXd& x) override;

 private:
  Eigen::VectorXd w1_, w2_, w3_;  // scratch of the default rhs / solve_shifted
};

}  // namespace mbfe::runtime
