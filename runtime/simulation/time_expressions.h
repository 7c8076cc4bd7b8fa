// The expressions in t of a model (the values of loads, the motions of driven
// joints) checked where a run first evaluates them, and named when one breaks
// a run later.
//
// A value that is not finite where it is first used is a fault of the model
// file: check_time_expressions() refuses it before the run starts, at the
// operation that gives the inf or NaN (exit status 2, nothing written). One
// that becomes non-finite later (1/(t - 0.5) at t = 0.5) is a numerical fault
// of the run, which ends with the rows so far (exit status 3): beam loads
// report it as they are evaluated (LoadValueError, runtime/fem/beam_loads.h);
// the loads and motions of bodies are evaluated by the generated solver,
// whose NaN ends the run, and non_finite_expression() names the one behind it.
#pragma once

#include <string>

#include "ir/model.h"
#include "runtime/abi/mbfe_model_abi.h"

namespace mbfe::runtime {

/// Evaluates every expression in t where a run from t0 to t_end first uses it:
///  - loads on bodies and motions: at t0 (the generated solver computes a
///    body's load at every t and multiplies it by 0 or 1 for its window, so an
///    inf outside the window spoils the sum all the same);
///  - beam point loads: at the later of t0 and the start of their window;
///  - moving loads: where they enter the beam (at t0 if they are on it).
/// A load first used after t_end is not checked. With `kernels` (a model with
/// bodies), the generated q'(t0) and q''(t0) of every driven joint are checked too.
/// @throws ir::ModelError at the node where the value stops being finite.
void check_time_expressions(const ir::Model& model, const mbfe_model_v1* kernels, double t0, double t_end);

/// The first load or motion of the rigid part whose value is not finite at
/// t, t + h/2 or t + h (the times a step from t evaluates), in words with its
/// position: `load #1: value "1/(t-0.5)" is inf at t = 0.5 s: division by zero (m.yaml:9:37)`;
/// empty when there is none.
std::string non_finite_expression(const ir::Model& model, double t, double h);

}  // namespace mbfe::runtime
