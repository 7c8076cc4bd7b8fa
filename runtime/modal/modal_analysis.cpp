#include "runtime/modal/modal_analysis.h"

#include <Eigen/Dense>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <algorithm>
#include <memory>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "runtime/modal/banded_qr.h"

namespace mbfe::runtime {

namespace {

/// (K - sigma M)^{-1} x by a sparse LDLT, in the form Spectra's
/// SymGEigsShiftSolver (ShiftInvert mode) expects of its OpType.
class SparseLdltShiftInvert {
 public:
  using Scalar = double;
  SparseLdltShiftInvert(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M)
      : K_(K), M_(M) {}
  Eigen::Index rows() const { return K_.rows(); }
  Eigen::Index cols() const { return K_.cols(); }
  void set_shift(double sigma) {
    Eigen::SparseMatrix<double> A = K_ - sigma * M_;
    ldlt_.compute(A);
    if (ldlt_.info() != Eigen::Success) {
      throw std::runtime_error("sparse modal analysis: K - sigma M (sigma = " +
                               std::to_string(sigma) + ") cannot be factorised");
    }
  }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, rows());
    y.noalias() = ldlt_.solve(x);
  }

 private:
  const Eigen::SparseMatrix<double>& K_;
  const Eigen::SparseMatrix<double>& M_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
};

/// (K - sigma M)^{-1} x with K = S^T S given by its factor S and sigma <= 0:
/// A = [S; sqrt(-sigma) U] (U^T U = M) and A = Q R, so K - sigma M = R^T R
/// and the solve is two banded triangular solves; K itself is never formed.
class FactorQrShiftInvert {
 public:
  using Scalar = double;
  FactorQrShiftInvert(const Eigen::SparseMatrix<double>& S, const Eigen::SparseMatrix<double>& M)
      : S_(S), M_(M) {}
  Eigen::Index rows() const { return S_.cols(); }
  Eigen::Index cols() const { return S_.cols(); }
  void set_shift(double sigma) {
    if (sigma > 0.0) {
      throw std::invalid_argument(
          "sparse modal analysis: a stiffness factor needs a shift <= 0, got " +
          std::to_string(sigma));
    }
    const Eigen::Index n = S_.cols();
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(S_.nonZeros() + 4 * M_.nonZeros());
    for (int c = 0; c < S_.outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(S_, c); it; ++it)
        t.emplace_back(it.row(), it.col(), it.value());
    Eigen::Index rows = S_.rows();
    if (sigma < 0.0) {
      Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>>
          llt(M_);
      if (llt.info() != Eigen::Success) {
        throw std::runtime_error("sparse modal analysis: M is not positive definite");
      }
      const Eigen::SparseMatrix<double> U = Eigen::SparseMatrix<double>(llt.matrixU());
      const double root = std::sqrt(-sigma);
      for (int c = 0; c < U.outerSize(); ++c)
        for (Eigen::SparseMatrix<double>::InnerIterator it(U, c); it; ++it)
          t.emplace_back(rows + it.row(), it.col(), root * it.value());
      rows += n;
    }
    Eigen::SparseMatrix<double, Eigen::RowMajor> A(rows, n);
    A.setFromTriplets(t.begin(), t.end());
    qr_ = std::make_unique<BandedQr>(A);
  }
  void perform_op(const double* x_in, double* y_out) const { qr_->solve_normal(x_in, y_out); }

 private:
  const Eigen::SparseMatrix<double>& S_;
  const Eigen::SparseMatrix<double>& M_;
  std::unique_ptr<BandedQr> qr_;
};

/// The k eigenpairs of K Phi = M Phi Lambda nearest options.shift, unsorted.
struct EigenPairs {
  Eigen::VectorXd lambda;
  Eigen::MatrixXd vectors;
};

template <typename Op>
EigenPairs lanczos(Op& op, const Eigen::SparseMatrix<double>& M, int k, int ncv,
                   const SparseModalOptions& options);

void check_sizes(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K) {
  if (M.rows() != M.cols() || K.rows() != K.cols() || M.rows() != K.rows()) {
    throw std::invalid_argument("modal analysis: M is " + std::to_string(M.rows()) + " x " +
                                std::to_string(M.cols()) + ", K is " + std::to_string(K.rows()) +
                                " x " + std::to_string(K.cols()) +
                                ", expected two square matrices of one size");
  }
}

/// Sorts modes by omega ascending, M-normalises and fixes signs.
ModalBasis finish(const Eigen::VectorXd& lambda, const Eigen::MatrixXd& vectors,
                  const Eigen::SparseMatrix<double>& M) {
  const Eigen::Index k = lambda.size();
  std::vector<Eigen::Index> order(k);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](Eigen::Index a, Eigen::Index b) { return lambda[a] < lambda[b]; });
  ModalBasis basis;
  basis.omega.resize(k);
  basis.phi.resize(vectors.rows(), k);
  for (Eigen::Index j = 0; j < k; ++j) {
    const Eigen::Index src = order[j];
    // Round-off can leave a rigid mode at -1e-9: clamp to zero.
    basis.omega[j] = std::sqrt(std::max(lambda[src], 0.0));
    Eigen::VectorXd v = vectors.col(src);
    v /= std::sqrt(v.dot(M * v));
    // Sign: the first entry above 1e-3 of the largest magnitude is positive
    // (the largest entry itself is ambiguous in symmetric modes, where two
    // entries tie in magnitude).
    const double vmax = v.cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < v.size(); ++i) {
      if (std::abs(v[i]) > 1e-3 * vmax) {
        if (v[i] < 0.0) v = -v;
        break;
      }
    }
    basis.phi.col(j) = v;
  }
  basis.complete = (k == vectors.rows());
  return basis;
}

}  // namespace

ModalBasis modal_dense(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K) {
  check_sizes(M, K);
  const Eigen::MatrixXd Md(M);
  const Eigen::MatrixXd Kd(K);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(Kd, Md);
  if (solver.info() != Eigen::Success) {
    throw std::runtime_error("dense modal analysis failed (is M positive definite?)");
  }
  return finish(solver.eigenvalues(), solver.eigenvectors(), M);
}

ModalBasis modal_sparse(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K,
                        int k, const SparseModalOptions& options) {
  check_sizes(M, K);
  const int n = static_cast<int>(M.rows());
  if (k < 1 || k >= n) {
    throw std::invalid_argument("sparse modal analysis: asked for " + std::to_string(k) +
                                " modes, expected 1 <= k < n = " + std::to_string(n));
  }
  const int ncv = options.subspace > 0 ? std::min(n, options.subspace)
                                       : std::min(n, std::max(2 * k + 1, k + 20));
  if (options.stiffness_factor) {
    if (options.stiffness_factor->cols() != n) {
      throw std::invalid_argument("sparse modal analysis: the stiffness factor has " +
                                  std::to_string(options.stiffness_factor->cols()) +
                                  " columns, expected " + std::to_string(n));
    }
    FactorQrShiftInvert op(*options.stiffness_factor, M);
    const EigenPairs pairs = lanczos(op, M, k, ncv, options);
    return finish(pairs.lambda, pairs.vectors, M);
  }
  SparseLdltShiftInvert op(K, M);
  const EigenPairs pairs = lanczos(op, M, k, ncv, options);
  return finish(pairs.lambda, pairs.vectors, M);
}

namespace {

template <typename Op>
EigenPairs lanczos(Op& op, const Eigen::SparseMatrix<double>& M, int k, int ncv,
                   const SparseModalOptions& options) {
  Spectra::SparseSymMatProd<double> bop(M);
  Spectra::SymGEigsShiftSolver<Op, Spectra::SparseSymMatProd<double>,
                               Spectra::GEigsMode::ShiftInvert>
      solver(op, bop, k, ncv, options.shift);
  solver.init();
  solver.compute(Spectra::SortRule::LargestMagn, options.max_restarts, options.tolerance,
                 Spectra::SortRule::SmallestAlge);
  if (solver.info() != Spectra::CompInfo::Successful) {
    throw std::runtime_error("sparse modal analysis: Lanczos did not converge for the " +
                             std::to_string(k) + " modes nearest the shift " + std::to_string(options.shift));
  }
  return {solver.eigenvalues(), solver.eigenvectors()};
}

}  // namespace

int eigenvalues_below(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K, double lambda) {
  check_sizes(M, K);
  // Sylvester's law of inertia: K - lambda M = P^T L D L^T P is a congruence,
  // so D has as many negative entries as K - lambda M has negative
  // eigenvalues, which (M positive definite) is the number of eigenvalues of
  // K Phi = M Phi Lambda below lambda.
  const Eigen::SparseMatrix<double> A = K - lambda * M;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
  if (ldlt.info() != Eigen::Success) {
    throw std::runtime_error("modal analysis: K - lambda M (lambda = " + std::to_string(lambda) +
                             ") cannot be factorised to count its eigenvalues");
  }
  return static_cast<int>((ldlt.vectorD().array() < 0.0).count());
}

ModalBasis modal_below(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K,
                       double omega_max, const SlicedModalOptions& options) {
  check_sizes(M, K);
  const int n = static_cast<int>(M.rows());
  if (!(omega_max > 0.0)) {
    throw std::invalid_argument("spectrum slicing: the bound must be > 0 rad/s, got " + std::to_string(omega_max));
  }
  if (options.slice_modes < 1) {
    throw std::invalid_argument("spectrum slicing: slice_modes must be >= 1, got " +
                                std::to_string(options.slice_modes));
  }
  if (options.stiffness_factor && options.stiffness_factor->cols() != n) {
    throw std::invalid_argument("spectrum slicing: the stiffness factor has " +
                                std::to_string(options.stiffness_factor->cols()) + " columns, expected " +
                                std::to_string(n));
  }
  // Counted a hair above the bound: a mode within round-off of it is one the
  // caller may still judge below (by its computed omega), so the mode
  // returned beyond the bound is clearly beyond it.
  const int wanted = eigenvalues_below(M, K, omega_max * omega_max * (1.0 + 1e-8)) + 1;
  if (wanted >= n) {
    throw std::invalid_argument("spectrum slicing: " + std::to_string(wanted - 1) + " of the " +
                                std::to_string(n) + " modes lie below " + std::to_string(omega_max) +
                                " rad/s, nearly every one");
  }
  double edge = options.lower;  // between two eigenvalues; every one below it is found
  if (eigenvalues_below(M, K, edge) != 0) {
    throw std::invalid_argument("spectrum slicing: the lower edge " + std::to_string(edge) +
                                " lies above the lowest eigenvalue");
  }
  const int per_run = std::min(options.slice_modes, n - 1);
  // A run whose modes disagree with the inertia count (Lanczos can miss a copy
  // of a nearly repeated eigenvalue) is repeated once with twice the modes.
  const int wide_run = std::min(2 * per_run, n - 1);
  bool widened = false;
  Eigen::VectorXd lambda(wanted);
  Eigen::MatrixXd vectors(n, wanted);
  int found = 0;
  double shift = edge;
  // Each run returns the per_run eigenvalues nearest its shift, i.e. every
  // eigenvalue inside (shift - D, shift + D). A run counts when that window
  // reaches below the edge; its new eigenvalues end at a new edge in the
  // widest gap of the window's upper third (so that a cluster of nearly equal
  // eigenvalues tends to stay in one run: vectors of a cluster split between
  // runs are M-orthogonal only to the Ritz tolerance over the cluster's gaps),
  // and the inertia count between the two edges must agree.
  const int max_runs = 4 * (wanted / per_run + 1) + 20;
  for (int run = 0; found < wanted; ++run) {
    if (run == max_runs) {
      throw std::runtime_error("spectrum slicing: " + std::to_string(found) + " of " + std::to_string(wanted) +
                               " modes after " + std::to_string(run) + " Lanczos runs");
    }
    SparseModalOptions so;
    so.shift = shift;
    so.tolerance = options.tolerance;
    so.max_restarts = options.max_restarts;
    const int nev = widened ? wide_run : per_run;
    const int ncv = std::min(n, 2 * nev + 1);
    EigenPairs pairs;
    if (options.stiffness_factor && shift <= 0.0) {
      FactorQrShiftInvert op(*options.stiffness_factor, M);
      pairs = lanczos(op, M, nev, ncv, so);
    } else {
      SparseLdltShiftInvert op(K, M);
      pairs = lanczos(op, M, nev, ncv, so);
    }
    const double reach = (pairs.lambda.array() - shift).abs().maxCoeff();
    if (shift - reach >= edge) {  // a gap above the edge: move the shift back
      shift = edge + 0.25 * (shift - edge);
      continue;
    }
    const double upper = shift + reach * (1.0 - 1e-9);  // a tie at the window's rim may be missing
    std::vector<Eigen::Index> inside;
    for (Eigen::Index j = 0; j < pairs.lambda.size(); ++j)
      if (pairs.lambda[j] > edge && pairs.lambda[j] < upper) inside.push_back(j);
    std::sort(inside.begin(), inside.end(),
              [&](Eigen::Index a, Eigen::Index b) { return pairs.lambda[a] < pairs.lambda[b]; });
    const int m = static_cast<int>(inside.size());
    int take = 0;
    double next_edge = 0.5 * (edge + upper);
    double widest = -1.0;
    for (int i = (2 * m) / 3; i < m; ++i) {
      const double lo = pairs.lambda[inside[i]];
      const double hi = i + 1 < m ? pairs.lambda[inside[i + 1]] : upper;
      if (hi - lo > widest) {
        widest = hi - lo;
        take = i + 1;
        next_edge = 0.5 * (lo + hi);
      }
    }
    const int counted = eigenvalues_below(M, K, next_edge) - found;
    if (counted != take && !widened) {
      widened = true;
      continue;
    }
    if (counted != take) {
      throw std::runtime_error("spectrum slicing: " + std::to_string(counted) + " eigenvalues lie between " +
                               std::to_string(edge) + " and " + std::to_string(next_edge) + ", Lanczos found " +
                               std::to_string(take));
    }
    for (int i = 0; i < take && found < wanted; ++i, ++found) {
      lambda[found] = pairs.lambda[inside[i]];
      vectors.col(found) = pairs.vectors.col(inside[i]);
    }
    // Next shift: ahead of the edge by 0.7 of the half-width this run's
    // density predicts, so the next window overlaps the edge. Eigenvalues of
    // a beam or a string thin out upwards: the prediction errs on the safe side.
    // (A window with no new eigenvalue has its own count for a density.)
    const double density = take > 0 ? take / (next_edge - edge) : nev / (2.0 * reach);
    widened = false;
    edge = next_edge;
    shift = edge + 0.7 * (0.5 * per_run) / density;
  }
  return finish(lambda, vectors, M);
}

// Scale of the lowest eigenvalue: max diag(K)/diag(M) is 420 EI/(rho A le^4)
// (slope DOF, consistent mass; 312 lumped), so dividing by 420 ne^4 gives
// about EI/(rho A L^4): 1/97 of a pinned beam's first eigenvalue, 1/12 of a
// cantilever's. -1 % of that is far below the lowest mode and keeps
// K - sigma M definite when the beam has rigid (omega = 0) modes.
double shift_below_lowest(const BeamSystem& beam) {
  const Eigen::VectorXd dk = beam.K.diagonal();
  const Eigen::VectorXd dm = beam.M.diagonal();
  const double ratio = (dk.array() / dm.array()).maxCoeff();
  const double ne = beam.num_nodes - 1;
  return -1e-2 * ratio / (420.0 * ne * ne * ne * ne);
}

ModalBasis modal_analysis(const BeamSystem& beam, const ModalOptions& options) {
  const int n = static_cast<int>(beam.M.rows());
  const bool all = options.num_modes <= 0 || options.num_modes >= n;
  if (n <= options.dense_limit) {
    ModalBasis basis = modal_dense(beam.M, beam.K);
    if (!all) {
      basis.omega.conservativeResize(options.num_modes);
      basis.phi.conservativeResize(Eigen::NoChange, options.num_modes);
      basis.complete = false;
    }
    return basis;
  }
  if (options.up_to_omega > 0.0) {
    SlicedModalOptions sliced;
    sliced.lower = shift_below_lowest(beam);
    sliced.slice_modes = options.slice_modes;
    if (beam.stiffness_factor.size() > 0) sliced.stiffness_factor = &beam.stiffness_factor;
    return modal_below(beam.M, beam.K, options.up_to_omega, sliced);
  }
  if (all) {
    throw std::invalid_argument("beam '" + beam.name + "' has " + std::to_string(n) +
                                " DOFs, above the dense limit " +
                                std::to_string(options.dense_limit) +
                                "; ask for the lowest k modes (sparse path)");
  }
  SparseModalOptions sparse;
  sparse.shift = shift_below_lowest(beam);
  if (beam.stiffness_factor.size() > 0) sparse.stiffness_factor = &beam.stiffness_factor;
  return modal_sparse(beam.M, beam.K, options.num_modes, sparse);
}

}  // namespace mbfe::runtime
