// Mass-normalised modes of K Phi = M Phi Omega^2 (eqs (20)-(22)).
#pragma once

#include <Eigen/Core>

namespace mbfe::runtime {

struct ModalBasis {
  Eigen::VectorXd omega;  // rad/s, ascending (k entries)
  Eigen::MatrixXd phi;    // n x k, Phi^T M Phi = I
  bool complete = false;  // k == n (all modes present)
};

}  // namespace mbfe::runtime
