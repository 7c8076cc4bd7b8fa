// The check that a state handed to the kernels at one instant (`mbfe eval`,
// Model::evaluate) holds unit quaternions: the kernels read a quaternion as a
// rotation, which it is only when unit (docs/model-format.md, "Quaternions").
#pragma once

#include <string>

#include "ir/model.h"

namespace mbfe::runtime {

/// The most such a quaternion may be off unit length: M, F and Q are then
/// off by about this much relative. A quaternion written with 7 significant
/// digits passes.
constexpr double kUnitQuaternionTol = 1e-6;

/// Empty when every quaternion of q (nq entries, model order) has
/// | |quat| - 1 | <= kUnitQuaternionTol; else what is wrong with the first
/// that does not (a NaN one too): its body, its coordinates, its norm and
/// what to do.
std::string non_unit_quaternion(const ir::Model& model, const double* q);

}  // namespace mbfe::runtime
