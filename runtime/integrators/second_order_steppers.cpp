// Backward Euler, the trapezoid rule, BDF2 and generalized-alpha on a
// SecondOrderSystem (second_order_system.h), with a modified Newton iteration:
// the iteration matrix is kept across steps and formed again only when the
// step size changes or the iteration slows (docs/implicit-integration.md).
//
// Each method writes q_{n+1} = q_pred + c_q a_{n+1}, q'_{n+1} = v_pred + c_v a_{n+1}:
//   backward Euler  q' = v_n + h a,           q = q_n + h q'
//   trapezoid       q' = v_n + h/2 (a_n + a), q = q_n + h/2 (v_n + q')
//   BDF2            q' = (4 v_n - v_{n-1})/3 + 2h/3 a, q = (4 q_n - q_{n-1})/3 + 2h/3 q'
//                   (the first step is a trapezoid step)
//   generalized-alpha (Arnold and Bruls, 2007): the equations hold at t_{n+1};
//                   an acceleration-like x with (1 - am) x_{n+1} + am x_n =
//                   (1 - af) a_{n+1} + af a_n drives Newmark's formulas
//                   q = q_n + h v_n + h^2 ((1/2 - beta) x_n + beta x_{n+1}),
//                   q' = v_n + h ((1 - gamma) x_n + gamma x_{n+1}).
// The first three are the first-order methods of the same names applied to
// y = [q; q'], written in the form that needs no first-order Jacobian.
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "runtime/integrators/second_order_steppers.h"

namespace mbfe::runtime {

namespace {

// Newton converged when the position correction c_q |da| is below this
// fraction of (1 + |q|): far below any step's truncation error, well above
// the round-off of the residuals.
constexpr double kNewtonTol = 1e-10;
constexpr int kMaxIterations = 12;
// A correction that shrinks by less than this factor per iteration means the
// kept matrix has gone stale: form it again at the current iterate.
constexpr double kSlowContraction = 0.3;
constexpr double kFirstContraction = 0.6;
// More iterations than this in a step with a kept matrix: refresh it for the
// next step, before convergence fails outright.
constexpr int kRefreshAfterIterations = 4;
// Round-off floor of the rates' correction (see iterate()): this many eps of
// (c_v / c_q) |q|, measured at 6x on the paper platform at 2.5e-6 s.
constexpr double kRoundOffFloor = 100.0 * 2.220446049250313e-16;
// Contractions up to this are estimated well enough by two corrections to
// stop one iteration early.
constexpr double kTrustedContraction = 0.1;
// A slow contraction calls for a new matrix only while the correction is
// this many tolerances or more.
constexpr double kStaleAbove = 100.0;
// Relative change of c_q below which the step counts as unchanged.
constexpr double kSameStep = 1e-6;

class SecondOrderStepper final : public Stepper {
 public:
  SecondOrderStepper(OdeSystem& ode, SecondOrderSystem& sys, SecondOrderMethod method, double rho_inf)
      : sys_(sys), method_(method), n_(sys.dof()), m_(sys.num_multipliers()) {
    if (ode.size() != 2 * n_) throw std::invalid_argument("second-order stepper: y must be [q; q']");
    am_ = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0);
    af_ = rho_inf / (rho_inf + 1.0);
    gamma_ = 0.5 - am_ + af_;
    beta_ = 0.25 * (gamma_ + 0.5) * (gamma_ + 0.5);
    for (auto* v : {&q_, &v_, &a_, &x_, &q_prev_, &v_prev_, &q_pred_, &v_pred_, &qn_, &vn_, &an_, &r_, &da_})
      v->resize(n_);
    for (auto* v : {&lambda_, &c_, &dl_, &lambda_n_}) v->resize(m_);
  }

  void reset(double t0, const Eigen::VectorXd& y0) override {
    q_ = y0.head(n_);
    v_ = y0.tail(n_);
    sys_.accelerations(t0, q_, v_, a_, lambda_);
    x_ = a_;
    steps_ = 0;
    factored_cq_ = 0.0;
  }

  void step(double t, double h, Eigen::VectorXd& y) override {
    qn_ = y.head(n_);
    vn_ = y.tail(n_);
    an_ = a_;
    lambda_n_ = lambda_;
    double c_q = 0.0, c_v = 0.0;
    predict(h, c_q, c_v);
    // t0 + k h differs from step to step in its last bits: only a real
    // change of the step (the last, shortened one) calls for a new matrix.
    if (!(std::abs(c_q - factored_cq_) <= kSameStep * c_q)) refresh_ = true;
    const double t1 = t + h;
    if (!iterate(t1, c_q, c_v)) {
      // The kept matrix may be too far from this state: start over with a fresh one.
      a_ = an_;
      lambda_ = lambda_n_;
      refresh_ = true;
      if (!iterate(t1, c_q, c_v, /*full_newton=*/true)) {
        std::ostringstream os;
        os << "implicit step at t = " << t1 << " s: Newton did not converge in " << kMaxIterations
           << " iterations, with the iteration matrix formed at every iteration (step " << h << " s)";
        throw std::runtime_error(os.str());
      }
    }
    // Accept: history for the next step.
    if (method_ == SecondOrderMethod::kGeneralizedAlpha) x_ = (af_ * an_ - am_ * x_ + (1.0 - af_) * a_) / (1.0 - am_);
    q_prev_ = qn_;
    v_prev_ = vn_;
    y.head(n_) = q_;
    y.tail(n_) = v_;
    ++steps_;
    ++stats_.steps;
  }

  NewtonStatistics newton_statistics() const override { return stats_; }

 private:
  void predict(double h, double& c_q, double& c_v) {
    SecondOrderMethod m = method_;
    if (m == SecondOrderMethod::kBdf2 && steps_ == 0) m = SecondOrderMethod::kTrapezoid;
    switch (m) {
      case SecondOrderMethod::kBackwardEuler:
        v_pred_ = vn_;
        c_v = h;
        q_pred_ = qn_ + h * vn_;
        c_q = h * h;
        break;
      case SecondOrderMethod::kTrapezoid:
        v_pred_ = vn_ + (0.5 * h) * an_;
        c_v = 0.5 * h;
        q_pred_ = qn_ + h * vn_ + (0.25 * h * h) * an_;
        c_q = 0.25 * h * h;
        break;
      case SecondOrderMethod::kBdf2: {
        const double k = 2.0 * h / 3.0;
        v_pred_ = (4.0 * vn_ - v_prev_) / 3.0;
        c_v = k;
        q_pred_ = (4.0 * qn_ - q_prev_) / 3.0 + k * v_pred_;
        c_q = k * k;
        break;
      }
      case SecondOrderMethod::kGeneralizedAlpha: {
        // x_{n+1} = x_known + (1 - af) / (1 - am) a_{n+1}
        const double s = (1.0 - af_) / (1.0 - am_);
        r_ = (af_ * an_ - am_ * x_) / (1.0 - am_);  // x_known, in scratch
        q_pred_ = qn_ + h * vn_ + (h * h * (0.5 - beta_)) * x_ + (h * h * beta_) * r_;
        c_q = h * h * beta_ * s;
        v_pred_ = vn_ + (h * (1.0 - gamma_)) * x_ + (h * gamma_) * r_;
        c_v = h * gamma_ * s;
        break;
      }
    }
  }

  /// Newton on (a, lambda) from their current values; false if it did not
  /// converge. `full_newton`: the matrix is formed again at every iteration
  /// (the retry after a failure with a kept one).
  bool iterate(double t1, double c_q, double c_v, bool full_newton = false) {
    double previous = 0.0;
    bool fresh = false;
    for (int it = 0; it < kMaxIterations; ++it) {
      q_ = q_pred_ + c_q * a_;
      v_ = v_pred_ + c_v * a_;
      if (refresh_) {
        sys_.factorize(t1, q_, v_, a_, lambda_, c_q, c_v);
        ++stats_.factorizations;
        factored_cq_ = c_q;
        refresh_ = false;
        fresh = true;
      }
      sys_.residual(t1, q_, v_, a_, lambda_, c_q, r_, c_);
      sys_.solve(r_, c_, da_, dl_);
      a_ -= da_;
      lambda_ -= dl_;
      ++stats_.iterations;
      // The size of the correction as the positions and rates see it.
      const double da = da_.norm();
      q_ = q_pred_ + c_q * a_;
      v_ = v_pred_ + c_v * a_;
      const double position = c_q * da / (1.0 + q_.norm());
      const double correction = std::max(position, c_v * da / (1.0 + v_.norm()));
      if (!std::isfinite(correction)) return false;
      // Converged; or the positions have, and the rates' correction is at the
      // round-off floor: the constraint rows (Phi / c_q) turn the round-off of
      // Phi into an acceleration noise ~ eps |q| / c_q, a rate noise
      // ~ eps (c_v / c_q) |q| that no iteration lowers (at small steps it is
      // above the tolerance).
      const double rate = c_v * da / (1.0 + v_.norm());
      const double floor = kRoundOffFloor * (c_v / c_q) * (1.0 + q_.norm()) / (1.0 + v_.norm());
      const bool at_noise_floor = position <= kNewtonTol && rate <= floor;
      // With a fast contraction theta, the corrections still to come sum to
      // at most theta / (1 - theta) of this one: below the tolerance, the
      // next iteration would not change the answer (Hairer and Wanner's test;
      // only for theta small enough that two corrections estimate it well).
      const double theta = it > 0 ? correction / previous : 1.0;
      const bool next_below = theta <= kTrustedContraction && correction * theta / (1.0 - theta) <= kNewtonTol;
      if (correction <= kNewtonTol || at_noise_floor || next_below) {
        if (!fresh && it + 1 > kRefreshAfterIterations) refresh_ = true;  // for the next step
        return true;
      }
      // Diverging with a matrix formed in this very step: give up (the caller
      // retries with full Newton). Contracting slowly: form the matrix again,
      // here at the current iterate, whether it is kept or fresh.
      if (it > 0 && fresh && correction > previous) return false;
      // (Near the tolerance, a slow contraction is round-off, not a stale matrix.)
      // The first contraction mixes in the predictor's error: judged on a
      // looser bound (kFirstContraction) than the ones after it.
      const double slow = it == 1 ? kFirstContraction : kSlowContraction;
      if (full_newton || (it > 0 && correction > slow * previous && correction > kStaleAbove * kNewtonTol))
        refresh_ = true;
      previous = correction;
    }
    return false;
  }

  SecondOrderSystem& sys_;
  SecondOrderMethod method_;
  int n_, m_;
  double am_ = 0, af_ = 0, gamma_ = 0, beta_ = 0;
  Eigen::VectorXd q_, v_, a_, x_, lambda_;           // state at t_{n+1} (during a step), history
  Eigen::VectorXd q_prev_, v_prev_;                  // BDF2: q_{n-1}, v_{n-1}
  Eigen::VectorXd q_pred_, v_pred_, qn_, vn_, an_, lambda_n_;
  Eigen::VectorXd r_, c_, da_, dl_;
  long steps_ = 0;
  bool refresh_ = true;
  double factored_cq_ = 0.0;
  NewtonStatistics stats_;
};

}  // namespace

std::unique_ptr<Stepper> make_second_order_stepper(OdeSystem& ode, SecondOrderSystem& system,
                                                   SecondOrderMethod method, double rho_inf) {
  return std::make_unique<SecondOrderStepper>(ode, system, method, rho_inf);
}

}  // namespace mbfe::runtime
