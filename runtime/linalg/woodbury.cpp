#include "runtime/linalg/woodbury.h"

#include <sstream>
#include <stdexcept>

namespace mbfe::runtime {

namespace {

// The capacity matrix I + D W^T A^-1 W is taken as singular below this
// reciprocal condition number (Eigen's 1-norm estimate; a margin of ~1e3 ulps).
constexpr double kSingularCapacityRcond = 1e-13;

}  // namespace

void WoodburyCorrection::factorize(Eigen::MatrixXd W, Eigen::VectorXd D, Eigen::MatrixXd Z,
                                   const std::vector<Block>& blocks, const std::string& what) {
  const Eigen::Index k = W.cols();
  if (D.size() != k || Z.rows() != W.rows() || Z.cols() != k)
    throw std::invalid_argument("Woodbury: W is " + std::to_string(W.rows()) + " x " + std::to_string(k) + ", D has " +
                                std::to_string(D.size()) + " entries, Z is " + std::to_string(Z.rows()) + " x " +
                                std::to_string(Z.cols()));
  W_ = std::move(W);
  D_ = std::move(D);
  Z_ = std::move(Z);
  if (k == 0) return;
  // W^T Z block by block: W is zero outside its blocks' rows (a dense product
  // would spend most of its time on those zeros in a model of several beams).
  Eigen::MatrixXd capacity = Eigen::MatrixXd::Zero(k, k);
  for (const Block& b : blocks)
    capacity.middleRows(b.col, b.cols).noalias() +=
        W_.block(b.row, b.col, b.rows, b.cols).transpose() * Z_.middleRows(b.row, b.rows);
  capacity = D_.asDiagonal() * capacity;
  capacity.diagonal().array() += 1.0;
  capacity_lu_.compute(capacity);
  const double rcond = capacity_lu_.rcond();
  if (!(rcond >= kSingularCapacityRcond)) {
    std::ostringstream os;
    os << what << " is singular in its low-rank part (the adjusted modes, by Woodbury: reciprocal condition number "
       << rcond << ")";
    throw std::runtime_error(os.str());
  }
}

void WoodburyCorrection::correct(Eigen::VectorXd& x) {
  if (W_.cols() == 0) return;
  s_.noalias() = W_.transpose() * x;
  s_ = D_.cwiseProduct(s_);
  x.noalias() -= Z_ * capacity_lu_.solve(s_);
}

}  // namespace mbfe::runtime
