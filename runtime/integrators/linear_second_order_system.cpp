#include "runtime/integrators/linear_second_order_system.h"

namespace mbfe::runtime {

void LinearSecondOrderSystem::rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) {
  const int n = dof();
  w1_.resize(n);
  load(t, w1_);
  w2_ = y.tail(n);
  mult_c(w2_, w3_);
  w1_ -= w3_;
  w2_ = y.head(n);
  mult_k(w2_, w3_);
  w1_ -= w3_;
  ydot.resize(2 * n);
  ydot.head(n) = y.tail(n);
  solve_combination(1.0, 0.0, 0.0, w1_, w3_);
  ydot.tail(n) = w3_;
}

void LinearSecondOrderSystem::solve_shifted(double, const Eigen::VectorXd&, double c, const Eigen::VectorXd& b,
                                            Eigen::VectorXd& x) {
  const int n = dof();
  w2_ = b.tail(n);
  mult_m(w2_, w1_);
  w2_ = b.head(n);
  mult_k(w2_, w3_);
  w1_ -= c * w3_;
  solve_combination(1.0, c, c * c, w1_, w3_);
  x.resize(2 * n);
  x.tail(n) = w3_;
  x.head(n) = b.head(n) + c * w3_;
}

}  // namespace mbfe::runtime
