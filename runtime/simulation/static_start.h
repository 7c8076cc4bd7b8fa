// The static start: the equilibrium at t = 0 of everything not driven, under
// gravity and the loads at t = 0, by Newton on the full nonlinear system
// (docs/model-format.md, `initial: {static: true}`).
//
// Unknowns x: the coordinates that are not driven. Residual: their
// accelerations at rest (driven joints move with their motion's q and q' at
// t = 0, every other velocity 0) and, for constraint contacts, Phi; x is an
// equilibrium when both vanish. Gauss-Newton with a central-difference
// Jacobian (central, so that a unilateral contact just touching counts with
// half its stiffness instead of none): the systems here are small (the
// rigid coordinates and the beams' DOFs, a few hundred), and every column
// costs one evaluation of the sparse model.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

namespace mbfe::runtime {

/// residual(x, r): r = [accelerations of the unknowns; Phi] at x.
using StaticResidualFn = std::function<void(const Eigen::VectorXd& x, Eigen::VectorXd& r)>;

struct StaticSolution {
  Eigen::VectorXd x;
  int iterations = 0;
  double residual = 0.0;  // max |r| at x
};

/// Newton from x0. `names` name the unknowns for messages.
/// @throws std::runtime_error "the structure is a mechanism: '<name>' ..."
///         when the Jacobian is singular (naming the unknown that carries the
///         null direction), or "... did not converge ..." after 50 iterations.
StaticSolution solve_static(const StaticResidualFn& residual, const Eigen::VectorXd& x0,
                            const std::vector<std::string>& names);

}  // namespace mbfe::runtime
