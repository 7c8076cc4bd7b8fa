// The step-by-step integrators of Section 5 of the paper (eqs (18)-(19)), plus
// RK4 and generalized-alpha, over an OdeSystem y' = f(t, y).
//
// The methods and their names: integrator_spec.h. Steppers: one_step_methods.cpp,
// linear_multistep.cpp, generalized_alpha.cpp.
//
// Implicit methods solve their stage equation with Newton on
// g(y) = y - c f(t, y) - r through OdeSystem::solve_shifted; a LinearSecondOrderSystem
// is known to be linear, so one Newton iteration is exact and only one is taken.
// Linear systems factorise once per (step size, method) and reuse the factor.
#pragma once

#include <Eigen/Core>
#include <memory>

#include "runtime/integrators/integrator_spec.h"
#include "runtime/integrators/linear_second_order_system.h"
#include "runtime/integrators/ode_system.h"
#include "runtime/integrators/second_order_system.h"

namespace mbfe::runtime {

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
  /// Newton iterations and factorisations so far (zero for explicit methods
  /// and for the first-order implicit ones).
  virtual NewtonStatistics newton_statistics() const { return {}; }
};

/// Binds `spec` to `system` (which must outlive the stepper). A system that is
/// also a SecondOrderSystem gets the second-order form of backward_euler,
/// trapezoid, bdf2 and generalized_alpha (second_order_steppers.h).
/// @throws std::invalid_argument if generalized_alpha is asked of a system that
/// is not a LinearSecondOrderSystem, or the lmm coefficients are malformed.
std::unique_ptr<Stepper> make_stepper(const IntegratorSpec& spec, OdeSystem& system);

}  // namespace mbfe::runtime
