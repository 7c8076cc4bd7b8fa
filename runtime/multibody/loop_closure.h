// The closed loops of a model of bodies (`constraints:`), Phi(q) = 0 with nc
// rows, as the loop systems use them: the kernels' Phi, J (nc x nv, with
// respect to the velocity coordinates) and gamma = -(dJ/dt) v; the choice of
// the dependent velocity coordinates (the largest pivots of J); and Newton's
// closure of Phi by moving either the dependent coordinates only or all of
// them by the least-norm step (docs/partitioning.md, "Closed loops").
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
  /// @throws std::invalid_argument if it has no loops or more rows than velocities.
  LoopClosure(const mbfe_model_v1& model, RigidCoordinates coordinates);

  int rows() const { return nc_; }
  const RigidCoordinates& coordinates() const { return coordinates_; }

  /// Phi(q) (nc; m, or a sine or cosine for an orientation row).
  void phi(const double* q, Eigen::VectorXd& out) const;
  /// J(q) (nc x nv).
  void jacobian(const double* q, Eigen::MatrixXd& out) const;
  /// gamma(q, v) = -(dJ/dt) v (nc).
  void gamma(const double* q, const double* v, Eigen::VectorXd& out) const;
  /// max |Phi(q)|, the loop residual (m).
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
  /// v <- v - J^T (J J^T)^-1 J v: the nearest velocity with Phi' = 0.
  void project_velocity(const double* q, double* v) const;

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

 private:
  [[noreturn]] void fail(const Eigen::VectorXd& phi, double t, int iterations) const;

  const mbfe_model_v1& model_;
  RigidCoordinates coordinates_;
  int nc_, nv_;
  std::vector<std::string> row_loop_;  // per row: its loop's name
};

}  // namespace mbfe::runtime
