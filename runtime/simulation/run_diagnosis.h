// The sentence that explains a run that did not complete, written once for
// every kind of model: an integrator beyond its stable limit, a model with no
// stable step for it, a numerical fault of the model, an interruption.
#pragma once

#include <complex>
#include <optional>
#include <string>

#include "runtime/integrators/simulation_driver.h"
#include "runtime/stability/step_limits.h"

namespace mbfe::runtime {

/// "-1.3702e5", or "-3.6817e0 + 7.3542e1i" (5 significant digits, no '+' or
/// leading zeros in the exponent).
std::string eigenvalue_text(std::complex<double> lambda);

/// Why `result` did not complete (empty for a completed run).
/// @param limit the integrator's stable limit for the model as simulated (the
///        linearisation at the initial state, or the beams' spectrum), absent
///        when unknown.
/// @param row_fault a fault met while writing an output row (the coupled
///        model's contact report), empty if none.
/// A fault at a step beyond a finite stable limit is blamed on the step (the
/// growing state broke the model); at a stable step, or with no stable step
/// at all, it is the model's own.
std::string diagnose_run(const SimulationResult& result, const std::optional<StepLimit>& limit,
                         const std::string& row_fault = "");

}  // namespace mbfe::runtime
