// The adjusted operators of a beam or a joined structure as the parts of a
// LowRankStructure (low_rank_structure.h), from its modes and their adjusted
// modal dynamics (runtime/damping/modal_adjustment.h).
#pragma once

#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "runtime/damping/modal_adjustment.h"
#include "runtime/modal/modal_basis.h"
#include "runtime/structure/low_rank_structure.h"

namespace mbfe::runtime {

/// The adjusted operators over modes `basis` of (M, K) with their adjusted
/// dynamics `adjusted` and the constant load P, over the coordinates `ranges`:
///  - a uniform adjustment (policy cap): the low-rank form over the kept
///    modes, the leading ones that are not kAdjusted, on B = M; a partial
///    basis must end with an adjusted mode (the tail beyond it is all adjusted);
///  - the policy mass: the same kept modes, on B = K (the capped modes'
///    modal mass raised, their stiffness kept);
///  - otherwise eq (27) over every mode (a complete basis).
/// @throws std::invalid_argument naming `name` when the basis does not allow it.
LowRankStructure::Parts adjusted_parts(const std::string& name, std::vector<LowRankStructure::Range> ranges,
                                       const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K,
                                       const Eigen::VectorXd& P, const ModalBasis& basis,
                                       const AdjustedModes& adjusted);

}  // namespace mbfe::runtime
