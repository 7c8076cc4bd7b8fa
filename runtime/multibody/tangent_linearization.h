// The Jacobian of a multibody ODE y' = f(t, y), y = [q; w], in minimal
// tangent coordinates (docs/partitioning.md, "Linearisation on the
// constraint manifold"): what `mbfe stability` analyses when q is not a
// vector space of its own, because it holds unit quaternions (4 numbers, 3
// degrees of freedom) or because closed loops tie the coordinates together.
//
// The positions are parametrised by increments dx along chosen velocity
// directions `moved` (indices into v, one per entry of w): q(dx) = q0 (+) dx,
// a quaternion turned by the rotation vector of its angular-velocity entries
// (rigid_coordinates.h, `displace`). A loop system closes q(dx) along its
// dependent directions inside its rhs, so with `moved` its independent
// coordinates the chart is the constraint manifold itself. The tangent state
// is z = [dx; w] (2 n entries, n = moved.size()), and
//
//   A = dz'/dz = [[P dq'/dx, P dq'/dw], [dw'/dx, dw'/dw]]
//
// by central differences along the chart, with P the left inverse of the
// chart's tangent: dq -> the entries `moved` of the velocity increment dv
// with dq = G(q0) dv (plain coordinates: dv = dq; a quaternion: the body-frame
// rotation 2 vec(conj(q0) dq)). At an equilibrium (v = 0) P dq'/dx vanishes
// and P dq'/dw is the identity, as for y = [q; q'].
#pragma once

#include <Eigen/Core>
#include <vector>

#include "runtime/integrators/ode_system.h"
#include "runtime/multibody/rigid_coordinates.h"

namespace mbfe::runtime {

/// A (2 n x 2 n, n = moved.size()) of `system` at (t, y), y = [q; w] with q
/// nq entries (c.nq) and w n entries (the velocities of the directions
/// `moved`, in that order). Column j perturbs dx_j (or w_j) by
/// +-rel_step * max(1, |.|) (a rotation by that many rad). The system is
/// evaluated at y last, so a system with state between calls (a Newton start)
/// is left where y puts it.
/// @throws std::invalid_argument when y has not nq + n entries or
///         system.size() differs; what system.rhs throws.
Eigen::MatrixXd tangent_jacobian(OdeSystem& system, const RigidCoordinates& c, const std::vector<int>& moved,
                                 double t, const Eigen::VectorXd& y, double rel_step = 1e-6);

/// dv (nv) with q0 (+) dv = q0 + dq to first order: P without the selection
/// of `moved`. q0's quaternions must be unit; dq has nq entries.
Eigen::VectorXd velocity_increment(const RigidCoordinates& c, const double* q0, const Eigen::VectorXd& dq);

}  // namespace mbfe::runtime
