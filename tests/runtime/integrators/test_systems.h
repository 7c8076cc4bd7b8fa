// Small systems with known solutions for the integrator tests.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <complex>

#include "runtime/integrators/integrator.h"

namespace mbfe::testing {

/// y' = -y^2, y(0) = 1: y = 1 / (1 + t). Nonlinear: implicit methods go
/// through Newton with the default finite-difference Jacobian.
class Riccati final : public runtime::OdeSystem {
 public:
  int size() const override { return 1; }
  void rhs(double, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) override {
    ydot.resize(1);
    ydot[0] = -y[0] * y[0];
  }
  static double exact(double t) { return 1.0 / (1.0 + t); }
};

/// y' = lambda y for complex lambda, as a real 2-vector [Re y, Im y].
class Scalar final : public runtime::OdeSystem {
 public:
  explicit Scalar(std::complex<double> lambda) : l_(lambda) {}
  int size() const override { return 2; }
  void rhs(double, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) override {
    ydot.resize(2);
    ydot[0] = l_.real() * y[0] - l_.imag() * y[1];
    ydot[1] = l_.imag() * y[0] + l_.real() * y[1];
  }

 private:
  std::complex<double> l_;
};

/// One damped oscillator q'' + 2 zeta w q' + w^2 q = p (constant p), from rest:
/// q = p / w^2 (1 - e^{-zeta w t} (cos wd t + zeta w / wd sin wd t)).
class Oscillator final : public runtime::LinearSecondOrderSystem {
 public:
  Oscillator(double w, double zeta, double p) : w_(w), z_(zeta), p_(p) {}
  int dof() const override { return 1; }
  void load(double, Eigen::VectorXd& out) override { out.setConstant(1, p_); }
  void mult_m(const Eigen::VectorXd& x, Eigen::VectorXd& out) override { out = x; }
  void mult_c(const Eigen::VectorXd& x, Eigen::VectorXd& out) override { out = 2.0 * z_ * w_ * x; }
  void mult_k(const Eigen::VectorXd& x, Eigen::VectorXd& out) override { out = w_ * w_ * x; }
  void solve_combination(double a, double b, double c, const Eigen::VectorXd& r, Eigen::VectorXd& x) override {
    x = r / (a + b * 2.0 * z_ * w_ + c * w_ * w_);
  }
  double exact(double t) const {
    const double wd = w_ * std::sqrt(1.0 - z_ * z_);
    return p_ / (w_ * w_) * (1.0 - std::exp(-z_ * w_ * t) * (std::cos(wd * t) + z_ * w_ / wd * std::sin(wd * t)));
  }

 private:
  double w_, z_, p_;
};

}  // namespace mbfe::testing
