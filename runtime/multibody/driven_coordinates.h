// Driven joints (`joint.motion`, docs/model-format.md): coordinates whose
// q'' is known. Both the rigid system and the coupled one eliminate them the
// same way.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace mbfe::runtime {

/// In M q'' = rhs, the entries `driven` of q'' are `qdd_driven` (in that
/// order): their columns of M move to the right-hand side and their rows
/// become q''_d = qdd_driven, so that M stays symmetric positive definite and
/// the free coordinates follow M_ff q''_f = rhs_f - M_fd q''_d.
inline void eliminate_driven(Eigen::MatrixXd& M, Eigen::VectorXd& rhs, const std::vector<int>& driven,
                             const Eigen::VectorXd& qdd_driven) {
  for (std::size_t k = 0; k < driven.size(); ++k) rhs -= M.col(driven[k]) * qdd_driven[static_cast<Eigen::Index>(k)];
  for (std::size_t k = 0; k < driven.size(); ++k) {
    const int d = driven[k];
    M.row(d).setZero();
    M.col(d).setZero();
    M(d, d) = 1.0;
    rhs[d] = qdd_driven[static_cast<Eigen::Index>(k)];
  }
}

}  // namespace mbfe::runtime
