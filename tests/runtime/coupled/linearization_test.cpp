// rhs_jacobian and the spectra of linearised second-order systems against
// closed forms: a damped pendulum theta'' = -(g/L) sin theta - c theta' away
// from equilibrium (A = [[0, 1], [-(g/L) cos theta, -c]]), and two uncoupled
// damped oscillators, whose eigenvalues are -zeta w +- i w sqrt(1 - zeta^2).
#include "runtime/coupled/linearization.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <complex>

#include "runtime/integrators/ode_system.h"

namespace mbfe::runtime {
namespace {

constexpr double kGOverL = 9.81 / 0.7;  // 1/s^2
constexpr double kDamping = 0.3;        // 1/s

/// Two uncoupled damped pendulums (y = [theta1, theta2, theta1', theta2']),
/// the second with twice the stiffness: a second-order system as
/// rhs_jacobian expects it.
class Pendulums final : public OdeSystem {
 public:
  int size() const override { return 4; }
  void rhs(double, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) override {
    ydot.resize(4);
    ydot << y[2], y[3], -kGOverL * std::sin(y[0]) - kDamping * y[2], -2.0 * kGOverL * std::sin(y[1]) - kDamping * y[3];
  }
};

// Central differences at steps 1e-6 max(1, |y|) of sin: truncation ~1e-12
// relative, round-off ~eps / 1e-6 ~ 1e-10 of the O(10) entries.
constexpr double kJacobianTol = 1e-8;
// Eigenvalues of a 4 x 4 matrix from those entries: the same relative error.
constexpr double kEigenvalueTol = 1e-8;

TEST(Linearization, JacobianIsTheClosedFormAwayFromEquilibrium) {
  Pendulums sys;
  Eigen::VectorXd y(4);
  y << 0.8, -0.4, 1.5, -0.2;
  const Eigen::MatrixXd A = rhs_jacobian(sys, 0.0, y);
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(4, 4);
  expected(0, 2) = expected(1, 3) = 1.0;
  expected(2, 0) = -kGOverL * std::cos(0.8);
  expected(3, 1) = -2.0 * kGOverL * std::cos(-0.4);
  expected(2, 2) = expected(3, 3) = -kDamping;
  EXPECT_LT((A - expected).cwiseAbs().maxCoeff(), kJacobianTol * kGOverL) << A;
}

TEST(Linearization, SpectrumAtRestIsTheDampedOscillators) {
  Pendulums sys;
  const StateSpectrum s = linearized_spectrum(sys, 0.0, Eigen::VectorXd::Zero(4));
  ASSERT_EQ(s.eigenvalues.size(), 4u);
  EXPECT_EQ(s.oscillatory_pairs, 2);
  // Sorted by modulus: w^2 = g/L first, then 2 g/L; +imag first in each pair.
  int k = 0;
  for (double w2 : {kGOverL, 2.0 * kGOverL}) {
    const double re = -0.5 * kDamping, im = std::sqrt(w2 - re * re);
    for (double sign : {1.0, -1.0}) {
      const std::complex<double> expected(re, sign * im);
      EXPECT_LT(std::abs(s.eigenvalues[k] - expected), kEigenvalueTol * std::sqrt(w2))
          << "eigenvalue " << k << ": " << s.eigenvalues[k] << " vs " << expected;
      ++k;
    }
  }
  // Forward Euler's limit, -2 Re / |lambda|^2, is set by the stiffer pair.
  EXPECT_NEAR(s.h_max_forward_euler, kDamping / (2.0 * kGOverL), kEigenvalueTol);
}

TEST(Linearization, DenseSpectrumOfAKnownMatrix) {
  // Block diagonal: a rotation-like pair -1 +- 2i and the real roots -3, -5.
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(4, 4);
  a.topLeftCorner(2, 2) << -1, 2, -2, -1;
  a(2, 2) = -5;
  a(3, 3) = -3;
  const StateSpectrum s = dense_spectrum(a);
  ASSERT_EQ(s.eigenvalues.size(), 4u);
  EXPECT_EQ(s.oscillatory_pairs, 1);
  EXPECT_LT(std::abs(s.eigenvalues[0] - std::complex<double>(-1, 2)), kEigenvalueTol);
  EXPECT_LT(std::abs(s.eigenvalues[1] - std::complex<double>(-1, -2)), kEigenvalueTol);
  EXPECT_LT(std::abs(s.eigenvalues[2] - std::complex<double>(-3, 0)), kEigenvalueTol);
  EXPECT_LT(std::abs(s.eigenvalues[3] - std::complex<double>(-5, 0)), kEigenvalueTol);
}

}  // namespace
}  // namespace mbfe::runtime
