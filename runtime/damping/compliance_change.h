// What an adjustment changes in the point compliance of a structure: the
// accuracy estimate of an adjusted run (docs/damping-adjustment.md, "The
// accuracy estimate", derives it).
//
// A force F e^{i Omega t} at a point of the structure (w = e^T q, e the point's
// displacement weights) moves the point by H(Omega) F, with the point
// receptance over the mass-normalised modes phi_j (p_j = phi_j^T e)
//
//   H(Omega) = sum_j p_j^2 / (k_j - m_j Omega^2 + i Omega c_j).
//
// An adjustment changes (m_j, c_j, k_j) of some modes (the capped ones, and
// the floored ones); the estimate is the change of H at the frequency Omega of
// the force there, relative to what sets the force's size at that frequency:
//
//   change = |H_adj(Omega) - H(Omega)| / (c_s + sum_{omega_j > Omega} p_j^2 / k_j)
//
// with c_s the compliance of a penalty contact's spring in series with the
// structure (0 for a pin, a link end, a load, a probe). The denominator is
// the point's quasi-static compliance at Omega: the spring plus the modes
// faster than the force (slower ones answer by their inertia, not their
// stiffness). Modes beyond a partial basis (a large beam's, all of them
// changed by the policy cap or mass) enter through three moments of the point,
// sum p^2, sum p^2 / k and sum p^2 / k^2, by sparse solves with the point's
// load less the basis' share (e - M Phi Phi^T e),
// and their original response (Rayleigh damping c = alpha + beta k, fitted to
// the basis' modes) by its expansion to first order in
// (Omega^2 - i Omega alpha) / k_j (valid because they are far above Omega).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "runtime/damping/modal_adjustment.h"
#include "runtime/modal/modal_basis.h"
#include "runtime/modal/state_spectrum.h"

namespace mbfe::runtime {

/// A point of a structure where a force acts or a displacement is read.
struct CompliancePoint {
  Eigen::VectorXd e;               // n: w = e^T q (dimensionless weights over the structure's coordinates)
  double series_compliance = 0.0;  // m/N: 1/k of a penalty contact's spring, 0 for none
  double omega = 0.0;              // rad/s: the highest frequency of the force there
};

/// What the adjustment changes at one point.
struct ComplianceChange {
  double compliance = 0.0;     // m/N: e^T K^-1 e, the original static point compliance
  double quasi_static = 0.0;   // m/N: c_s + sum over the modes faster than omega of p_j^2 / k_j
  double changed_share = 0.0;  // the changed modes' p_j^2 / k_j over quasi_static (their quasi-static share)
  double static_change = 0.0;  // |H_adj(0) - H(0)| / (c_s + compliance): the static compliance's relative change
  double change = 0.0;         // |H_adj(omega) - H(omega)| / quasi_static: the estimate
  double band_change = 0.0;    // the largest of static_change and |H_adj(W) - H(W)| / quasi_static(W), 0 < W <= omega
  double band_omega = 0.0;     // rad/s: the W of band_change (0 when it is static_change)
};

class ComplianceChangeEstimator {
 public:
  /// @param M, K, C the structure's matrices (n x n; K positive definite: a
  ///        structure its supports hold; the damping itself is read from
  ///        `original`, Rayleigh beyond a partial basis);
  /// @param basis its modes, complete or the lowest ones (every mode beyond a
  ///        partial basis must be one the policy cap or mass changes); held by
  ///        reference, not copied (a catenary wire's is tens of MB): it must
  ///        outlive the estimator;
  /// @param original their modal dynamics (unit modal mass).
  /// @throws std::invalid_argument when the sizes do not fit, std::runtime_error
  ///         when K is not positive definite.
  ComplianceChangeEstimator(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K,
                            const Eigen::SparseMatrix<double>& C, const ModalBasis& basis,
                            std::vector<ModalDynamics> original);

  /// A point's participations and moments: computed once (two sparse solves
  /// with K, one with M), then evaluated for any adjustment of the modes.
  struct Point {
    Eigen::VectorXd p2;  // p_j^2 over the basis
    double series_compliance = 0.0, omega = 0.0;
    double compliance = 0.0;                    // e^T K^-1 e
    double tail0 = 0.0, tail1 = 0.0, tail2 = 0.0;  // sum p^2, p^2/k, p^2/k^2 beyond the basis
  };
  Point point(const CompliancePoint& p) const;
  /// Many points at once, the same numbers as point() one by one would give
  /// up to round-off: the products with the basis as matrix products over
  /// fixed blocks of points, the blocks on the machine's cores (a catenary
  /// wire has hundreds of points, each product a pass over its kept modes).
  /// Each point's bits depend on its block alone, not on the thread count.
  std::vector<Point> points(const std::vector<CompliancePoint>& given) const;

  /// The change `adjusted` (the basis' modes adjusted: adjust_modes of
  /// `original`) makes at the point; with `band`, band_change too (512
  /// frequencies over [0, omega], a few hundred times the cost of the rest;
  /// without, band_change is static_change). @throws std::invalid_argument
  /// when the sizes do not fit, or a partial basis meets a policy other than
  /// cap or mass.
  ComplianceChange evaluate(const Point& point, const AdjustedModes& adjusted, bool band = false) const;

  int size() const { return static_cast<int>(M_.rows()); }
  const ModalBasis& basis() const { return basis_; }
  const std::vector<ModalDynamics>& original() const { return original_; }

 private:
  Eigen::SparseMatrix<double> M_;
  const ModalBasis& basis_;
  std::vector<ModalDynamics> original_;
  std::shared_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> k_factor_, m_factor_;
  double alpha_ = 0.0, beta_ = 0.0;  // 1/s, s: the Rayleigh damping c = alpha + beta k fitted to the basis' modes

  // One block of points (first, first + count) of `given` into `out`.
  void point_block(const std::vector<CompliancePoint>& given, std::size_t first, std::size_t count,
                   std::vector<Point>& out) const;
};

}  // namespace mbfe::runtime
