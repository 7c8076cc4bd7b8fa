// The implicit steppers of a SecondOrderSystem (second_order_system.h), made
// by make_stepper() (integrator.h) when the system is one.
#pragma once

#include <memory>

#include "runtime/integrators/integrator.h"
#include "runtime/integrators/second_order_system.h"

namespace mbfe::runtime {

enum class SecondOrderMethod { kBackwardEuler, kTrapezoid, kBdf2, kGeneralizedAlpha };

/// `ode` is the same object as `system` seen as an OdeSystem (y = [q; q']).
/// @param rho_inf generalized-alpha only, in [0, 1].
std::unique_ptr<Stepper> make_second_order_stepper(OdeSystem& ode, SecondOrderSystem& system,
                                                   SecondOrderMethod method, double rho_inf);

}  // namespace mbfe::runtime
