// Joined structures: beams joined by links (a catenary's wires and droppers)
// whose adjustment blocks have scope 'joined' are analysed and adjusted as one
// structure, the links' springs taut (docs/catenary.md, "The joined
// structure"). The adjusted structure is the low-rank form of
// docs/damping-adjustment.md over the stacked coordinates of its beams; a
// slack link is a force correction, a link's damper a force (beam_links.h).
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "ir/model.h"
#include "runtime/damping/beam_model.h"
#include "runtime/damping/modal_adjustment.h"
#include "runtime/structure/low_rank_structure.h"

namespace mbfe::runtime {

struct JoinedStructure {
  std::vector<int> beams;  // model order; the stacked coordinates follow it
  std::vector<int> links;  // the links between them, model order
  int dof = 0;
  /// Modes of K_s Phi = M_s Phi Omega^2: every one (dense, up to the dense
  /// limit) or, beyond it, every one the cap keeps and the first it changes
  /// (spectrum slicing; basis.complete is false).
  ModalBasis basis;
  std::vector<ModalDynamics> original;  // one per basis mode: k_j = omega_j^2, c_j = phi_j^T C_s phi_j
  AdjustedModes adjusted;               // by the beams' (shared) adjustment block
  double k_star = 0.0, c_star = 0.0;    // the cap: k* M, c* M on every mode left out
  /// The largest eigenvalue of [sqrt(k_a k_b) g_a^T K_adj^-1 g_b] over the
  /// slack links inside (0 without any): below 1, the adjusted structure stays
  /// positive definite whichever of them go slack.
  double slack_stiffness_ratio = 0.0;
  /// The adjusted operators over the members' coordinates in q_c (their
  /// ranges follow `beams`).
  std::shared_ptr<const LowRankStructure> structure;
};

/// Why a joined structure cannot be adjusted; `beam` is its first beam (model order).
class JoinedStructureError : public std::invalid_argument {
 public:
  JoinedStructureError(int beam, const std::string& what) : std::invalid_argument(what), beam(beam) {}
  int beam;
};

/// The joined structures of `model`: the beams whose active adjustment has
/// scope 'joined', grouped by the links between them (the parser has checked
/// that each has a link and that linked beams share the block).
/// Structures above `dense_limit` DOFs are analysed by spectrum slicing.
/// @throws JoinedStructureError if a structure's cap lies above nearly all its
///         modes while it is beyond `dense_limit`, its adjusted modes are not
///         a tail of its spectrum, or its slack links could leave it without
///         stiffness (slack_stiffness_ratio >= 1); the message names the beams.
std::vector<JoinedStructure> joined_structures(const ir::Model& model, const BeamModel& beams, int dense_limit);

/// 'contact_wire+messenger' (with the quotes): the names of `beams`.
std::string joined_name(const ir::Model& model, const std::vector<int>& beams);

}  // namespace mbfe::runtime
