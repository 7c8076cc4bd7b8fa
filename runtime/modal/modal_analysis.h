// Modal analysis K Phi = M Phi Omega^2 (eqs (20)-(22) of the paper) with
// mass-normalised modes, Phi^T M Phi = I.
//
// Three paths:
//  - dense (Eigen::GeneralizedSelfAdjointEigenSolver): every mode; forms
//    dense n x n copies of M and K, so only for small models;
//  - sparse shift-invert Lanczos (Spectra::SymGEigsShiftSolver with a sparse
//    LDLT of K - sigma M): the lowest k modes of a large model, memory
//    O(nnz + n k), never a dense n x n matrix;
//  - spectrum slicing: every mode below a bound, by shift-invert Lanczos runs
//    at successive shifts whose results the inertia of K - sigma M checks
//    (docs/beams-and-modal.md, "Every mode below a bound"). For the hundreds
//    or thousands of modes a cap keeps in a large beam, where one Lanczos run
//    would need a basis nearly as wide as the model.
// Mode signs are fixed so that the first significant entry (above 1e-3 of the
// largest) of each column of Phi is positive, so the two paths agree column
// by column.
#pragma once

#include <Eigen/SparseCore>
#include <optional>

#include "runtime/fem/beam_system.h"
#include "runtime/modal/modal_basis.h"
#include "runtime/modal/slicing_defaults.h"

namespace mbfe::runtime {

/// Every mode, dense. @param M, K symmetric n x n, M positive definite.
/// @throws std::runtime_error if the eigen-solver fails (M not positive definite).
ModalBasis modal_dense(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K);

struct SparseModalOptions {
  /// Shift sigma (rad^2/s^2): the modes nearest sigma are found. Must lie
  /// below the lowest eigenvalue for "the lowest k" to hold; a small negative
  /// value also copes with rigid-body (omega = 0) modes.
  double shift = 0.0;
  /// Lanczos subspace size; 0 = min(n, max(2k + 1, k + 20)).
  int subspace = 0;
  double tolerance = 1e-10;  // relative, on the Ritz values
  int max_restarts = 1000;
  /// Optional S with S^T S = K (BeamSystem::stiffness_factor). When given,
  /// K - sigma M (sigma <= 0) is factorised by a sparse QR of
  /// [S; sqrt(-sigma) U] (U^T U = M) instead of an LDLT of K - sigma M. This
  /// never squares the conditioning: cond(K) of a beam grows as ne^4 and the
  /// LDLT loses the lowest modes entirely near 50,000 elements (1e5 DOF),
  /// while the QR keeps them to ~eps sqrt(cond(K)).
  const Eigen::SparseMatrix<double>* stiffness_factor = nullptr;
};

/// The lowest k modes by sparse shift-invert Lanczos. @param k 1 <= k < n.
/// @throws std::invalid_argument on bad k or sizes (or a stiffness factor
/// with a positive shift); std::runtime_error if
/// K - sigma M cannot be factorised or Lanczos does not converge.
ModalBasis modal_sparse(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K,
                        int k, const SparseModalOptions& options = {});

/// The number of eigenvalues of K Phi = M Phi Lambda below lambda (the
/// negative pivots of a sparse LDLT of K - lambda M; Sylvester's law of
/// inertia). @throws std::runtime_error if K - lambda M cannot be factorised
/// (lambda is an eigenvalue).
int eigenvalues_below(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K, double lambda);

struct SlicedModalOptions {
  /// Eigenvalue (rad^2/s^2) below the lowest one, where slicing starts.
  double lower = -1.0;
  /// Modes per Lanczos run (its basis is 2 slice_modes + 1 wide;
  /// slicing_defaults.h says why 30).
  int slice_modes = kDefaultSliceModes;
  double tolerance = 1e-10;  // relative, on the Ritz values
  int max_restarts = 1000;
  /// As SparseModalOptions::stiffness_factor, for the runs with a shift <= 0.
  const Eigen::SparseMatrix<double>* stiffness_factor = nullptr;
};

/// Every mode with omega <= omega_max and the first one above it (so a caller
/// knows the spectrum beyond the bound starts there), by spectrum slicing.
/// Memory O(nnz + n k) for the k modes returned.
/// @throws std::invalid_argument on omega_max <= 0, slice_modes < 1, a
/// lower edge above the lowest eigenvalue, or a bound above all but one mode
/// (the dense path is the one for that); std::runtime_error if a factorisation
/// fails, Lanczos does not converge, a run's modes disagree with the inertia
/// count twice (the second time with twice the modes), or the runs do not
/// reach the bound in a few times the runs it should take.
ModalBasis modal_below(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K,
                       double omega_max, const SlicedModalOptions& options = {});

struct ModalOptions {
  /// 0 = every mode; otherwise the lowest num_modes.
  int num_modes = 0;
  /// > 0 (rad/s): for a model above dense_limit, every mode up to this and the
  /// first above it (spectrum slicing) instead of num_modes.
  double up_to_omega = 0.0;
  /// Modes per Lanczos run of the slicing (SlicedModalOptions::slice_modes).
  int slice_modes = SlicedModalOptions{}.slice_modes;
  /// Models with more DOFs than this use the sparse path (and need
  /// num_modes > 0); smaller ones use the dense path.
  int dense_limit = 2000;
};

/// A shift (rad^2/s^2, < 0) below the lowest eigenvalue of `beam`, from its
/// element stiffness/mass ratio; K - sigma M stays definite with rigid modes.
double shift_below_lowest(const BeamSystem& beam);

/// Modal analysis of one assembled beam, choosing the path by size. The
/// sparse and sliced paths shift by -1e-2 times a lower estimate of the beam's lowest
/// eigenvalue (from its element stiffness/mass ratio), so beams with rigid
/// modes work too, and uses the beam's stiffness factor when it has one. @throws std::invalid_argument when a model above
/// dense_limit asks for every mode.
ModalBasis modal_analysis(const BeamSystem& beam, const ModalOptions& options = {});

}  // namespace mbfe::runtime
