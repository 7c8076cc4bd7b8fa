#include "runtime/simulation/simulate.h"

#include <cmath>

#include "runtime/simulation/invalid_input.h"
#include "runtime/simulation/runs.h"
#include "runtime/simulation/time_expressions.h"

namespace mbfe::runtime {

namespace detail {

SimulationOptions driver_options(const SimulationRequest& request) {
  SimulationOptions options;
  options.step = request.step;
  options.t_end = request.t_end;
  options.every = request.every;
  options.quiet = request.quiet;
  options.handle_sigint = request.handle_sigint;
  return options;
}

const char* coordinate_unit(const ir::Body& body) {
  return body.joint.type == ir::JointType::kRevolute ? "rad" : "m";
}

const char* rate_unit(const ir::Body& body) {
  return body.joint.type == ir::JointType::kRevolute ? "rad/s" : "m/s";
}

}  // namespace detail

SimulationReport simulate(const AssembledModel& model, const SimulationRequest& request,
                          SimulationObserver& observer) {
  if (!(request.step > 0.0) || !std::isfinite(request.step)) throw InvalidInput("--step must be > 0");
  if (!(request.t_end > 0.0) || !std::isfinite(request.t_end)) throw InvalidInput("--t-end must be > 0");
  if (request.every < 0) throw InvalidInput("--every must be a positive integer");
  const std::string& name = model.ir().name;
  // Runs start at t = 0 (driver_options leaves SimulationOptions::t0 alone).
  check_time_expressions(model.ir(), model.kernels(), 0.0, request.t_end);
  switch (model.kind()) {
    case ModelKind::kRigid:
      if (request.integrator.kind == IntegratorKind::kGeneralizedAlpha)
        throw InvalidInput("generalized_alpha needs a linear second-order (beam) model; for rigid models use "
                           "rk4, trapezoid, backward_euler, ...");
      if (request.adjust || !request.probes.empty())
        throw InvalidInput("--adjust and --probe apply to beam models only ('" + name + "' has no beams)");
      return detail::run_rigid(model, request, observer);
    case ModelKind::kBeams:
      return detail::run_beams(model, request, observer);
    case ModelKind::kCoupled:
      return detail::run_coupled(model, request, observer);
  }
  throw InvalidInput("unknown kind of model");
}

}  // namespace mbfe::runtime
