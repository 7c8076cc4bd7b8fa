#include "runtime/simulation/linearised_step_solve.h"

#include <stdexcept>

namespace mbfe::runtime {

namespace {

// A pivot of the equilibrated system (every row and column scaled to a
// largest entry of 1) below this: a body held by nothing (singular).
constexpr double kSingularPivot = 1e-13;

}  // namespace

Eigen::VectorXd LinearisedStepSolve::equilibrated(const Eigen::MatrixXd& B, const Eigen::MatrixXd& E,
                                                  const Eigen::MatrixXd& G, const Eigen::VectorXd& slopes,
                                                  const Eigen::VectorXd& residual) const {
  const int nz = static_cast<int>(G.rows()), n = nr_ + nz;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n, n);
  J.topLeftCorner(nr_, nr_) = B;
  J.topRightCorner(nr_, nz) = E;
  J.bottomRightCorner(nz, nz).setIdentity();
  for (int e = 0; e < nz; ++e) {
    if (slopes[e] == 0.0) continue;
    J.block(nr_ + e, 0, 1, nr_) = -slopes[e] * E.col(e).transpose();
    J.block(nr_ + e, nr_, 1, nz) += slopes[e] * G.row(e);
  }
  Eigen::VectorXd row_scale(n), col_scale(n);
  for (int i = 0; i < n; ++i) {
    const double largest = J.row(i).cwiseAbs().maxCoeff();
    row_scale[i] = largest > 0.0 ? 1.0 / largest : 1.0;
  }
  J = row_scale.asDiagonal() * J;
  for (int i = 0; i < n; ++i) {
    const double largest = J.col(i).cwiseAbs().maxCoeff();
    col_scale[i] = largest > 0.0 ? 1.0 / largest : 1.0;
  }
  J = J * col_scale.asDiagonal();
  Eigen::PartialPivLU<Eigen::MatrixXd> lu(J);
  if (!(lu.matrixLU().diagonal().cwiseAbs().minCoeff() > kSingularPivot))
    throw std::runtime_error(
        "the linearised static equilibrium is singular: a body is held by nothing (no contact pressing, no spring)");
  return col_scale.cwiseProduct(lu.solve(-row_scale.cwiseProduct(residual)));
}

void LinearisedStepSolve::start_steps(const Eigen::MatrixXd& B) {
  if (nr_ > 0) b_lu_.compute(B);
  if (nr_ > 0 && !b_lu_.isInvertible())
    throw std::runtime_error("the linearised step is singular: the bodies' M, C, K give no regular step matrix");
  f_slopes_.resize(0);
}

Eigen::VectorXd LinearisedStepSolve::by_blocks(const Eigen::MatrixXd& E, const Eigen::MatrixXd& G,
                                               const Eigen::VectorXd& slopes, const Eigen::VectorXd& residual) {
  const int nz = static_cast<int>(G.rows()), na = nz - nf_, nu = nr_ + nf_;
  if (f_slopes_.size() != nf_ || f_slopes_ != slopes.head(nf_)) {
    f_slopes_ = slopes.head(nf_);
    Eigen::MatrixXd F = f_slopes_.asDiagonal() * G.topLeftCorner(nf_, nf_);
    F.diagonal().array() += 1.0;
    f_lu_.compute(F);
  }
  // A^-1 applied to the columns of `rhs` (rows: bodies, then fixed elements).
  const auto solve_a = [&](Eigen::MatrixXd rhs) {
    if (nr_ > 0) rhs.topRows(nr_) = b_lu_.solve(rhs.topRows(nr_));
    if (nf_ > 0) rhs.bottomRows(nf_) = f_lu_.solve(rhs.bottomRows(nf_));
    return rhs;
  };
  Eigen::VectorXd delta(nr_ + nz);
  const Eigen::MatrixXd v = solve_a(-residual.head(nu));
  if (na == 0) {
    delta = v;
    return delta;
  }
  // C: the contacts' columns of the (bodies, fixed elements) rows; D: the
  // contacts' rows of the (bodies, fixed elements) columns.
  Eigen::MatrixXd C(nu, na), D(na, nu), S(na, na);
  for (int a = 0; a < na; ++a) {
    const int e = nf_ + a;
    C.col(a).head(nr_) = E.col(e);
    C.col(a).tail(nf_) = f_slopes_.cwiseProduct(G.col(e).head(nf_));
    D.row(a).head(nr_) = -slopes[e] * E.col(e).transpose();
    D.row(a).tail(nf_) = slopes[e] * G.row(e).head(nf_);
    S.row(a) = slopes[e] * G.row(e).tail(na);
    S(a, a) += 1.0;
  }
  const Eigen::MatrixXd X = solve_a(C);
  S.noalias() -= D * X;
  const Eigen::FullPivLU<Eigen::MatrixXd> s_lu(S);
  if (!s_lu.isInvertible()) throw std::runtime_error("the linearised step is singular: a contact's system has no solution");
  const Eigen::VectorXd dz_c = s_lu.solve(-residual.tail(na) - D * v.col(0));
  delta.head(nu) = v.col(0) - X * dz_c;
  delta.tail(na) = dz_c;
  return delta;
}

}  // namespace mbfe::runtime
