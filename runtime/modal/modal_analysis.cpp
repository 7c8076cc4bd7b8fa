#include "modal/modal_analysis.h"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

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
  SparseLdltShiftInvert op(K, M);
  Spectra::SparseSymMatProd<double> bop(M);
  Spectra::SymGEigsShiftSolver<SparseLdltShiftInvert, Spectra::SparseSymMatProd<double>,
                               Spectra::GEigsMode::ShiftInvert>
      solver(op, bop, k, ncv, options.shift);
  solver.init();
  solver.compute(Spectra::SortRule::LargestMagn, options.max_restarts, options.tolerance,
                 Spectra::SortRule::SmallestAlge);
  if (solver.info() != Spectra::CompInfo::Successful) {
    throw std::runtime_error("sparse modal analysis: Lanczos did not converge for the lowest " +
                             std::to_string(k) + " modes");
  }
  return finish(solver.eigenvalues(), solver.eigenvectors(), M);
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
  if (all) {
    throw std::invalid_argument("beam '" + beam.name + "' has " + std::to_string(n) +
                                " DOFs, above the dense limit " +
                                std::to_string(options.dense_limit) +
                                "; ask for the lowest k modes (sparse path)");
  }
  // Scale of the lowest eigenvalue: max diag(K)/diag(M) is 420 EI/(rho A le^4)
  // (slope DOF, consistent mass; 312 lumped), so dividing by 420 ne^4 gives
  // about EI/(rho A L^4): 1/97 of a pinned beam's first eigenvalue, 1/12 of a
  // cantilever's. A shift of -1 % of that is far below the lowest mode and
  // keeps K - sigma M definite when the beam has rigid (omega = 0) modes.
  const Eigen::VectorXd dk = beam.K.diagonal();
  const Eigen::VectorXd dm = beam.M.diagonal();
  const double ratio = (dk.array() / dm.array()).maxCoeff();
  const double ne = beam.num_nodes - 1;
  SparseModalOptions sparse;
  sparse.shift = -1e-2 * ratio / (420.0 * ne * ne * ne * ne);
  return modal_sparse(beam.M, beam.K, options.num_modes, sparse);
}

}  // namespace mbfe::runtime
