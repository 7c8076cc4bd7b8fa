// A solve with a sparse LDL^T factor that allocates nothing.
//
// Eigen's SimplicialLDLT::solve ends with an in-place permutation of its
// result, for which Eigen allocates a mask on every call, and its vectorD()
// returns D by value; in a step loop those are heap allocations per solve.
// This does the same operations in the same order (P b, L, D^-1, L^T, P^-1),
// reading D where the factor keeps it and permuting from a workspace into x:
// the same bits as Eigen's solve.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>

namespace mbfe::runtime {

/// x = A^-1 b for the factor `f` of A (n x n; b and x n entries, distinct).
/// `work` is resized to n once and reused.
namespace detail {

/// The factor's D without a copy: a pointer to the protected member taken
/// through a derived class, the one access C++ allows from outside.
template <typename Factor>
struct LdltDiagonalAccess : Factor {
  static const Eigen::VectorXd& of(const Factor& f) { return f.*(&LdltDiagonalAccess::m_diag); }
};

template <typename Factor>
const Eigen::VectorXd& ldlt_diagonal(const Factor& f) {
  return LdltDiagonalAccess<Factor>::of(f);
}

}  // namespace detail

template <typename Factor>
void solve_ldlt(const Factor& f, const Eigen::Ref<const Eigen::VectorXd>& b, Eigen::Ref<Eigen::VectorXd> x,
                Eigen::VectorXd& work) {
  const Eigen::Index n = b.size();
  if (work.size() != n) work.resize(n);
  // Written as loops: Eigen's permutation and diagonal products may evaluate
  // into a temporary; the coefficients are the same (P b)_{p(i)} = b_i and
  // (D^-1 w)_i = (1 / d_i) w_i.
  const auto& p = f.permutationP().indices();
  if (p.size() > 0) {
    for (Eigen::Index i = 0; i < n; ++i) work[p[i]] = b[i];
  } else {
    work = b;
  }
  f.matrixL().solveInPlace(work);
  const Eigen::VectorXd& d = detail::ldlt_diagonal(f);
  for (Eigen::Index i = 0; i < n; ++i) work[i] = (1.0 / d[i]) * work[i];
  f.matrixU().solveInPlace(work);
  const auto& pinv = f.permutationPinv().indices();
  if (pinv.size() > 0) {
    for (Eigen::Index i = 0; i < n; ++i) x[pinv[i]] = work[i];
  } else {
    x = work;
  }
}

}  // namespace mbfe::runtime
