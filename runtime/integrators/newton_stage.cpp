#include "runtime/integrators/newton_stage.h"

#include <sstream>
#include <stdexcept>

#include "runtime/integrators/linear_second_order_system.h"

namespace mbfe::runtime {

namespace {

// Newton on the implicit stage equation g(y) = y - c f(t, y) - r = 0.
// Converged when the correction is below this fraction of |y| (+ the same
// absolute amount): far below any integrator's truncation error.
constexpr double kNewtonTol = 1e-12;
constexpr int kNewtonMaxIterations = 25;

}  // namespace

void newton_solve(OdeSystem& sys, bool linear, double t, double c, const Eigen::VectorXd& r,
                  Eigen::VectorXd& y, NewtonWork& w) {
  for (int it = 0; it < kNewtonMaxIterations; ++it) {
    sys.rhs(t, y, w.f);
    w.g = y - c * w.f - r;
    sys.solve_shifted(t, y, c, w.g, w.delta);
    y -= w.delta;
    if (linear) return;  // exact for a linear f: (I - c J) is the whole Jacobian of g
    if (!(w.delta.norm() <= kNewtonTol * (1.0 + y.norm()))) continue;
    return;
  }
  std::ostringstream msg;
  msg << "implicit step at t = " << t << " s: Newton did not converge in " << kNewtonMaxIterations
      << " iterations";
  throw std::runtime_error(msg.str());
}

bool is_linear(OdeSystem& sys) { return dynamic_cast<LinearSecondOrderSystem*>(&sys) != nullptr; }

}  // namespace mbfe::runtime
