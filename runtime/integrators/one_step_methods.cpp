// Forward and backward Euler, the trapezoid rule, RK4 and the explicit
// midpoint rule (two-step, started by one forward-Euler step as the paper's
// Fig. 3).
#include "runtime/integrators/newton_stage.h"
#include "runtime/integrators/steppers.h"

namespace mbfe::runtime {

namespace {

class ForwardEuler final : public Stepper {
 public:
  explicit ForwardEuler(OdeSystem& sys) : sys_(sys), f_(sys.size()) {}
  void reset(double, const Eigen::VectorXd&) override {}
  void step(double t, double h, Eigen::VectorXd& y) override {
    sys_.rhs(t, y, f_);
    y.noalias() += h * f_;
  }

 private:
  OdeSystem& sys_;
  Eigen::VectorXd f_;
};

class Rk4 final : public Stepper {
 public:
  explicit Rk4(OdeSystem& sys)
      : sys_(sys), k1_(sys.size()), k2_(sys.size()), k3_(sys.size()), k4_(sys.size()), tmp_(sys.size()) {}
  void reset(double, const Eigen::VectorXd&) override {}
  void step(double t, double h, Eigen::VectorXd& y) override {
    sys_.rhs(t, y, k1_);
    tmp_ = y + (0.5 * h) * k1_;
    sys_.rhs(t + 0.5 * h, tmp_, k2_);
    tmp_ = y + (0.5 * h) * k2_;
    sys_.rhs(t + 0.5 * h, tmp_, k3_);
    tmp_ = y + h * k3_;
    sys_.rhs(t + h, tmp_, k4_);
    y += (h / 6.0) * (k1_ + 2.0 * k2_ + 2.0 * k3_ + k4_);
  }

 private:
  OdeSystem& sys_;
  Eigen::VectorXd k1_, k2_, k3_, k4_, tmp_;
};

class BackwardEuler final : public Stepper {
 public:
  explicit BackwardEuler(OdeSystem& sys) : sys_(sys), linear_(is_linear(sys)), r_(sys.size()) {
    w_.resize(sys.size());
  }
  void reset(double, const Eigen::VectorXd&) override {}
  void step(double t, double h, Eigen::VectorXd& y) override {
    r_ = y;
    newton_solve(sys_, linear_, t + h, h, r_, y, w_);
  }

 private:
  OdeSystem& sys_;
  bool linear_;
  Eigen::VectorXd r_;
  NewtonWork w_;
};

class Trapezoid final : public Stepper {
 public:
  explicit Trapezoid(OdeSystem& sys) : sys_(sys), linear_(is_linear(sys)), r_(sys.size()), f_(sys.size()) {
    w_.resize(sys.size());
  }
  void reset(double, const Eigen::VectorXd&) override {}
  void step(double t, double h, Eigen::VectorXd& y) override {
    sys_.rhs(t, y, f_);
    r_ = y + (0.5 * h) * f_;
    newton_solve(sys_, linear_, t + h, 0.5 * h, r_, y, w_);
  }

 private:
  OdeSystem& sys_;
  bool linear_;
  Eigen::VectorXd r_, f_;
  NewtonWork w_;
};

/// y_n = y_{n-2} + 2 h f_{n-1}; the first step is forward Euler.
class ExplicitMidpoint final : public Stepper {
 public:
  explicit ExplicitMidpoint(OdeSystem& sys) : sys_(sys), prev_(sys.size()), f_(sys.size()) {}
  void reset(double, const Eigen::VectorXd&) override { started_ = false; }
  void step(double t, double h, Eigen::VectorXd& y) override {
    sys_.rhs(t, y, f_);
    if (!started_) {
      prev_ = y;
      y.noalias() += h * f_;
      started_ = true;
      return;
    }
    // new = prev + 2 h f; then prev <- old y.
    prev_.noalias() += (2.0 * h) * f_;
    prev_.swap(y);
  }

 private:
  OdeSystem& sys_;
  Eigen::VectorXd prev_, f_;
  bool started_ = false;
};

}  // namespace

std::unique_ptr<Stepper> make_forward_euler(OdeSystem& system) { return std::make_unique<ForwardEuler>(system); }
std::unique_ptr<Stepper> make_rk4(OdeSystem& system) { return std::make_unique<Rk4>(system); }
std::unique_ptr<Stepper> make_backward_euler(OdeSystem& system) { return std::make_unique<BackwardEuler>(system); }
std::unique_ptr<Stepper> make_trapezoid(OdeSystem& system) { return std::make_unique<Trapezoid>(system); }
std::unique_ptr<Stepper> make_explicit_midpoint(OdeSystem& system) {
  return std::make_unique<ExplicitMidpoint>(system);
}

}  // namespace mbfe::runtime
