// A general linear multistep method sum alpha_i y_{n+i} = h sum beta_i f_{n+i}
// (ab2 and bdf2 are presets), started by RK4 steps.
#include "runtime/integrators/newton_stage.h"
#include "runtime/integrators/steppers.h"

namespace mbfe::runtime {

namespace {

class LinearMultistep final : public Stepper {
 public:
  LinearMultistep(OdeSystem& sys, const LmmCoefficients& c)
      : sys_(sys), c_(c), k_(c.steps()), linear_(is_linear(sys)), starter_(make_rk4(sys)), rhs_(sys.size()) {
    ys_.assign(k_, Eigen::VectorXd(sys.size()));
    fs_.assign(k_, Eigen::VectorXd(sys.size()));
    w_.resize(sys.size());
  }
  void reset(double, const Eigen::VectorXd&) override { filled_ = 0; }
  void step(double t, double h, Eigen::VectorXd& y) override {
    // ys_[(head_ + i) % k_] = y_{n+i}, i = 0..k-1 (oldest first).
    if (filled_ < k_) {
      const int slot = filled_;
      ys_[slot] = y;
      sys_.rhs(t, y, fs_[slot]);
      ++filled_;
      head_ = 0;
      if (filled_ < k_) {
        starter_->step(t, h, y);
        return;
      }
    } else {
      // y (the newest value) was produced by the previous call; shift it in.
      ys_[head_] = y;
      sys_.rhs(t, y, fs_[head_]);
      head_ = (head_ + 1) % k_;
    }
    rhs_.setZero();
    for (int i = 0; i < k_; ++i) {
      const int slot = (head_ + i) % k_;
      rhs_ += (h * c_.beta[i]) * fs_[slot] - c_.alpha[i] * ys_[slot];
    }
    const double ak = c_.alpha[k_];
    rhs_ /= ak;
    if (c_.explicit_method()) {
      y = rhs_;
    } else {
      // y currently holds y_{n+k-1}: the predictor.
      newton_solve(sys_, linear_, t + h, h * c_.beta[k_] / ak, rhs_, y, w_);
    }
  }

 private:
  OdeSystem& sys_;
  LmmCoefficients c_;
  int k_;
  bool linear_;
  std::unique_ptr<Stepper> starter_;  // RK4 for the first k - 1 steps
  std::vector<Eigen::VectorXd> ys_, fs_;
  Eigen::VectorXd rhs_;
  NewtonWork w_;
  int filled_ = 0;
  int head_ = 0;
};

}  // namespace

std::unique_ptr<Stepper> make_linear_multistep(OdeSystem& system, const LmmCoefficients& c) {
  return std::make_unique<LinearMultistep>(system, c);
}

}  // namespace mbfe::runtime
