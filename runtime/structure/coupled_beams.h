// The beams of a coupled model as CoupledDynamics sees them: mass matrix, load
// and internal force C q' + K q, with the original (Rayleigh) or the adjusted
// operators of the modal adjustment of damping (docs/damping-adjustment.md).
#pragma once

#include "runtime/damping/beam_model.h"
#include "runtime/structure/coupled_beam.h"
#include "runtime/structure/joined_structures.h"

namespace mbfe::runtime {

/// The beam's internal force C q' + K q: sparse Rayleigh (original, or a beam
/// without an active adjustment), low rank for a uniform cap (M s + S + U d U^T,
/// docs/damping-adjustment.md "low-rank form"), eq (27) over every mode otherwise.
BeamForceFn beam_force(const BeamPart& beam, bool adjusted);

/// The beam's free acceleration M^-1 (P - C q' - K q) without a solve with M,
/// for the low-rank adjusted beam (M^-1 U = Phi_L: a = M^-1 P - (s_C q' + s_K q)
/// - Phi_L (d_C .* U^T q' + d_K .* U^T q)); empty for the others (CoupledDynamics
/// then solves with M).
BeamForceFn beam_acceleration(const BeamPart& beam, bool adjusted);

/// Every beam of `beams` as a CoupledBeam, original or adjusted. An adjusted
/// member of a joined structure carries its own part only (C = c* M,
/// K = k* M; the structure's low-rank part is CoupledDynamics').
std::vector<CoupledBeam> coupled_beams(const BeamModel& beams, bool adjusted,
                                       const std::vector<JoinedStructure>& joined = {});

}  // namespace mbfe::runtime
