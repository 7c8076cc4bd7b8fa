// The accuracy estimate of an adjusted run, made before its first step
// (docs/damping-adjustment.md, "The accuracy estimate", derives both figures
// and holds them against measured errors):
//  - where it applies, the linearised run of both models
//    (linearised_estimate.h): the largest change the adjustment makes in a
//    slider_spring contact's force over the run, relative to its peak;
//  - beside it, and in its place where it does not apply, the point figures:
//    at every place of an adjusted beam where a force acts (contacts, links,
//    point and moving loads) or a displacement is read (probes), the relative
//    change the adjustment makes in the compliance there
//    (runtime/damping/compliance_change.h).
#pragma once

#include <string>
#include <vector>

#include "runtime/simulation/assembled_model.h"
#include "runtime/simulation/linearised_model.h"
#include "runtime/simulation/simulation_types.h"

namespace mbfe::runtime {

/// Above this estimate (1 %) a run tells the user (adjustment_notice).
constexpr double kAdjustmentNoticeThreshold = 0.01;

/// The estimate for the adjusted beams of `model` with these probes, for a
/// run from `start` (null: model_start(model), the start the model file
/// asks for). The point figures: moving points (slider contacts, moving
/// loads) are evaluated at up to 33 nodes spread along their beam and report
/// the largest; beams adjusted with scope joined, or whose partial basis does
/// not end in a changed mode, are listed in not_estimated. The linearised
/// run's figures where it applies (max and where are then its), else
/// linearised_unavailable says why. @throws InvalidInput for a probe on no beam.
AdjustmentEstimate estimate_adjustment(const AssembledModel& model, const std::vector<ProbeSpec>& probes,
                                       const LinearisationPoint* start = nullptr);

/// The lowest omega_limit (rad/s) of beam `beam` (an adjustment block with
/// omega_limit: auto) whose estimate, the largest over the places on that
/// beam where contacts, links and loads act, stays at or below the block's
/// tolerance: a log grid (40 points a decade from 1.01 times the fastest root
/// down to the limit whose capped root is the fastest bounce of a body on a
/// contact spring, or to half the lowest mode without one), the lowest point
/// from which every higher one meets it, refined by bisection. The beam's
/// every mode is needed.
/// @throws InvalidInput (file:line:col at omega_limit) for scope joined, a
///         beam beyond the dense modal analysis, or a damping floor that alone
///         exceeds the tolerance.
double choose_omega_limit(const ir::Model& model, std::size_t beam, const BeamAnalysisOptions& options);

/// One line for the user when estimate.max exceeds kAdjustmentNoticeThreshold
/// (what, where, how much, by which figure, what to do); empty otherwise.
std::string adjustment_notice(const AdjustmentEstimate& estimate, const ir::Model& model);

}  // namespace mbfe::runtime
