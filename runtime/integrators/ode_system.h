// What an integrator steps: a first-order system y' = f(t, y).
//
// Second-order models M q'' + C q' + K q = P (beams) and
// M(q) q'' + F(q, q') = Q(q, q', t) (rigid chains, coupled models) present
// themselves with y = [q; q'] (position block first, then velocities).
#pragma once

#include <Eigen/Core>
#include <string>

namespace mbfe::runtime {

class OdeSystem {
 public:
  virtual ~OdeSystem() = default;

  /// Length of y.
  virtual int size() const = 0;

  /// ydot = f(t, y). @throws std::runtime_error (or a subclass) for a numerical
  /// fault the user must hear about (singular mass matrix, ...).
  virtual void rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) = 0;

  /// Implicit methods: solve (I - c J) x = b with J = df/dy at (t, y).
  /// The default forms J by finite differences and a dense LU; linear systems
  /// override it with a factorisation reused for a fixed c.
  virtual void solve_shifted(double t, const Eigen::VectorXd& y, double c,
                             const Eigen::VectorXd& b, Eigen::VectorXd& x);

  /// Called after each accepted step; systems with algebraic constraints
  /// project y back onto them here. Default: nothing.
  virtual void after_step(double /*t*/, Eigen::VectorXd& /*y*/) {}

  /// Names of the entries of y, for CSV headers.
  virtual std::string name(int i) const { return "y" + std::to_string(i); }
};

}  // namespace mbfe::runtime
