// The stage equation of the implicit one-step and multistep methods,
// y - c f(t, y) = r, solved by Newton through OdeSystem::solve_shifted.
#pragma once

#include <Eigen/Core>

#include "runtime/integrators/ode_system.h"

namespace mbfe::runtime {

/// Scratch vectors of newton_solve, sized once.
struct NewtonWork {
  Eigen::VectorXd f, g, delta;
  void resize(int n) {
    f.resize(n);
    g.resize(n);
    delta.resize(n);
  }
};

/// Solves y - c f(t, y) = r for y, starting from the y given. For a linear f
/// (`linear`) one iteration is exact and only one is taken. Converged when the
/// correction is below 1e-12 (1 + |y|). @throws std::runtime_error when 25
/// iterations do not converge, or what the system throws.
void newton_solve(OdeSystem& sys, bool linear, double t, double c, const Eigen::VectorXd& r, Eigen::VectorXd& y,
                  NewtonWork& w);

/// True for a LinearSecondOrderSystem.
bool is_linear(OdeSystem& sys);

}  // namespace mbfe::runtime
