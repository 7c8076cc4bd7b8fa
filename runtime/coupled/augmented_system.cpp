#include "runtime/coupled/augmented_system.h"

namespace mbfe::runtime {

AugmentedSystem::AugmentedSystem(std::shared_ptr<CoupledDynamics> dyn)
    : CoupledSystem(std::move(dyn)) {
  q_.resize(dyn_->n());
  qd_.resize(dyn_->n());
}

void AugmentedSystem::rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) {
  const int n = dyn_->n();
  if (y.size() != 2 * n) {
    throw std::invalid_argument("AugmentedSystem: y has " + std::to_string(y.size()) +
                                " entries, expected " + std::to_string(2 * n));
  }
  q_ = y.head(n);
  qd_ = y.tail(n);
  dyn_->evaluate(t, q_, qd_);
  dyn_->solve_augmented(t, qdd_, lambda_);
  ydot.resize(2 * n);
  ydot.head(n) = qd_;
  ydot.tail(n) = qdd_;
}

std::string AugmentedSystem::name(int i) const {
  const std::vector<std::string> names = dyn_->model().coordinate_names();
  const int n = dyn_->n();
  return i < n ? names[i] : names[i - n] + "_dot";
}

Eigen::VectorXd AugmentedSystem::initial_state(double, const Eigen::VectorXd& q,
                                               const Eigen::VectorXd& qd) {
  Eigen::VectorXd y(2 * dyn_->n());
  y << q, qd;
  return y;
}

void AugmentedSystem::full_state(double, const Eigen::VectorXd& y, Eigen::VectorXd& q,
                                 Eigen::VectorXd& qd) {
  q = y.head(dyn_->n());
  qd = y.tail(dyn_->n());
}

const ContactReport& AugmentedSystem::report(double t, const Eigen::VectorXd& y) {
  rhs(t, y, report_ydot_);
  ContactReport& r = report_;
  r.lambda = lambda_;
  r.qdd = qdd_;
  r.phi = dyn_->values().phi;
  r.phi_max = dyn_->phi_max(dyn_->values());
  r.s = dyn_->values().s;
  return r;
}

}  // namespace mbfe::runtime
