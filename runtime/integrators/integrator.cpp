#include "runtime/integrators/integrator.h"

#include <stdexcept>

#include "runtime/integrators/second_order_steppers.h"
#include "runtime/integrators/steppers.h"

namespace mbfe::runtime {

namespace {

bool is_bdf2(const IntegratorSpec& spec) {
  return spec.kind == IntegratorKind::kLinearMultistep && spec.lmm.alpha == std::vector<double>{0.5, -2.0, 1.5} &&
         spec.lmm.beta == std::vector<double>{0.0, 0.0, 1.0};
}

void check_rho_inf(const IntegratorSpec& spec) {
  if (!(spec.rho_inf >= 0.0 && spec.rho_inf <= 1.0))
    throw std::invalid_argument("generalized_alpha: rho_inf must be in [0, 1]");
}

}  // namespace

std::unique_ptr<Stepper> make_stepper(const IntegratorSpec& spec, OdeSystem& system) {
  if (auto* second = dynamic_cast<SecondOrderSystem*>(&system)) {
    switch (spec.kind) {
      case IntegratorKind::kBackwardEuler:
        return make_second_order_stepper(system, *second, SecondOrderMethod::kBackwardEuler, 0.0);
      case IntegratorKind::kTrapezoid:
        return make_second_order_stepper(system, *second, SecondOrderMethod::kTrapezoid, 0.0);
      case IntegratorKind::kGeneralizedAlpha:
        check_rho_inf(spec);
        return make_second_order_stepper(system, *second, SecondOrderMethod::kGeneralizedAlpha, spec.rho_inf);
      default:
        if (is_bdf2(spec)) return make_second_order_stepper(system, *second, SecondOrderMethod::kBdf2, 0.0);
        break;
    }
  }
  switch (spec.kind) {
    case IntegratorKind::kForwardEuler:
      return make_forward_euler(system);
    case IntegratorKind::kBackwardEuler:
      return make_backward_euler(system);
    case IntegratorKind::kExplicitMidpoint:
      return make_explicit_midpoint(system);
    case IntegratorKind::kTrapezoid:
      return make_trapezoid(system);
    case IntegratorKind::kRk4:
      return make_rk4(system);
    case IntegratorKind::kLinearMultistep:
      validate_lmm(spec.lmm);
      return make_linear_multistep(system, spec.lmm);
    case IntegratorKind::kGeneralizedAlpha: {
      auto* second = dynamic_cast<LinearSecondOrderSystem*>(&system);
      if (!second)
        throw std::invalid_argument(
            "integrator generalized_alpha needs a linear second-order system (M q'' + C q' + K q = P); "
            "this model is not one");
      check_rho_inf(spec);
      return make_generalized_alpha(*second, spec.rho_inf);
    }
  }
  throw std::invalid_argument("unknown integrator kind");
}


}  // namespace mbfe::runtime
