// Which of the three kinds of model a model file describes: what decides
// how it is assembled and simulated.
#pragma once

#include "ir/model.h"

namespace mbfe::runtime {

/// kRigid: bodies only; kBeams: beams only; kCoupled: bodies and beams
/// (contacts optional).
enum class ModelKind { kRigid, kBeams, kCoupled };

/// @throws InvalidInput for a model with neither bodies nor beams.
ModelKind model_kind(const ir::Model& model);

}  // namespace mbfe::runtime
