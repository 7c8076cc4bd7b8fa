// The tangent of the rigid equations of motion for implicit integrators: with
// the inverse dynamics tau(q, q', a) = M(q) a + F(q, q') - Q(q, q', t),
//
//   K = d tau / dq   = d(M a)/dq - d(Q - F)/dq     (a given: the iterate's)
//   C = d tau / dq'  = -d(Q - F)/dq'
//
// derived in closed form by forward differentiation of the kernels' own
// straight-line code (forward_derivatives.h); M a is formed from the
// composite-rigid-body outputs S_j . U_k, not from a symbolic M.
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "generator/symbolic/rigid_dynamics.h"
#include "ir/model.h"

namespace mbfe::gen {

/// The kernel `dynamics_jacobians(q, qd, qdd, t, K, C)`, K and C row-major
/// nq x nq. `qdd` are the acceleration input symbols. Call after
/// derive_rigid_dynamics().
Kernel derive_dynamics_jacobians(const ir::Model& model, RigidDerivation& d, const std::vector<GiNaC::symbol>& qdd);

}  // namespace mbfe::gen
