#include "runtime/coupled/truncated_tangents.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "runtime/structure/low_rank_structure.h"

namespace mbfe::runtime {

namespace {

// A shifted matrix whose reciprocal condition is below this is singular (sigma
// an eigenvalue: a zero mode for sigma = 0), as the nodal tangents' LU says.
constexpr double kSingularRcond = 1e-14;

// Where each free coordinate's row of T lives: a rigid one is its own unit
// row; a beam DOF is row `local` of structure `owner`'s Phi_L, whose columns
// start at reduced column `first[owner]`.
struct Basis {
  int rigid = 0, size = 0;
  std::vector<const LowRankStructure*> structures;
  std::vector<int> first, owner, local;  // owner, local: per beam DOF

  // s += x * (row i of T).
  void add_row(int i, double x, Eigen::VectorXd& s, std::vector<bool>& touched) const {
    if (i < rigid) {
      s[i] += x;
      touched[0] = true;
      return;
    }
    const int k = owner[static_cast<std::size_t>(i - rigid)];
    const LowRankStructure& st = *structures[static_cast<std::size_t>(k)];
    s.segment(first[static_cast<std::size_t>(k)], st.rank()) +=
        x * st.phi().row(local[static_cast<std::size_t>(i - rigid)]).transpose();
    touched[static_cast<std::size_t>(k) + 1] = true;
  }
};

// out = T^T X T, column by column of X: s = T^T X e_j, then out += s (row j of T).
void project(const Basis& basis, const Eigen::SparseMatrix<double>& x, Eigen::MatrixXd& out) {
  out.setZero(basis.size, basis.size);
  Eigen::VectorXd s = Eigen::VectorXd::Zero(basis.size);
  std::vector<bool> touched(basis.structures.size() + 1);
  auto block = [&](std::size_t b, int& start, int& length) {
    start = b == 0 ? 0 : basis.first[b - 1];
    length = b == 0 ? basis.rigid : basis.structures[b - 1]->rank();
  };
  for (int j = 0; j < x.outerSize(); ++j) {
    std::fill(touched.begin(), touched.end(), false);
    bool any = false;
    for (Eigen::SparseMatrix<double>::InnerIterator it(x, j); it; ++it) {
      basis.add_row(static_cast<int>(it.row()), it.value(), s, touched);
      any = true;
    }
    if (!any) continue;
    for (std::size_t b = 0; b < touched.size(); ++b) {
      if (!touched[b]) continue;
      int start, length;
      block(b, start, length);
      const auto sb = s.segment(start, length);
      if (j < basis.rigid) {
        out.col(j).segment(start, length) += sb;
      } else {
        const int k = basis.owner[static_cast<std::size_t>(j - basis.rigid)];
        const LowRankStructure& st = *basis.structures[static_cast<std::size_t>(k)];
        const auto row = st.phi().row(basis.local[static_cast<std::size_t>(j - basis.rigid)]);
        out.block(start, basis.first[static_cast<std::size_t>(k)], length, st.rank()).noalias() += sb * row;
      }
      s.segment(start, length).setZero();
    }
  }
}

}  // namespace

TruncatedTangents::TruncatedTangents(const CoupledTangents& tangents) : num_driven_(tangents.num_driven()) {
  const CoupledModel& model = tangents.model();
  Basis basis;
  basis.rigid = rigid_ = tangents.rigid_size();
  const int beam_dofs = tangents.size() - rigid_;
  basis.owner.assign(static_cast<std::size_t>(beam_dofs), -1);
  basis.local.assign(static_cast<std::size_t>(beam_dofs), -1);
  int r = rigid_;
  for (const auto& st : model.structures()) {
    if (!st->truncated())
      throw std::invalid_argument("structure '" + st->name() +
                                  "' is not truncated: the projection on kept modes is the linearisation of "
                                  "truncated beams only");
    const int k = static_cast<int>(basis.structures.size());
    basis.structures.push_back(st.get());
    basis.first.push_back(r);
    r += st->rank();
    int row = 0;
    for (const LowRankStructure::Range& range : st->ranges())
      for (int i = 0; i < range.size; ++i) {
        basis.owner[static_cast<std::size_t>(range.offset + i)] = k;
        basis.local[static_cast<std::size_t>(range.offset + i)] = row++;
      }
  }
  for (int i = 0; i < beam_dofs; ++i)
    if (basis.owner[static_cast<std::size_t>(i)] < 0)
      throw std::invalid_argument("a beam outside any truncated structure (coordinate " + std::to_string(i) +
                                  " of the beams): the projection on kept modes needs every beam truncated");
  basis.size = r;
  project(basis, tangents.mass_without_structures(), m_);
  project(basis, tangents.damping_without_structures(), c_);
  project(basis, tangents.stiffness_without_structures(), k_);
  // Each structure's own terms, diagonal on its kept modes.
  modal_mass_.resize(r - rigid_);
  for (std::size_t k = 0; k < basis.structures.size(); ++k) {
    const LowRankStructure& st = *basis.structures[k];
    const Eigen::VectorXd& b = st.base_modal();
    for (int j = 0; j < st.rank(); ++j) {
      const int i = basis.first[k] + j;
      m_(i, i) += st.mass().mu * b[j] + st.mass().d[j];
      c_(i, i) += st.damping().mu * b[j] + st.damping().d[j];
      k_(i, i) += st.stiffness().mu * b[j] + st.stiffness().d[j];
    }
  }
  // No force element has mass: M_r is the rigid block and the modal masses.
  if (!m_.topRightCorner(rigid_, r - rigid_).isZero(0.0) ||
      !m_.bottomRightCorner(r - rigid_, r - rigid_).isDiagonal(0.0))
    throw std::logic_error("TruncatedTangents: the reduced mass matrix is not block diagonal");
  rigid_mass_lu_.compute(m_.topLeftCorner(rigid_, rigid_));
  modal_mass_ = m_.diagonal().tail(r - rigid_);
}

void TruncatedTangents::solve_mass(const Eigen::VectorXd& r, Eigen::VectorXd& x) const {
  x.resize(r.size());
  if (rigid_ > 0) x.head(rigid_) = rigid_mass_lu_.solve(r.head(rigid_));
  x.tail(r.size() - rigid_) = r.tail(r.size() - rigid_).cwiseQuotient(modal_mass_);
}

void TruncatedTangents::apply_state_matrix(const double* in, double* out) const {
  const int n = size();
  const Eigen::Map<const Eigen::VectorXd> z(in, n), zd(in + n, n);
  rhs_.noalias() = k_ * z;
  rhs_.noalias() += c_ * zd;
  solve_mass(rhs_, sol_);
  Eigen::Map<Eigen::VectorXd>(out, n) = zd;
  Eigen::Map<Eigen::VectorXd>(out + n, n) = -sol_;
}

void TruncatedTangents::factorize_shifted(double sigma) {
  factored_ = false;
  sigma_ = sigma;
  const Eigen::MatrixXd s = sigma * sigma * m_ + sigma * c_ + k_;
  shifted_lu_.compute(s);
  if (!(shifted_lu_.rcond() >= kSingularRcond))
    throw std::runtime_error("the truncated model's shifted matrix sigma^2 M + sigma C + K at sigma = " +
                             std::to_string(sigma) + " is singular");
  factored_ = true;
}

void TruncatedTangents::solve_shifted(const double* in, double* out) const {
  if (!factored_) throw std::logic_error("TruncatedTangents::solve_shifted before factorize_shifted");
  // As the nodal tangents: x2 = b1 + sigma x1,
  // (sigma^2 M + sigma C + K) x1 = -(M (b2 + sigma b1) + C b1).
  const int n = size();
  const Eigen::Map<const Eigen::VectorXd> b1(in, n), b2(in + n, n);
  tmp_ = b2 + sigma_ * b1;
  rhs_.noalias() = m_ * tmp_;
  rhs_.noalias() += c_ * b1;
  sol_ = shifted_lu_.solve(-rhs_);
  Eigen::Map<Eigen::VectorXd>(out, n) = sol_;
  Eigen::Map<Eigen::VectorXd>(out + n, n) = b1 + sigma_ * sol_;
}

Eigen::MatrixXd TruncatedTangents::dense_state_matrix() const {
  const int n = size();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  a.topRightCorner(n, n).setIdentity();
  Eigen::VectorXd x;
  for (int j = 0; j < n; ++j) {
    solve_mass(k_.col(j), x);
    a.col(j).tail(n) = -x;
    solve_mass(c_.col(j), x);
    a.col(n + j).tail(n) = -x;
  }
  return a;
}

}  // namespace mbfe::runtime
