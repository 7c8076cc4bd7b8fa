#include "runtime/linalg/modal_block_solver.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace mbfe::runtime {

namespace {

// The capacity matrix I + E_RS (A^-1)_SR, equilibrated, is taken as singular
// below this reciprocal condition number (Eigen's 1-norm estimate; a margin
// of ~1e3 ulps).
constexpr double kSingularCapacityRcond = 1e-13;

}  // namespace


void ModalBlockSolver::index(std::vector<int> members, Coupled& out) const {
  std::sort(members.begin(), members.end());
  members.erase(std::unique(members.begin(), members.end()), members.end());
  out.list = std::move(members);
  out.pos.assign(size_, -1);
  out.in_block.assign(blocks_.size(), {});
  out.first.assign(blocks_.size(), -1);
  for (std::size_t i = 0; i < out.list.size(); ++i) {
    const int g = out.list[i];
    out.pos[g] = static_cast<int>(i);
    const int k = block_of_[g];
    if (k < 0) continue;
    if (out.in_block[k].empty()) out.first[k] = static_cast<int>(i);
    out.in_block[k].push_back(g - blocks_[k].row);
  }
}

void ModalBlockSolver::factorize(int size, const std::vector<Eigen::Triplet<double>>& entries,
                                 std::vector<ModalBlock> blocks) {
  size_ = size;
  blocks_ = std::move(blocks);
  block_of_.assign(size, -1);
  for (std::size_t k = 0; k < blocks_.size(); ++k) {
    const ModalBlock& b = blocks_[k];
    const int nk = static_cast<int>(b.phi->rows());
    if (b.row < 0 || b.row + nk > size || b.base_factor->rows() != nk || b.d.size() != b.phi->cols() ||
        (b.base_modal != nullptr && b.base_modal->size() != b.phi->cols()))
      throw std::invalid_argument("modal block " + std::to_string(k) + ": rows, Phi, b and d do not fit");
    for (int i = b.row; i < b.row + nk; ++i) {
      if (block_of_[i] >= 0) throw std::invalid_argument("modal blocks overlap at row " + std::to_string(i));
      block_of_[i] = static_cast<int>(k);
    }
  }
  rest_index_.assign(size, -1);
  rest_global_.clear();
  for (int i = 0; i < size; ++i)
    if (block_of_[i] < 0) {
      rest_index_[i] = static_cast<int>(rest_global_.size());
      rest_global_.push_back(i);
    }
  // The rest's own entries, and the couplings E: every entry touching a block.
  std::vector<Eigen::Triplet<double>> rest, couplings;
  std::vector<int> rows, cols;
  for (const Eigen::Triplet<double>& e : entries) {
    if (block_of_[e.row()] < 0 && block_of_[e.col()] < 0) {
      rest.emplace_back(rest_index_[e.row()], rest_index_[e.col()], e.value());
    } else {
      couplings.push_back(e);
      rows.push_back(e.row());
      cols.push_back(e.col());
    }
  }
  index(std::move(rows), rows_);
  index(std::move(cols), cols_);
  const int r = static_cast<int>(rows_.list.size()), s = static_cast<int>(cols_.list.size());
  coupling_.setZero(r, s);
  for (const Eigen::Triplet<double>& e : couplings) coupling_(rows_.pos[e.row()], cols_.pos[e.col()]) += e.value();

  const int n_rest = static_cast<int>(rest_global_.size());
  if (n_rest > 0) {
    rest_.resize(n_rest, n_rest);
    rest_.setFromTriplets(rest.begin(), rest.end());
    rest_lu_.analyzePattern(rest_);
    rest_lu_.factorize(rest_);
    if (rest_lu_.info() != Eigen::Success)
      throw std::runtime_error("the Newton matrix is singular outside its low-rank beams (" +
                               rest_lu_.lastErrorMessage() + ")");
  }
  weights_.clear();
  for (std::size_t k = 0; k < blocks_.size(); ++k) {
    const ModalBlock& b = blocks_[k];
    const Eigen::ArrayXd base = b.base_modal != nullptr ? Eigen::ArrayXd(b.alpha * b.base_modal->array())
                                                        : Eigen::ArrayXd::Constant(b.d.size(), b.alpha);
    const Eigen::ArrayXd sum = base + b.d.array();
    if (!(b.alpha > 0.0) || !(base > 0.0).all() || !(sum.abs() > 0.0).all()) {
      std::ostringstream os;
      os << "the Newton matrix is singular in a low-rank beam (alpha " << b.alpha << ", smallest |alpha b + d| "
         << (sum.size() > 0 ? sum.abs().minCoeff() : 0.0) << ")";
      throw std::runtime_error(os.str());
    }
    weights_.push_back((sum.inverse() - base.inverse()).matrix());
  }

  // G = (A^-1)_SR, block by block (A is block diagonal).
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(s, r);
  for (int j = 0; j < r; ++j) {
    const int col = rows_.list[j];
    if (block_of_[col] >= 0) continue;
    rest_b_.setZero(n_rest);
    rest_b_[rest_index_[col]] = 1.0;
    rest_x_ = rest_lu_.solve(rest_b_);
    for (int i = 0; i < s; ++i)
      if (block_of_[cols_.list[i]] < 0) g(i, j) = rest_x_[rest_index_[cols_.list[i]]];
  }
  for (std::size_t k = 0; k < blocks_.size(); ++k) {
    const ModalBlock& b = blocks_[k];
    const std::vector<int>& in_r = rows_.in_block[k];
    const std::vector<int>& in_s = cols_.in_block[k];
    if (in_r.empty() || in_s.empty()) continue;
    const int nr = static_cast<int>(in_r.size()), ns = static_cast<int>(in_s.size());
    Eigen::MatrixXd phi_r(nr, b.phi->cols()), phi_s(ns, b.phi->cols());
    for (int i = 0; i < nr; ++i) phi_r.row(i) = b.phi->row(in_r[i]);
    for (int i = 0; i < ns; ++i) phi_s.row(i) = b.phi->row(in_s[i]);
    auto gk = g.block(cols_.first[k], rows_.first[k], ns, nr);
    gk.noalias() = phi_s * weights_[k].asDiagonal() * phi_r.transpose();
    for (int j = 0; j < nr; ++j) {
      block_b_.setZero(b.phi->rows());
      block_b_[in_r[j]] = 1.0;
      block_x_ = b.base_factor->solve(block_b_);
      for (int i = 0; i < ns; ++i) gk(i, j) += block_x_[in_s[i]] / b.alpha;
    }
  }
  Eigen::MatrixXd capacity = coupling_ * g;
  capacity.diagonal().array() += 1.0;
  // Equilibrated (rows, then columns, to unit largest entry): under the
  // static start's weight a stiff coupling's row is ~1e13 times a plain one,
  // which the condition estimate would take for singularity.
  row_scale_ = capacity.rowwise().lpNorm<Eigen::Infinity>().cwiseMax(1e-300).cwiseInverse();
  capacity = row_scale_.asDiagonal() * capacity;
  col_scale_ = capacity.colwise().lpNorm<Eigen::Infinity>().transpose().cwiseMax(1e-300).cwiseInverse();
  capacity = capacity * col_scale_.asDiagonal();
  capacity_lu_.compute(capacity);
  const double rcond = r > 0 ? capacity_lu_.rcond() : 1.0;
  if (!(rcond >= kSingularCapacityRcond)) {
    std::ostringstream os;
    os << "the Newton matrix is singular in its couplings (contacts, links: reciprocal condition number " << rcond
       << ")";
    throw std::runtime_error(os.str());
  }
}

void ModalBlockSolver::apply_block_inverse(const Eigen::VectorXd& b, Eigen::VectorXd& x, bool sparse_at_rows) {
  x.resize(size_);
  if (!rest_global_.empty()) {
    rest_b_.resize(static_cast<Eigen::Index>(rest_global_.size()));
    for (std::size_t i = 0; i < rest_global_.size(); ++i) rest_b_[i] = b[rest_global_[i]];
    rest_x_ = rest_lu_.solve(rest_b_);
    for (std::size_t i = 0; i < rest_global_.size(); ++i) x[rest_global_[i]] = rest_x_[i];
  }
  for (std::size_t k = 0; k < blocks_.size(); ++k) {
    const ModalBlock& blk = blocks_[k];
    const Eigen::Index nk = blk.phi->rows();
    block_b_ = b.segment(blk.row, nk);
    if (sparse_at_rows) {
      modal_.setZero(blk.phi->cols());
      for (int i : rows_.in_block[k]) modal_.noalias() += block_b_[i] * blk.phi->row(i).transpose();
    } else {
      modal_.noalias() = blk.phi->transpose() * block_b_;
    }
    modal_ = weights_[k].cwiseProduct(modal_);
    block_x_ = blk.base_factor->solve(block_b_);
    block_x_ /= blk.alpha;
    block_x_.noalias() += *blk.phi * modal_;
    x.segment(blk.row, nk) = block_x_;
  }
}

void ModalBlockSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (b.size() != size_)
    throw std::invalid_argument("ModalBlockSolver: b has " + std::to_string(b.size()) + " entries, expected " +
                                std::to_string(size_));
  apply_block_inverse(b, y_, false);
  const int r = static_cast<int>(rows_.list.size()), s = static_cast<int>(cols_.list.size());
  if (r == 0) {
    x = y_;
    return;
  }
  modal_.resize(s);
  for (int i = 0; i < s; ++i) modal_[i] = y_[cols_.list[i]];
  z_.noalias() = coupling_ * modal_;
  z_ = row_scale_.cwiseProduct(z_);
  modal_ = capacity_lu_.solve(z_);
  z_ = col_scale_.cwiseProduct(modal_);
  v_.setZero(size_);
  for (int i = 0; i < r; ++i) v_[rows_.list[i]] = z_[i];
  apply_block_inverse(v_, x, true);
  x = y_ - x;
}

}  // namespace mbfe::runtime
