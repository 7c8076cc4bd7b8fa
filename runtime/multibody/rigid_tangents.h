// The tangents of the rigid part's equations of motion at one state:
//
//   tau(q, v) = M(q) a + F(q, v) - Q(q, v, t),  a held fixed,
//   K = d tau / d q,  C = d tau / d v,
//
// what a Newton matrix or a linearisation of the bodies needs (the coupled
// model's tangents, coupled/coupled_tangents.h; the linearised run of an
// accuracy estimate). From the generated Jacobian kernel when the solver has
// one, else by central differences of the kernels.
#pragma once

#include <Eigen/Core>

#include "runtime/abi/mbfe_model_abi.h"

namespace mbfe::runtime {

/// K and C (nb x nb, nb = kernels.num_coordinates; N/m, N s/m or their
/// rotational units by coordinate) of `kernels` at (t, q, v) with the
/// accelerations `a` held fixed; q, v, a have nb entries each (planar models:
/// q and v alike). The differences, where used, take a relative step of
/// 6e-6 (1 + |x|) per coordinate.
void rigid_dynamics_tangents(const mbfe_model_v1& kernels, double t, const double* q, const double* v, const double* a,
                             Eigen::MatrixXd& K, Eigen::MatrixXd& C);

}  // namespace mbfe::runtime
