// The closed loops of a model of bodies (`constraints:`), Phi(q, t) = 0 with
// nc rows, as the loop systems use them: the kernels' Phi, J (nc x nv, with
// respect to the velocity coordinates) and gamma = -(dJ/dt) v; the choice of
// the dependent velocity coordinates (the largest pivots of J); and Newton's
// closure of Phi by moving either the dependent coordinates only or all of
// them by the least-norm step (docs/partitioning.md, "Closed loops").
//
// A loop row that repeats the conditions of the others (a spatial revolute
// loop closing a linkage whose joint axes are all parallel: its rows out of
// the plane vanish) is found at the configuration the closure is built at,
// and a little way off it, by a column-pivoted QR of the rows, and left out:
// the closure works with the independent rows only, and residual() still
// measures every row.
//
// Driven joints (`motion:`) are driving constraints, one row each after the
// loops' rows: q_d - motion(t) = 0, a unit row of J, J v = motion'(t) at
// velocity level and gamma = motion''(t) at acceleration level. Their
// multipliers are the drives' reactions; their coordinates are always among
// the dependent ones (no other column reaches their rows).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "runtime/abi/mbfe_model_abi.h"
#include "runtime/multibody/rigid_coordinates.h"

namespace mbfe::runtime {

/// Which velocity coordinates the loops make dependent (nc of them, closed
/// by Newton) and which stay independent (nv - nc, integrated).
struct LoopPartition {
  std::vector<int> dependent;    // ascending indices into v
  std::vector<int> independent;  // ascending indices into v
};

class LoopClosure {
 public:
  /// @param model a solver with loop kernels (num_loop_rows > 0); must outlive this.
  /// @param rows_at a configuration (nq) at which the loop rows that repeat
  ///        the others are found and left out; null keeps every row.
  /// @throws std::invalid_argument if it has no loops or more rows (loops'
  ///         and drives') than velocities.
  LoopClosure(const mbfe_model_v1& model, RigidCoordinates coordinates, const double* rows_at = nullptr);

  /// Every row used: the loops' independent rows and then one per driven joint.
  int rows() const { return nc_; }
  int loop_rows() const { return na_; }
  int driven_rows() const { return nc_ - na_; }
  /// The loop rows left out as repeating the others (indices into the
  /// kernels' rows), and the loop of each.
  const std::vector<int>& redundant_rows() const { return redundant_; }
  const std::vector<std::string>& redundant_row_loops() const { return redundant_loops_; }
  const RigidCoordinates& coordinates() const { return coordinates_; }
  /// Per driven joint, model order: its entry of v (its entry of q is
  /// the model's driven_positions).
  const std::vector<int>& driven_velocities() const { return drive_v_; }

  /// Phi(q, t) (nc; m, or a sine or cosine for an orientation row; a
  /// drive's row in its coordinate's unit).
  void phi(const double* q, double t, Eigen::VectorXd& out) const;
  /// J(q) (nc x nv).
  void jacobian(const double* q, Eigen::MatrixXd& out) const;
  /// gamma(q, v, t) = -(dJ/dt) v, motion''(t) in the drives' rows (nc).
  void gamma(const double* q, const double* v, double t, Eigen::VectorXd& out) const;
  /// The right-hand side of J v = nu(t): 0 in the loops' rows, motion'(t)
  /// in the drives' (nc).
  void velocity_target(double t, Eigen::VectorXd& out) const;
  /// The driven coordinates of q and v set to their motion at t.
  void impose_motion(double t, double* q, double* v) const;
  /// max |Phi(q)| over the loops' rows, the loop residual (m).
  double residual(const double* q) const;

  /// The best dependent coordinates at q: the first nc pivots of a
  /// column-pivoted QR of J. `sigma_min` receives the smallest singular value
  /// of the chosen J_d. @throws SingularConstraintError naming the loop that
  /// carries most of the lost rank when J has rank below nc (a redundant
  /// loop, or a linkage at a dead point), at time t.
  /// `keep`, when given (nv entries), marks velocity coordinates to leave
  /// independent where J allows: their columns pivot last.
  LoopPartition choose_partition(const double* q, double t, double* sigma_min = nullptr,
                                 const std::vector<bool>* keep = nullptr) const;

  /// Newton on Phi(q) = 0 moving only the `dependent` velocity directions
  /// (q <- q (+) dv, dv zero elsewhere) until max |Phi| <= kClosureTol.
  /// Returns the iterations. @throws NewtonClosureError (naming the loop
  /// with the largest residual) when it does not get there.
  int close(double* q, const std::vector<int>& dependent, double t) const;
  /// Newton with the least-norm step dv = -J^T (J J^T)^-1 Phi over all
  /// velocity coordinates (the augmented formulation's projection).
  int project(double* q, double t) const;
  /// v <- v - J^T (J J^T)^-1 (J v - nu(t)): the nearest velocity with Phi' = 0.
  void project_velocity(const double* q, double t, double* v) const;

  /// Newton stops when max |Phi| is below this (m): a few ulps of a
  /// linkage of metres.
  static constexpr double kClosureTol = 1e-13;
  /// Newton also stops, converged, at a residual below this (m) that it no
  /// longer halves: round-off of a large linkage.
  static constexpr double kStagnationTol = 1e-10;
  static constexpr int kMaxNewton = 30;
  /// J_d is singular when sigma_min(J_d) < kSingularLoops ||J||_F (double
  /// precision with a margin of ~1e3 ulps, as for contacts).
  static constexpr double kSingularLoops = 1e-13;
  /// A loop row repeats the others when its pivot in the QR of the rows is
  /// below this fraction of the largest: a structural repetition leaves
  /// round-off (~1e-16), a linkage near (not at) a dead point far more.
  static constexpr double kRedundantRow = 1e-9;
  /// The rows are also counted at a configuration moved by about this much
  /// (rad or m) in every velocity coordinate, and the larger rank decides: a
  /// dead point loses rank at one configuration only, so its rows are the
  /// linkage's own (and the run then stops there, SingularConstraintError).
  static constexpr double kRedundancyProbe = 0.05;

 private:
  [[noreturn]] void fail(const Eigen::VectorXd& phi, double t, int iterations) const;
  /// rows_ and redundant_ from the rows of J at q (see the header comment).
  void select_rows(const double* q);
  /// The motion at t into the scratch below.
  void motion(double t) const;

  const mbfe_model_v1& model_;
  RigidCoordinates coordinates_;
  int nl_;      // the kernels' loop rows
  int na_ = 0;  // of them used (rows_)
  int nc_ = 0;  // used rows with the drives'
  int nv_;
  std::vector<int> rows_;       // the loop rows used, ascending
  std::vector<int> redundant_;  // the loop rows left out, ascending
  std::vector<std::string> redundant_loops_;
  std::vector<int> drive_v_, drive_q_;  // per driven joint: its entry of v, of q
  std::vector<std::string> row_loop_;   // per row: its loop's name, or the driven body's
  std::vector<std::string> row_what_;   // per row: "loop 'name'" or "the motion of 'body'"
  mutable Eigen::VectorXd motion_q_, motion_qd_, motion_qdd_;
  mutable Eigen::VectorXd full_phi_;  // every loop row, before the selection
  mutable Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> full_j_;
};

}  // namespace mbfe::runtime
