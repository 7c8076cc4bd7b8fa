// What a coordinate or an output column measures, and its SI unit: one rule
// for every column, sidecar and message (a beam's slope w' = dw/ds is a
// length over a length, "1", and its rate "1/s"; a quaternion entry is "1").
#pragma once

#include <string>

#include "ir/model.h"

namespace mbfe::ir {

enum class Quantity {
  kTime,    // s
  kLength,  // m
  kAngle,   // rad
  kRatio,   // 1: a slope, a quaternion entry
  kForce,   // N
  kMoment,  // N m
};

/// The SI unit of the `rate`-th time derivative of `quantity` (0, 1 or 2):
/// "m", "m/s", "m/s^2"; "rad", "rad/s", "rad/s^2"; "1", "1/s", "1/s^2";
/// "N"; "N m"; "s".
inline std::string si_unit(Quantity quantity, int rate = 0) {
  const char* base = "";
  switch (quantity) {
    case Quantity::kTime: return "s";
    case Quantity::kForce: return "N";
    case Quantity::kMoment: return "N m";
    case Quantity::kLength: base = "m"; break;
    case Quantity::kAngle: base = "rad"; break;
    case Quantity::kRatio: base = "1"; break;
  }
  const std::string per = rate == 0 ? "" : rate == 1 ? "/s" : "/s^" + std::to_string(rate);
  return base + per;
}

/// What the coordinate of a revolute (an angle) or prismatic joint (a length)
/// measures; its rate is the same quantity's first derivative.
inline Quantity joint_coordinate(JointType type) {
  return type == JointType::kRevolute ? Quantity::kAngle : Quantity::kLength;
}

/// What the reaction that drives a revolute (a moment) or prismatic joint (a
/// force) is.
inline Quantity joint_reaction(JointType type) {
  return type == JointType::kRevolute ? Quantity::kMoment : Quantity::kForce;
}

/// A beam DOF: a deflection (a length) or a slope (a ratio).
inline Quantity beam_dof(bool slope) { return slope ? Quantity::kRatio : Quantity::kLength; }

}  // namespace mbfe::ir
