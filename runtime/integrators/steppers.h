// The stepper of each integrator family, made by make_stepper()
// (integrator.h): one-step methods (one_step_methods.cpp), linear multistep
// methods (linear_multistep.cpp) and generalized-alpha (generalized_alpha.cpp).
#pragma once

#include <memory>

#include "runtime/integrators/integrator.h"
#include "runtime/integrators/linear_second_order_system.h"

namespace mbfe::runtime {

std::unique_ptr<Stepper> make_forward_euler(OdeSystem& system);
std::unique_ptr<Stepper> make_rk4(OdeSystem& system);
std::unique_ptr<Stepper> make_backward_euler(OdeSystem& system);
std::unique_ptr<Stepper> make_trapezoid(OdeSystem& system);
std::unique_ptr<Stepper> make_explicit_midpoint(OdeSystem& system);
/// @param c validated coefficients.
std::unique_ptr<Stepper> make_linear_multistep(OdeSystem& system, const LmmCoefficients& c);
/// @param rho_inf spectral radius at infinity, in [0, 1].
std::unique_ptr<Stepper> make_generalized_alpha(LinearSecondOrderSystem& system, double rho_inf);

}  // namespace mbfe::runtime
