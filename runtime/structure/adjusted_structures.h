// The beams of a model as a coupled model sees them (coupled_beam.h): the
// original beams with their Rayleigh C and K, or the adjusted operators of the
// modal adjustment of damping (docs/damping-adjustment.md) as low-rank
// structures (low_rank_structure.h), one per adjusted beam or per joined
// structure.
#pragma once

#include <vector>

#include "runtime/damping/beam_model.h"
#include "runtime/structure/coupled_beam.h"
#include "runtime/structure/joined_structures.h"

namespace mbfe::runtime {

/// Every beam of `beams`, original or adjusted (an adjusted beam of scope
/// 'joined' by the structure of `joined` that holds it).
/// @throws what adjusted_parts and LowRankStructure throw.
CoupledBeams coupled_beams(const BeamModel& beams, bool adjusted, const std::vector<JoinedStructure>& joined = {});

}  // namespace mbfe::runtime
