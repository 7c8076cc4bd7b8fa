// Which node of a beam's uniform mesh a position along it falls on: one rule
// for the front end (supports and point loads must be at nodes) and the
// runtime (assembly of a beam built in memory).
#pragma once

#include <cmath>

namespace mbfe::ir {

/// A position counts as "at a node" within this fraction of the beam's length
/// of it: far above the rounding of a decimal position (1e-16), far below any
/// element length a model could use.
constexpr double kNodeTolerance = 1e-9;

struct NodeOnBeam {
  long nearest = 0;      // index of the nearest node (0 .. elements)
  double spacing = 0.0;  // m, element length
  bool on_node = false;  // s is within kNodeTolerance * length of `nearest`
};

/// @param length m (> 0) @param elements (> 0) @param s m along the beam.
inline NodeOnBeam node_on_beam(double length, int elements, double s) {
  NodeOnBeam out;
  out.spacing = length / elements;
  out.nearest = std::lround(s / out.spacing);
  if (out.nearest < 0) out.nearest = 0;
  if (out.nearest > elements) out.nearest = elements;
  out.on_node = std::fabs(s - out.nearest * out.spacing) <= kNodeTolerance * length;
  return out;
}

}  // namespace mbfe::ir
