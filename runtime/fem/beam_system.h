// One beam's assembled finite-element system, supports applied:
//   M q'' + C q' + K q = P          (eq (11a) of the paper)
// q = the beam's free DOFs in contract order: nodes from s = 0 to s = L,
// [w, w'] per node, DOFs fixed by supports removed.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "model/model.h"

namespace mbfe::runtime {

struct BeamSystem {
  std::string name;
  int num_nodes = 0;                 // elements + 1
  double element_length = 0.0;       // m
  Eigen::SparseMatrix<double> M;     // kg (consistent or lumped), n x n
  Eigen::SparseMatrix<double> K;     // N/m
  Eigen::SparseMatrix<double> C;     // alpha M + beta K
  Eigen::VectorXd P;                 // N: gravity (own weight) + point loads
  /// free_dof[k] = index into the full 2 * num_nodes vector of free DOF k.
  std::vector<int> free_dof;
  /// full_to_free[i] = free index of full DOF i, or -1 if fixed by a support.
  std::vector<int> full_to_free;
};

/// Assembles one beam. @param gravity ground-frame gravity (m/s^2); its
/// transverse component loads the beam with its own weight.
BeamSystem assemble_beam(const model::Beam& beam, const model::Vec2& gravity);

}  // namespace mbfe::runtime
