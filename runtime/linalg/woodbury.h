// Solves with A + W D W^T, given solves with A, by the Woodbury identity in
// the form that never inverts D (an entry of D may be zero):
//
//   (A + W D W^T)^-1 b = y - Z (I + D W^T Z)^-1 D W^T y,   y = A^-1 b,  Z = A^-1 W.
//
// W is n x k and dense but zero outside a few blocks of rows (a low-rank
// structure's coordinates), so W^T Z is formed block by block.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <string>
#include <vector>

namespace mbfe::runtime {

class WoodburyCorrection {
 public:
  /// Rows [row, row + rows) of W, for columns [col, col + cols), are where W
  /// is not zero.
  struct Block {
    int row = 0, rows = 0, col = 0, cols = 0;
  };

  /// Keeps W (n x k), D (k) and Z = A^-1 W, and factors I + D W^T Z.
  /// @throws std::runtime_error (naming `what`) when that capacity matrix is
  ///         singular, which it is exactly when A + W D W^T is (A regular).
  void factorize(Eigen::MatrixXd W, Eigen::VectorXd D, Eigen::MatrixXd Z, const std::vector<Block>& blocks,
                 const std::string& what);
  /// x = A^-1 b on entry, (A + W D W^T)^-1 b on return.
  void correct(Eigen::VectorXd& x);
  /// Columns of W (0: no correction).
  int width() const { return static_cast<int>(W_.cols()); }

 private:
  Eigen::MatrixXd W_, Z_;
  Eigen::VectorXd D_, s_;
  Eigen::PartialPivLU<Eigen::MatrixXd> capacity_lu_;
};

}  // namespace mbfe::runtime
