// Form finding for links with `hold` (docs/catenary.md): the rest offset of
// each such link that puts its point a at the given deflection in the static
// equilibrium of the beams (their constant loads, own weight included) and
// all their links taut. The equations are linear in the offsets:
//
//   A u = P + sum_l k_l rest_l g_l,    A = K + sum_l k_l g_l g_l^T
//   N_a,h . u = hold_h  for every link h with `hold`
//
// so one sparse factorisation of A and one solve per held link give them.
#pragma once

#include <vector>

#include "ir/model.h"
#include "runtime/damping/beam_model.h"

namespace mbfe::runtime {

struct LinkFormFinding {
  std::vector<double> rest;     // per link, model order: the offset to use (m)
  std::vector<double> tension;  // per link: its tension in that equilibrium (N)
  Eigen::VectorXd deflection;   // the equilibrium, the beams' free DOFs in model order
};

/// @throws InvalidInput if the beams and links have no static equilibrium
///         (a beam held by nothing), or a slack link would have to push to
///         hold its point (negative tension).
LinkFormFinding find_link_rest_offsets(const ir::Model& model, const BeamModel& beams);

}  // namespace mbfe::runtime
