// The step-by-step integrators of Section 5 of the paper (eqs (18)-(19)), plus
// RK4 and generalized-alpha, over an OdeSystem y' = f(t, y).
//
// Names accepted by parse_integrator() (and `--integrator`):
//   forward_euler      y_n = y_{n-1} + h f_{n-1}                      order 1, explicit
//   backward_euler     y_n = y_{n-1} + h f_n                          order 1, implicit, A-stable
//   explicit_midpoint  y_n = y_{n-2} + 2 h f_{n-1}                    order 2, explicit, two-step;
//                      the first step is one forward-Euler step (as the paper's Fig. 3)
//   trapezoid          y_n = y_{n-1} + h/2 (f_n + f_{n-1})            order 2, implicit, A-stable
//   rk4                classical 4-stage Runge-Kutta                  order 4, explicit
//   ab2, bdf2          Adams-Bashforth 2 and BDF2 (presets of lmm)
//   lmm:alpha=a0,..,ak:beta=b0,..,bk
//                      a general linear multistep method
//                      sum_{i=0..k} alpha_i y_{n+i} = h sum_{i=0..k} beta_i f_{n+i}
//                      (explicit when beta_k = 0); the first k-1 steps are taken with RK4
//   generalized_alpha  Chung-Hulbert for M q'' + C q' + K q = P(t) (a LinearSecondOrderSystem
//                      only); order 2, A-stable; spectral radius at infinity rho_inf in [0, 1]
//                      (default 0.9)
//
// Implicit methods solve their stage equation with Newton on
// g(y) = y - c f(t, y) - r through OdeSystem::solve_shifted; a LinearSecondOrderSystem
// is known to be linear, so one Newton iteration is exact and only one is taken.
// Linear systems factorise once per (step size, method) and reuse the factor.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

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

/// Coefficients of sum_{i=0..k} alpha_i y_{n+i} = h sum_{i=0..k} beta_i f_{n+i};
/// alpha and beta have k + 1 entries each, alpha_k != 0.
struct LmmCoefficients {
  std::vector<double> alpha;
  std::vector<double> beta;
  bool explicit_method() const { return beta.empty() || beta.back() == 0.0; }
  int steps() const { return static_cast<int>(alpha.size()) - 1; }
};

enum class IntegratorKind {
  kForwardEuler,
  kBackwardEuler,
  kExplicitMidpoint,
  kTrapezoid,
  kRk4,
  kLinearMultistep,
  kGeneralizedAlpha,
};

/// Which integrator, with its parameters.
struct IntegratorSpec {
  IntegratorKind kind = IntegratorKind::kRk4;
  std::string name = "rk4";  // canonical name, used in messages ("forward_euler", "lmm", ...)
  LmmCoefficients lmm;       // kLinearMultistep only
  double rho_inf = 0.9;      // kGeneralizedAlpha only, in [0, 1]
  /// Order of accuracy (global error ~ h^order).
  int order() const;
  bool implicit() const;
};

/// Parses an integrator name (see the list above). @throws std::invalid_argument
/// with a message naming the accepted names for anything else.
IntegratorSpec parse_integrator(const std::string& text);

/// The names parse_integrator() accepts (without the lmm:... form), for help texts.
std::vector<std::string> integrator_names();

/// One integrator bound to one system. reset() then step() repeatedly; steppers
/// with history (multistep, generalized-alpha) keep it inside. No allocation
/// happens in step() after the first call.
class Stepper {
 public:
  virtual ~Stepper() = default;
  /// Starts from y0 at t0. Must be called before step().
  virtual void reset(double t0, const Eigen::VectorXd& y0) = 0;
  /// Advances y from t to t + h in place. The step size must stay the same
  /// between reset() calls for multistep methods. @throws std::runtime_error
  /// from the system (singular matrix, ...).
  virtual void step(double t, double h, Eigen::VectorXd& y) = 0;
};

/// Binds `spec` to `system` (which must outlive the stepper).
/// @throws std::invalid_argument if generalized_alpha is asked of a system that
/// is not a LinearSecondOrderSystem, or the lmm coefficients are malformed.
std::unique_ptr<Stepper> make_stepper(const IntegratorSpec& spec, OdeSystem& system);

}  // namespace mbfe::runtime
