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
#include <memory>
#include <functional>
#include <string>
#include <vector>

#include "ir/model.h"
#include "runtime/coupled/coupled_dynamics.h"
#include "runtime/multibody/loop_systems.h"
#include "runtime/multibody/rigid_system.h"

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
///         null direction), "Newton lost hold of '<name>' ..." when the
///         Jacobian turns singular only after the first iteration (a contact
///         the steps carried away: a structure far softer than its loads),
///         or "... did not converge ..." after 50 iterations. A step to
///         where `residual` throws ContactError (loops that cannot close
///         there) is halved until it does not (at most 20 times). Converged when
///         the update is 1e-12 of the coordinates, or stalls below 1e-9 of
///         them (its round-off floor) once the residual has fallen by 1e-5.
StaticSolution solve_static(const StaticResidualFn& residual, const Eigen::VectorXd& x0,
                            const std::vector<std::string>& names);

/// A coupled model's static start: q (n = [q_b; q_c], the starting guess)
/// becomes the equilibrium at t = 0, qd zero but for the driven joints'
/// motion. @throws ir::ModelError at `model.initial.loc` when there is none.
void coupled_static_state(const ir::Model& model, CoupledDynamics& dyn, Eigen::VectorXd& q, Eigen::VectorXd& qd);

/// The same for a large coupled model (thousands of beam DOFs, where the dense
/// difference Jacobian above is out of reach): Newton with the sparse
/// tangent of the implicit integrators (coupled_implicit_system.h), K_t
/// bordered by the contact rows. Needs the beams' sparse C and K (the original
/// model, or a cap adjustment's c* M and k* M with its low-rank part); returns
/// false (q untouched) when they are not there (eq (27) over every mode).
/// @throws ir::ModelError at `model.initial.loc` when Newton does not converge.
bool coupled_static_state_sparse(const ir::Model& model, const std::shared_ptr<CoupledDynamics>& dyn,
                                 Eigen::VectorXd& q, Eigen::VectorXd& qd);

/// Coupled models up to this many coordinates find their static start with
/// the dense difference Jacobian (tested longest); larger ones with the
/// sparse tangent.
inline constexpr int kDenseStaticCoordinates = 600;

/// coupled_static_state for a model of up to kDenseStaticCoordinates
/// coordinates or one without the beams' sparse matrices,
/// coupled_static_state_sparse otherwise: what a run and the advisor use.
void coupled_static_start(const ir::Model& model, const std::shared_ptr<CoupledDynamics>& dyn, Eigen::VectorXd& q,
                          Eigen::VectorXd& qd);

/// A rigid model's static start on y = [q; q'] (q the starting guess).
/// @throws ir::ModelError at `model.initial.loc` when there is none.
void rigid_static_state(const ir::Model& model, RigidSystem& system, Eigen::VectorXd& y);

/// A rigid model's static start when its positions are not a vector space of
/// their own: Newton on the increments along the free velocity directions
/// (q0 (+) dx: three rotation increments per quaternion), the residual their
/// accelerations at rest (driven joints moving as their motion says).
/// y = [q; v] (q the starting guess). @throws ir::ModelError at
/// `model.initial.loc` when there is none.
void quaternion_static_state(const ir::Model& model, RigidSystem& system, Eigen::VectorXd& y);

/// A model with closed loops: the equilibrium on the constraint manifold, by
/// Newton on the increments of the independent coordinates of the partition
/// at q, the loops closed by `system` at every iterate (docs/partitioning.md,
/// "Closed loops"). q must close the loops on entry; it becomes the
/// equilibrium (closed), v zero but for the driven joints' motion (the
/// velocities that motion gives through the loops). @throws ir::ModelError at
/// `model.initial.loc` when there is none.
void loop_static_state(const ir::Model& model, LoopPartitionedSystem& system, Eigen::VectorXd& q, Eigen::VectorXd& v);

/// A stable static equilibrium of a rigid model near y = [q; q'] (the
/// minimum of its potential the motion from y, damped, settles into; a
/// Newton solve alone may land on an unstable one, a pendulum upside down):
/// dynamic relaxation with the damping 2 omega_min and steps 0.5 / omega_max,
/// omega_* the scales of the model's modes, then rigid_static_state from the
/// settled state. Returns false (y unchanged) when it does not settle.
bool rigid_settled_state(const ir::Model& model, RigidSystem& system, double omega_min, double omega_max,
                         Eigen::VectorXd& y);

}  // namespace mbfe::runtime
