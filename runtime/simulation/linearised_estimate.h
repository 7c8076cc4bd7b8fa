// The accuracy estimate of an adjusted run by the linearised moving-contact
// run (linearised_model.h, linearised_run.h): the model linearised once,
// run with the original modes and with the adjusted ones, and each
// slider_spring contact's force compared over the whole run
// (docs/damping-adjustment.md, "The accuracy estimate"). And omega_limit:
// auto chosen by it.
#pragma once

#include <string>
#include <vector>

#include "runtime/simulation/assembled_model.h"
#include "runtime/simulation/linearised_model.h"
#include "runtime/simulation/simulation_types.h"

namespace mbfe::runtime {

/// The point a run of the model as its file says would start from: its
/// `initial:` coordinates with the driven ones at their motion, at the
/// original model's static equilibrium when the file asks for a static start,
/// over the file's t_end. @throws what the static start throws.
LinearisationPoint model_start(const AssembledModel& model);

/// Each contact's change from `original` to `adjusted` (run_linearised of
/// the same structure and excitation), the worst one marked; a contact that
/// never presses in the original run is compared with the adjusted run's peak.
LinearisedEstimate compare_contact_forces(const std::vector<std::string>& contacts, const LinearisedHistory& original,
                                          const LinearisedHistory& adjusted);

/// The linearised estimate of the adjusted run of `model` (each beam under its
/// own adjustment) from `point`; the two runs go on two threads when the run
/// may use two (the same bits either way). @throws InvalidInput where the
/// linearised run does not apply (linearised_run_unavailable says why);
/// std::runtime_error when its static equilibrium or a step is singular, or
/// when it would take more than point.step_budget steps.
LinearisedEstimate linearised_estimate(const AssembledModel& model, const LinearisationPoint& point);

/// omega_limit: auto by the linearised run. The beams `auto_beams` (their
/// adjustment blocks as the model file gives them; each must be analysed
/// with every mode, in `model` under any limit) take one common limit, the
/// lowest on a log grid (10 points a decade from 1.01 times their fastest
/// root down to half their lowest mode) from which every higher grid point
/// keeps the worst contact's change within the smallest of their
/// tolerances, refined by bisection and rounded up to four digits as
/// printed: the stable step of an explicit integrator is set by the
/// largest limit of the model, so a common limit is the one that allows
/// the longest step for the tolerance. The original run is made once.
/// @throws InvalidInput (file:line:col at the first beam's omega_limit) when
///         even the top of the grid does not meet the tolerance (a damping
///         floor alone exceeds it); what linearised_estimate throws.
double choose_common_omega_limit(const AssembledModel& model, const std::vector<std::size_t>& auto_beams,
                                 const LinearisationPoint& point);

}  // namespace mbfe::runtime
