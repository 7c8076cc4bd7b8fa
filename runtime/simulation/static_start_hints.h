// What holds nothing at a coupled model's static start, found before Newton
// from the model and the state at t = 0: the words a failed start gives in
// place of "Newton lost hold ... check the units" when the cause is plain.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "ir/model.h"
#include "runtime/coupled/coupled_dynamics.h"

namespace mbfe::runtime {

/// Whether a beam's own supports hold it against rigid motion (its stiffness
/// K, supports included, positive definite): a clamp, or supports that fix w
/// at two places (pinned or spring). Tension does not: its geometric
/// stiffness has the rigid motions in its null space.
bool held_against_rigid_motion(const ir::Beam& beam);

/// "no support", "1 support at s = 0 m", "2 supports at s = 0, 20 m".
std::string supports_in_words(const ir::Beam& beam);

/// One clause per cause, in model order:
///  - a body whose every compression-only slider_spring (unilateral, or
///    Hertz's law) has its point outside its beam's [0, L] at t = 0: "body
///    'rear_wheel' is over no beam at t = 0: its contacts 'rear_approach' (s =
///    -1 m; beam 'approach' spans 0 to 10 m), ... hold nothing up";
///  - a beam its supports do not hold against rigid motion and that no link,
///    pin or slider_pin joins to anything: "beam 'bridge' has 1 support at s
///    = 0 m, which leaves it free to turn or move as a rigid body; only the
///    contacts on it hold it (...)".
/// Evaluates `dyn` at (q, qd), t = 0. Empty when there is none.
std::vector<std::string> static_start_hints(const ir::Model& model, CoupledDynamics& dyn, const Eigen::VectorXd& q,
                                            const Eigen::VectorXd& qd);

}  // namespace mbfe::runtime
