#include "runtime/simulation/settled_state.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include "ir/model_error.h"
#include "runtime/simulation/static_start.h"

namespace mbfe::runtime {

namespace {

// Settled once the rates are this small against the motion's scale (as
// rigid_settled_state).
constexpr double kSettledRate = 1e-6;
// At most this many periods of the slowest mode: a damped mode settles in a few.
constexpr double kMaxPeriods = 200.0;
// And at most this many steps (two evaluations each): a model whose modes
// span many decades is linearised where it starts rather than relaxed for
// minutes.
constexpr double kMaxSteps = 5e4;

// Semi-implicit Euler on y = [q; w] (w the nw velocities the system
// integrates) with the damping -c w taken implicitly: w first, then q moved
// by the new rates. `system.after_step` closes the loops or renormalises.
bool relax(OdeSystem& system, int nq, double omega_min, double omega_max, Eigen::VectorXd& y) {
  if (!(omega_min > 0.0) || !(omega_max >= omega_min) || !std::isfinite(omega_max)) return false;
  const Eigen::Index nw = y.size() - nq;
  const double h = 0.5 / omega_max;
  const double c = 2.0 * omega_min;
  const long max_steps = static_cast<long>(std::min(kMaxSteps, kMaxPeriods * 2.0 * M_PI / omega_min / h));
  Eigen::VectorXd ydot;
  y.tail(nw).setZero();
  for (long k = 0; k < max_steps; ++k) {
    system.rhs(0.0, y, ydot);
    y.tail(nw) = (y.tail(nw) + h * ydot.tail(nw)) / (1.0 + h * c);
    system.rhs(0.0, y, ydot);  // the positions' rates at the new velocities
    y.head(nq) += h * ydot.head(nq);
    system.after_step(0.0, y);
    if (!y.allFinite()) return false;
    if (nw == 0 || y.tail(nw).cwiseAbs().maxCoeff() <= kSettledRate * omega_min * (1.0 + y.head(nq).norm()))
      return true;
  }
  return false;
}

// Newton from the relaxed state makes the rest exact where the equilibrium
// is isolated. Where it is not (a body free to roll or yaw on its
// suspension: the static stiffness is singular, and Newton says "nothing
// holds" it) the relaxed state, at rest to kSettledRate, is kept.
template <typename Newton>
void polish(const Newton& newton) {
  try {
    newton();
  } catch (const ir::ModelError&) {
  }
}

}  // namespace

bool loop_settled_state(const ir::Model& model, LoopPartitionedSystem& system, double omega_min, double omega_max,
                        Eigen::VectorXd& q, Eigen::VectorXd& v) {
  try {
    Eigen::VectorXd qs = q, vs = Eigen::VectorXd::Zero(v.size());
    Eigen::VectorXd y = system.state_of(0.0, qs, vs);
    if (!relax(system, static_cast<int>(qs.size()), omega_min, omega_max, y)) return false;
    system.full_state(0.0, y, qs, vs);
    polish([&] { loop_static_state(model, system, qs, vs); });
    q = qs;
    v = vs;
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

bool quaternion_settled_state(const ir::Model& model, RigidSystem& system, double omega_min, double omega_max,
                              Eigen::VectorXd& y) {
  try {
    Eigen::VectorXd state = y;
    system.impose_motion(0.0, state);
    if (!relax(system, system.num_coordinates(), omega_min, omega_max, state)) return false;
    Eigen::VectorXd polished = state;
    polish([&] { quaternion_static_state(model, system, polished); });
    y = polished;
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace mbfe::runtime
