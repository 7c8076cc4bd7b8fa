// Before the static start's Newton: a compression-only contact that touches
// its beam's smooth line but not its running surface (a wheel at height 0
// over a rail below the axis) has no stiffness there, and Newton would call
// the start a mechanism. Such contacts are seated on their surfaces first.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "ir/model.h"
#include "runtime/coupled/coupled_dynamics.h"

namespace mbfe::runtime {

/// Seats on its running surface every compression-only slider_spring
/// (unilateral, or Hertz's law) that at q touches or presses its beam's
/// smooth line (delta without the profile and camber >= 0) but is apart from
/// the running surface (delta < 0): a wheel at height 0 where the rail lies
/// below the axis. Apart, such a contact has no stiffness and Newton would
/// call the start a mechanism. The rigid unknowns move by the least change
/// that presses each of them 1e-5 m into its surface and keeps the
/// penetration of the other compression-only contacts on their beams (a
/// minimum-norm least-squares step, penetrations by central differences).
/// Leaves q alone when no contact needs it, and when the seating fails (Newton
/// from q as given then says why). docs/profiles.md, "Static start on a rough
/// rail".
/// @param unknown the coordinates the static start solves for (the rigid ones
///        among them are moved); @param relative_step the central-difference
///        step relative to a coordinate's size.
void seat_on_running_surfaces(const ir::Model& model, CoupledDynamics& dyn, const std::vector<int>& unknown,
                              double relative_step, Eigen::VectorXd& q, const Eigen::VectorXd& qd);

}  // namespace mbfe::runtime
