// Generalized-alpha's spectral properties against Chung & Hulbert (1993) on
// the undamped oscillator q'' + w^2 q = 0 at Omega = w h: the displacements
// the stepper produces satisfy the three-term recurrence of the method's
// amplification matrix, built here from the method's defining equations;
// its spectral radius tends to rho_inf as Omega grows (all three roots to
// -rho_inf, the closed form that fixes alpha_m and alpha_f), and it is 1 for
// every Omega when rho_inf = 1. Second order is checked in integrators_test.cpp.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <memory>

#include "runtime/integrators/integrator.h"
#include "runtime/integrators/linear_second_order_system.h"

namespace mbfe::runtime {
namespace {

// The stepper's displacements in the amplification matrix's recurrence:
// O(1) values, each step a few ulps of round-off, over 12 steps.
constexpr double kRecurrenceTol = 1e-12;
// At Omega = 1e6 the recurrence differs from its limit by O(Omega^-2) = 1e-12.
// (There q_{n+1} is -rho_inf q_n up to that: the sequence shows one root, too
// few to fit the three coefficients from it.)
constexpr double kHighOmega = 1e6;
constexpr double kLimitTol = 1e-9;
// rho_inf = 1: the product of the roots, fitted from four O(1) displacements.
constexpr double kUnitRadiusTol = 1e-10;

/// q'' + w^2 q = P(t), with P non-zero only at the start time, where it sets
/// the initial acceleration a0 = P(t0) - w^2 q0 (reset() evaluates it there;
/// the steps evaluate the load strictly inside each step).
class FreeOscillator final : public LinearSecondOrderSystem {
 public:
  FreeOscillator(double w, double start_load) : w2_(w * w), p0_(start_load) {}
  int dof() const override { return 1; }
  void load(double t, Eigen::VectorXd& out) override { out.setConstant(1, t == 0.0 ? p0_ : 0.0); }
  void mult_m(const Eigen::VectorXd& x, Eigen::VectorXd& out) override { out = x; }
  void mult_c(const Eigen::VectorXd& x, Eigen::VectorXd& out) override { out = 0.0 * x; }
  void mult_k(const Eigen::VectorXd& x, Eigen::VectorXd& out) override { out = w2_ * x; }
  void solve_combination(double a, double, double c, const Eigen::VectorXd& r, Eigen::VectorXd& x) override {
    x = r / (a + c * w2_);
  }

 private:
  double w2_, p0_;
};

/// Chung & Hulbert's parameters from rho_inf (their eq. 25 and the
/// second-order condition gamma = 1/2 - am + af, beta = (1 - am + af)^2 / 4).
struct Parameters {
  double am, af, gamma, beta;
  explicit Parameters(double rho) {
    am = (2.0 * rho - 1.0) / (rho + 1.0);
    af = rho / (rho + 1.0);
    gamma = 0.5 - am + af;
    beta = 0.25 * (1.0 - am + af) * (1.0 - am + af);
  }
};

/// The amplification matrix of X = (q, h v, h^2 a) for q'' + w^2 q = 0 with
/// step h (Omega = w h), from the method's three equations:
///   (1 - am) a1 + am a0 + w^2 ((1 - af) q1 + af q0) = 0
///   q1 = q0 + h v0 + h^2 ((1/2 - beta) a0 + beta a1)
///   v1 = v0 + h ((1 - gamma) a0 + gamma a1)
Eigen::Matrix3d amplification(double rho, double omega) {
  const Parameters p(rho);
  const double o2 = omega * omega;
  Eigen::Matrix3d L, R;  // L X1 = R X0
  L << 1, 0, -p.beta,  //
      0, 1, -p.gamma,  //
      (1 - p.af) * o2, 0, 1 - p.am;
  R << 1, 1, 0.5 - p.beta,  //
      0, 1, 1 - p.gamma,    //
      -p.af * o2, 0, -p.am;
  return L.partialPivLu().solve(R);
}

/// (c2, c1, c0) of q_{n+3} = c2 q_{n+2} + c1 q_{n+1} + c0 q_n: the
/// characteristic polynomial lambda^3 - c2 lambda^2 - c1 lambda - c0 of A.
Eigen::Vector3d recurrence_of(const Eigen::Matrix3d& A) {
  const double minors = A(0, 0) * A(1, 1) - A(0, 1) * A(1, 0) + A(0, 0) * A(2, 2) - A(0, 2) * A(2, 0) +
                        A(1, 1) * A(2, 2) - A(1, 2) * A(2, 1);
  return {A.trace(), -minors, A.determinant()};
}

/// q_0 .. q_{steps} of the stepper from the state (q0, h v0, h^2 a0) =
/// (1, 0.4, -0.7), which excites every root and keeps every q_n O(1).
Eigen::VectorXd displacements(double rho, double omega, int steps) {
  const double h = 1.0, w = omega / h;
  const double q0 = 1.0, v0 = 0.4 / h, a0 = -0.7 / (h * h);
  FreeOscillator sys(w, a0 + w * w * q0);
  IntegratorSpec spec = parse_integrator("generalized_alpha");
  spec.rho_inf = rho;
  auto stepper = make_stepper(spec, sys);
  Eigen::VectorXd y(2);
  y << q0, v0;
  stepper->reset(0.0, y);
  Eigen::VectorXd q(steps + 1);
  q[0] = q0;
  for (int n = 1; n <= steps; ++n) {
    stepper->step((n - 1) * h, h, y);
    q[n] = y[0];
  }
  return q;
}

/// max_n |q_{n+3} - c2 q_{n+2} - c1 q_{n+1} - c0 q_n| / max |q|.
double recurrence_residual(const Eigen::VectorXd& q, const Eigen::Vector3d& c) {
  double worst = 0.0;
  for (Eigen::Index n = 0; n + 3 < q.size(); ++n)
    worst = std::max(worst, std::abs(q[n + 3] - c[0] * q[n + 2] - c[1] * q[n + 1] - c[2] * q[n]));
  return worst / q.cwiseAbs().maxCoeff();
}

/// The coefficients of the three-term recurrence fitted from six
/// displacements (rho_inf < 1: the q sequence sees all three roots).
Eigen::Vector3d fitted_recurrence(double rho, double omega) {
  const Eigen::VectorXd q = displacements(rho, omega, 5);
  Eigen::Matrix3d H;
  Eigen::Vector3d rhs;
  for (int n = 0; n < 3; ++n) {
    H.row(n) << q[n + 2], q[n + 1], q[n];
    rhs[n] = q[n + 3];
  }
  return H.fullPivLu().solve(rhs);
}

double spectral_radius(const Eigen::Vector3d& c) {
  // Roots of lambda^3 - c2 lambda^2 - c1 lambda - c0: eigenvalues of the companion matrix.
  Eigen::Matrix3d companion;
  companion << c[0], c[1], c[2], 1, 0, 0, 0, 1, 0;
  return companion.eigenvalues().cwiseAbs().maxCoeff();
}

constexpr int kSteps = 12;

TEST(GeneralizedAlpha, StepperFollowsTheAmplificationMatrix) {
  for (double rho : {0.0, 0.3, 0.6, 0.9, 1.0})
    for (double omega : {0.1, 1.0, 3.0, 30.0}) {
      const Eigen::Vector3d reference = recurrence_of(amplification(rho, omega));
      EXPECT_LT(recurrence_residual(displacements(rho, omega, kSteps), reference), kRecurrenceTol)
          << "rho_inf " << rho << ", Omega " << omega << ", recurrence " << reference.transpose();
    }
}

TEST(GeneralizedAlpha, AllRootsTendToMinusRhoInf) {
  // Chung & Hulbert: at Omega -> infinity the characteristic polynomial is
  // (lambda + rho_inf)^3, so the spectral radius there is rho_inf.
  for (double rho : {0.0, 0.3, 0.6, 0.9, 1.0}) {
    const Eigen::Vector3d limit(-3.0 * rho, -3.0 * rho * rho, -rho * rho * rho);
    EXPECT_LT(recurrence_residual(displacements(rho, kHighOmega, kSteps), limit), kLimitTol) << "rho_inf " << rho;
  }
}

TEST(GeneralizedAlpha, SpectralRadiusFallsFromOneToRhoInf) {
  // rho_inf < 1 damps high frequencies more than low ones: the radius falls
  // with Omega from 1 towards rho_inf.
  for (double rho : {0.0, 0.5, 0.8}) {
    double previous = 1.0;
    for (double omega : {0.3, 1.0, 3.0, 10.0, 100.0}) {
      const double r = spectral_radius(fitted_recurrence(rho, omega));
      EXPECT_LT(r, previous) << "rho_inf " << rho << ", Omega " << omega;
      EXPECT_GE(r, rho) << "rho_inf " << rho << ", Omega " << omega;
      previous = r;
    }
  }
}

TEST(GeneralizedAlpha, RhoInfOneDampsNothing) {
  // rho_inf = 1: the third root (-1) does not reach q, which follows
  // q_{n+2} = d1 q_{n+1} + d0 q_n with a complex pair of roots whose product
  // -d0 is 1 at every Omega: no numerical damping.
  for (double omega : {0.3, 1.0, 3.0, 10.0, 100.0}) {
    const Eigen::VectorXd q = displacements(1.0, omega, 3);
    Eigen::Matrix2d H;
    H << q[1], q[0], q[2], q[1];
    const Eigen::Vector2d d = H.partialPivLu().solve(Eigen::Vector2d(q[2], q[3]));
    EXPECT_NEAR(d[1], -1.0, kUnitRadiusTol) << "Omega " << omega;
    EXPECT_LT(std::abs(d[0]), 2.0) << "Omega " << omega;  // complex pair: on the unit circle
  }
}

}  // namespace
}  // namespace mbfe::runtime
