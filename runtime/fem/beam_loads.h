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
#include <stdexcept>
#include <string>
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

/// A load's value is not finite at some time of a run: a numerical fault of
/// the run (it ends with the rows so far), not of the file, which was checked
/// where the run starts (runtime/simulation/time_expressions.h). what() names
/// the load, its text and position, the value and the time.
class LoadValueError : public std::runtime_error {
 public:
  LoadValueError(const std::string& message, double t) : std::runtime_error(message), t_(t) {}
  double t() const { return t_; }

 private:
  double t_;
};

/// Clears `out` and appends the time-dependent loads of `beam` at t (an index
/// may appear more than once: add them up). Nothing is allocated once `out`
/// has grown to its largest size. @throws LoadValueError when a load's value
/// at t is not finite.
void time_dependent_loads(const BeamSystem& beam, double t, std::vector<NodalForce>& out);

/// Position (m) of a moving load at time t.
inline double moving_load_position(const ir::BeamMovingLoad& load, double t) {
  return load.start + load.speed * (t - load.t0);
}

}  // namespace mbfe::runtime
