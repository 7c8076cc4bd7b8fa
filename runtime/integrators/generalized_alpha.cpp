// Generalized-alpha (Chung-Hulbert) for M q'' + C q' + K q = P(t).
#include <cmath>

#include "runtime/integrators/steppers.h"

namespace mbfe::runtime {

namespace {

class GeneralizedAlpha final : public Stepper {
 public:
  GeneralizedAlpha(LinearSecondOrderSystem& sys, double rho_inf) : sys_(sys), n_(sys.dof()) {
    am_ = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0);
    af_ = rho_inf / (rho_inf + 1.0);
    gamma_ = 0.5 - am_ + af_;
    beta_ = 0.25 * (1.0 - am_ + af_) * (1.0 - am_ + af_);
    for (auto* v : {&a_, &p_, &r_, &tmp_, &mx_, &q_, &v_, &anew_}) v->resize(n_);
  }
  void reset(double t0, const Eigen::VectorXd& y0) override {
    q_ = y0.head(n_);
    v_ = y0.tail(n_);
    sys_.load(t0, p_);
    sys_.mult_c(v_, tmp_);
    r_ = p_ - tmp_;
    sys_.mult_k(q_, tmp_);
    r_ -= tmp_;
    sys_.solve_combination(1.0, 0.0, 0.0, r_, a_);
  }
  void step(double t, double h, Eigen::VectorXd& y) override {
    q_ = y.head(n_);
    v_ = y.tail(n_);
    sys_.load(t + (1.0 - af_) * h, p_);
    // r = P - am M a_n - C[v_n + (1-af) h (1-gamma) a_n] - K[q_n + (1-af)(h v_n + h^2 (1/2 - beta) a_n)]
    r_ = p_;
    sys_.mult_m(a_, mx_);
    r_ -= am_ * mx_;
    tmp_ = v_ + ((1.0 - af_) * h * (1.0 - gamma_)) * a_;
    sys_.mult_c(tmp_, mx_);
    r_ -= mx_;
    tmp_ = q_ + (1.0 - af_) * (h * v_ + (h * h * (0.5 - beta_)) * a_);
    sys_.mult_k(tmp_, mx_);
    r_ -= mx_;
    sys_.solve_combination(1.0 - am_, (1.0 - af_) * gamma_ * h, (1.0 - af_) * beta_ * h * h, r_, anew_);
    y.head(n_) = q_ + h * v_ + (h * h) * ((0.5 - beta_) * a_ + beta_ * anew_);
    y.tail(n_) = v_ + h * ((1.0 - gamma_) * a_ + gamma_ * anew_);
    a_.swap(anew_);
  }

 private:
  LinearSecondOrderSystem& sys_;
  int n_;
  double am_, af_, gamma_, beta_;
  Eigen::VectorXd a_, p_, r_, tmp_, mx_, q_, v_, anew_;
};

}  // namespace

std::unique_ptr<Stepper> make_generalized_alpha(LinearSecondOrderSystem& system, double rho_inf) {
  return std::make_unique<GeneralizedAlpha>(system, rho_inf);
}

}  // namespace mbfe::runtime
