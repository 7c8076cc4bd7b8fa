// The Newton update of one step of the linearised run (linearised_run.h):
//
//   J = [[B, E], [-L' E^T, I + L' G]],  J delta = -residual,
//
// over the bodies' deviations y (B = K_r, or K_r + 2 C_r / h + 4 M_r / h^2 in
// a step), then the element forces z: the fixed elements first (links and
// dashpots, which act on beams alone, so E is zero in their columns), then
// the moving contacts. L' holds each law's slope dF/dx, G the elements'
// compliance through the modes.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>

namespace mbfe::runtime {

class LinearisedStepSolve {
 public:
  /// `bodies` rows of y, `fixed` fixed elements ahead of the contacts in z.
  LinearisedStepSolve(int bodies, int fixed) : nr_(bodies), nf_(fixed) {}

  /// The statics' update: one LU of J with its rows and columns
  /// equilibrated (forces, stiffnesses and compliances differ by twenty
  /// orders of magnitude), since B = K_r may be singular there (a body held
  /// by its contacts alone) and only the whole system is regular.
  /// @throws std::runtime_error when J is singular (a body held by nothing).
  Eigen::VectorXd equilibrated(const Eigen::MatrixXd& B, const Eigen::MatrixXd& E, const Eigen::MatrixXd& G,
                               const Eigen::VectorXd& slopes, const Eigen::VectorXd& residual) const;

  /// Starts the steps of a run with their constant, regular B.
  /// @throws std::runtime_error when B is singular.
  void start_steps(const Eigen::MatrixXd& B);
  /// A step's update by blocks: with E zero in the fixed elements' columns,
  ///   A = [[B, 0], [0, F]],  F = I + L_f' G_ff,
  /// and the moving contacts (a few) join through the Schur complement
  ///   S = I + L_c' G_cc - D A^-1 C.
  /// B is factored once a run (start_steps), F only when a fixed element's
  /// slope changes (a dropper going slack): a step factors no large matrix.
  /// @throws std::runtime_error when S is singular.
  Eigen::VectorXd by_blocks(const Eigen::MatrixXd& E, const Eigen::MatrixXd& G, const Eigen::VectorXd& slopes,
                            const Eigen::VectorXd& residual);

 private:
  int nr_, nf_;
  Eigen::FullPivLU<Eigen::MatrixXd> b_lu_;
  Eigen::PartialPivLU<Eigen::MatrixXd> f_lu_;
  Eigen::VectorXd f_slopes_;  // the fixed elements' slopes f_lu_ was made for (empty: none yet)
};

}  // namespace mbfe::runtime
