// The implicit second-order steppers on two hand-built systems: a pendulum in
// Cartesian coordinates (x, y) held by x^2 + y^2 = L^2 (nonlinear, one
// multiplier) against a fine RK4 solution of theta'' = -(g / L) sin theta,
// for each method's order and the constraint at every step; and the linear
// oscillator, where backward Euler and the trapezoid rule must give their
// closed-form one-step maps.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "runtime/integrators/ode_system.h"
#include "runtime/integrators/second_order_steppers.h"

namespace mbfe::runtime {
namespace {

constexpr double kLength = 1.0;    // m
constexpr double kGravity = 9.81;  // m/s^2
constexpr double kMass = 2.0;      // kg
constexpr double kTheta0 = 0.6;    // rad, from rest
constexpr double kEnd = 1.0;       // s

// Observed order log2(e(h) / e(h/2)) within 0.2 of the method's at these
// steps (the h^(p+1) terms are a few percent of the error).
constexpr double kOrderTol = 0.2;
// Newton stops at 1e-10 (1 + |q|) in position; Phi is c_q times the
// constraint row's residual, far below that.
constexpr double kClosureTol = 1e-10;
// One step of a 2 x 2 linear map, values O(1e-2): round-off.
constexpr double kOneStepTol = 1e-15;

/// m q'' + (0, m g) + G^T lambda = 0 with Phi = |q|^2 - L^2, G = 2 q^T
/// (y up; the pendulum hangs from the origin).
class CartesianPendulum final : public OdeSystem, public SecondOrderSystem {
 public:
  int size() const override { return 4; }
  int dof() const override { return 2; }
  int num_multipliers() const override { return 1; }
  void rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) override {
    Eigen::VectorXd a, l;
    accelerations(t, y.head(2), y.tail(2), a, l);
    ydot.resize(4);
    ydot << y.tail(2), a;
  }
  void residual(double, const Eigen::VectorXd& q, const Eigen::VectorXd&, const Eigen::VectorXd& a,
                const Eigen::VectorXd& lambda, double c_q, Eigen::VectorXd& r, Eigen::VectorXd& c) override {
    r = kMass * a + Eigen::Vector2d(0.0, kMass * kGravity) + 2.0 * q * lambda[0];
    c.resize(1);
    c[0] = (q.squaredNorm() - kLength * kLength) / c_q;
  }
  void factorize(double, const Eigen::VectorXd& q, const Eigen::VectorXd&, const Eigen::VectorXd&,
                 const Eigen::VectorXd& lambda, double c_q, double) override {
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    A.topLeftCorner<2, 2>() = (kMass + c_q * 2.0 * lambda[0]) * Eigen::Matrix2d::Identity();
    A.block<2, 1>(0, 2) = 2.0 * q;
    A.block<1, 2>(2, 0) = 2.0 * q.transpose();
    lu_.compute(A);
  }
  void solve(const Eigen::VectorXd& r, const Eigen::VectorXd& c, Eigen::VectorXd& da,
             Eigen::VectorXd& dlambda) override {
    const Eigen::Vector3d x = lu_.solve(Eigen::Vector3d(r[0], r[1], c[0]));
    da = x.head(2);
    dlambda = x.tail(1);
  }
  void accelerations(double, const Eigen::VectorXd& q, const Eigen::VectorXd& v, Eigen::VectorXd& a,
                     Eigen::VectorXd& lambda) override {
    // [m I, 2 q; 2 q^T, 0] [a; lambda] = [-(0, m g); -2 |v|^2]  (Phi'' = 0)
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    A.topLeftCorner<2, 2>() = kMass * Eigen::Matrix2d::Identity();
    A.block<2, 1>(0, 2) = 2.0 * q;
    A.block<1, 2>(2, 0) = 2.0 * q.transpose();
    const Eigen::Vector3d x = A.partialPivLu().solve(Eigen::Vector3d(0.0, -kMass * kGravity, -2.0 * v.squaredNorm()));
    a = x.head(2);
    lambda = x.tail(1);
  }

 private:
  Eigen::PartialPivLU<Eigen::Matrix3d> lu_;
};

/// theta(kEnd) of theta'' = -(g / L) sin theta from (kTheta0, 0): RK4 at
/// 1e-4 s, error ~1e-14, far below the steppers' at 2.5e-3 s.
double reference_angle() {
  const auto f = [](const Eigen::Vector2d& s) { return Eigen::Vector2d(s[1], -kGravity / kLength * std::sin(s[0])); };
  Eigen::Vector2d s(kTheta0, 0.0);
  const int n = 10000;
  const double h = kEnd / n;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d k1 = f(s), k2 = f(s + h / 2 * k1), k3 = f(s + h / 2 * k2), k4 = f(s + h * k3);
    s += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  return s[0];
}

/// |theta - reference| at kEnd with step h; also the largest |Phi| met.
double angle_error(SecondOrderMethod method, double h, double reference, double* max_phi = nullptr) {
  CartesianPendulum sys;
  auto stepper = make_second_order_stepper(sys, sys, method, 0.8);
  Eigen::VectorXd y(4);
  y << kLength * std::sin(kTheta0), -kLength * std::cos(kTheta0), 0.0, 0.0;
  stepper->reset(0.0, y);
  const int steps = static_cast<int>(std::lround(kEnd / h));
  double phi = 0.0;
  for (int i = 0; i < steps; ++i) {
    stepper->step(i * h, h, y);
    phi = std::max(phi, std::abs(y.head(2).squaredNorm() - kLength * kLength));
  }
  if (max_phi) *max_phi = phi;
  return std::abs(std::atan2(y[0], -y[1]) - reference);
}

struct MethodCase {
  const char* name;
  SecondOrderMethod method;
  int order;
};

class PendulumOrder : public ::testing::TestWithParam<MethodCase> {};

TEST_P(PendulumOrder, ConvergesAtItsOrderWithTheConstraintClosed) {
  const MethodCase c = GetParam();
  const double reference = reference_angle();
  double phi1 = 0.0, phi2 = 0.0;
  const double e1 = angle_error(c.method, 5e-3, reference, &phi1);
  const double e2 = angle_error(c.method, 2.5e-3, reference, &phi2);
  EXPECT_NEAR(std::log2(e1 / e2), c.order, kOrderTol) << c.name << ": errors " << e1 << ", " << e2;
  EXPECT_LT(std::max(phi1, phi2), kClosureTol) << c.name;
}

INSTANTIATE_TEST_SUITE_P(SecondOrderSteppers, PendulumOrder,
                         ::testing::Values(MethodCase{"backward_euler", SecondOrderMethod::kBackwardEuler, 1},
                                           MethodCase{"trapezoid", SecondOrderMethod::kTrapezoid, 2},
                                           MethodCase{"bdf2", SecondOrderMethod::kBdf2, 2},
                                           MethodCase{"generalized_alpha", SecondOrderMethod::kGeneralizedAlpha, 2}),
                         [](const ::testing::TestParamInfo<MethodCase>& i) { return std::string(i.param.name); });

/// q'' + 2 zeta w q' + w^2 q = p: unconstrained, linear.
class Oscillator final : public OdeSystem, public SecondOrderSystem {
 public:
  static constexpr double w = 10.0, zeta = 0.05, p = 3.0;
  int size() const override { return 2; }
  int dof() const override { return 1; }
  int num_multipliers() const override { return 0; }
  void rhs(double, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) override {
    ydot.resize(2);
    ydot << y[1], p - 2 * zeta * w * y[1] - w * w * y[0];
  }
  void residual(double, const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a,
                const Eigen::VectorXd&, double, Eigen::VectorXd& r, Eigen::VectorXd& c) override {
    r = a + 2 * zeta * w * v + w * w * q - Eigen::VectorXd::Constant(1, p);
    c.resize(0);
  }
  void factorize(double, const Eigen::VectorXd&, const Eigen::VectorXd&, const Eigen::VectorXd&,
                 const Eigen::VectorXd&, double c_q, double c_v) override {
    matrix_ = 1.0 + c_v * 2 * zeta * w + c_q * w * w;
  }
  void solve(const Eigen::VectorXd& r, const Eigen::VectorXd&, Eigen::VectorXd& da, Eigen::VectorXd& dl) override {
    da = r / matrix_;
    dl.resize(0);
  }
  void accelerations(double, const Eigen::VectorXd& q, const Eigen::VectorXd& v, Eigen::VectorXd& a,
                     Eigen::VectorXd& l) override {
    a = Eigen::VectorXd::Constant(1, p) - 2 * zeta * w * v - w * w * q;
    l.resize(0);
  }

 private:
  double matrix_ = 1.0;
};

TEST(SecondOrderSteppers, LinearStepsAreTheClosedFormMaps) {
  // y' = A y + b, y = [q; q']: backward Euler y1 = (I - hA)^-1 (y0 + h b),
  // the trapezoid rule y1 = (I - hA/2)^-1 ((I + hA/2) y0 + h b).
  Eigen::Matrix2d A;
  A << 0, 1, -Oscillator::w * Oscillator::w, -2 * Oscillator::zeta * Oscillator::w;
  const Eigen::Vector2d b(0, Oscillator::p);
  const Eigen::Vector2d y0(0.01, -0.2);
  const double h = 0.01;
  const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
  const Eigen::Vector2d be = (I - h * A).inverse() * (y0 + h * b);
  const Eigen::Vector2d tr = (I - 0.5 * h * A).inverse() * ((I + 0.5 * h * A) * y0 + h * b);
  for (auto [method, expected] : {std::pair{SecondOrderMethod::kBackwardEuler, be},
                                  std::pair{SecondOrderMethod::kTrapezoid, tr}}) {
    Oscillator sys;
    auto stepper = make_second_order_stepper(sys, sys, method, 1.0);
    Eigen::VectorXd y = y0;
    stepper->reset(0.0, y);
    stepper->step(0.0, h, y);
    EXPECT_LT((y - Eigen::VectorXd(expected)).norm(), kOneStepTol) << static_cast<int>(method);
    // Linear: Newton from the kept start converges in one correction plus the check.
    EXPECT_LE(stepper->newton_statistics().iterations, 2);
  }
}

TEST(SecondOrderSteppers, WrongSizedOdeIsRefused) {
  Oscillator sys;
  CartesianPendulum other;
  EXPECT_THROW(make_second_order_stepper(other, sys, SecondOrderMethod::kBdf2, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace mbfe::runtime
