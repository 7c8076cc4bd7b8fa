// ||A^-1||_F from any factorisation of a square A, one unit column at a
// time: the exact (up to rounding) figure behind the conditioning bounds
//   sigma_min(A) >= 1 / ||A^-1||_F,  rcond_2(A) >= 1 / (||A||_F ||A^-1||_F)
// that small_lu.h gives for the partitioned solver's small systems and the
// augmented formulation (coupled/coupled_dynamics.cpp) for its saddle-point
// matrix. Cheap where n is small; `column` is the caller's, so no allocation
// once it is sized.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace mbfe::runtime {

/// sqrt(sum_c ||A^-1 e_c||^2), where unit_solve(c, x) overwrites the zero
/// vector x with A^-1 e_c (placing the 1 where its factors' row permutation
/// puts it, so that no permutation is applied to a whole vector).
template <class UnitSolve>
double inverse_frobenius_norm(Eigen::Index n, Eigen::VectorXd& column, UnitSolve&& unit_solve) {
  double sum = 0.0;
  for (Eigen::Index c = 0; c < n; ++c) {
    column.setZero(n);
    unit_solve(c, column);
    sum += column.squaredNorm();
  }
  return std::sqrt(sum);
}

}  // namespace mbfe::runtime
