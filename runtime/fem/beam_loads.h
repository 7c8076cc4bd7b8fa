// The loads of a beam that change with time, at one instant, as a sparse
// nodal load vector on the beam's free DOFs:
//  - point loads whose value is an expression in t or that have a time
//    window (start <= t < stop), on their node's w;
//  - moving loads, value(t) at s(t) = start + speed (t - t0) while s is in
//    [0, L]: the consistent nodal loads value * N_a(s) of the element under s
//    (N_a the element's Hermite shape functions; the same loads the virtual
//    work of a point force gives, so w(s) is what the force works on).
// The constant part of the load stays in BeamSystem::P.
#pragma once

#include <functional>
#include <vector>

#include "runtime/fem/beam_system.h"

namespace mbfe::runtime {

/// One entry of a sparse load vector on a beam's free DOFs.
struct NodalForce {
  int index = -1;      // free DOF
  double value = 0.0;  // N or N m
};

/// The time-dependent part of a load at t: clears `out`, appends nodal forces
/// (indices into the system's DOFs).
using TimeLoadFn = std::function<void(double t, std::vector<NodalForce>& out)>;

/// Clears `out` and appends the time-dependent loads of `beam` at t (an index
/// may appear more than once: add them up). Nothing is allocated once `out`
/// has grown to its largest size.
void time_dependent_loads(const BeamSystem& beam, double t, std::vector<NodalForce>& out);

/// Position (m) of a moving load at time t.
inline double moving_load_position(const ir::BeamMovingLoad& load, double t) {
  return load.start + load.speed * (t - load.t0);
}

}  // namespace mbfe::runtime
