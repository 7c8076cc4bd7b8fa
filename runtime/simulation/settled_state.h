// A stable equilibrium near a state of a model whose positions are not a
// vector space of their own (quaternions) or live on closed loops, for the
// stability advisor: where a model released away from equilibrium swings,
// its modes are those of the equilibrium it swings about (the same reason as
// rigid_settled_state in static_start.h, for the cases that one does not
// take). Dynamic relaxation damps the motion until it rests, then the
// model's static start (Newton) makes the rest exact; Newton alone may land
// on an unstable equilibrium (a pendulum upside down).
#pragma once

#include <Eigen/Core>

#include "ir/model.h"
#include "runtime/multibody/loop_systems.h"
#include "runtime/multibody/rigid_system.h"

namespace mbfe::runtime {

/// The equilibrium on the loops that the motion released at rest from q,
/// damped, settles into: q and v are overwritten with it (v zero but for the
/// driven joints). omega_min and omega_max are the scales of the model's
/// modes (the moduli of its linearisation's eigenvalues): the damping is
/// 2 omega_min and the step 0.5 / omega_max. Newton then makes the rest
/// exact; where it does not converge (an equilibrium that is not isolated)
/// the rested state is kept. Returns false (q, v unchanged) when the motion
/// does not come to rest.
bool loop_settled_state(const ir::Model& model, LoopPartitionedSystem& system, double omega_min, double omega_max,
                        Eigen::VectorXd& q, Eigen::VectorXd& v);

/// The same for a tree with quaternions, y = [q; v].
bool quaternion_settled_state(const ir::Model& model, RigidSystem& system, double omega_min, double omega_max,
                              Eigen::VectorXd& y);

}  // namespace mbfe::runtime
