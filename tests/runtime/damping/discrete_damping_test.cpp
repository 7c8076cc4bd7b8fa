// The damping of a beam's discrete parts (runtime/fem/beam_system.h,
// damping_remainder): the nodal C is Rayleigh over the elements plus the
// supports' dampers, while a modal form damps every mode by
// alpha + beta omega_j^2 of the whole M and K, point masses and spring
// supports included. The remainder R = C - (alpha M + beta K) is checked
// against its closed form, c - alpha m - beta k on each discrete part's DOF,
// and the modal form with it (runtime/damping/beam_ode.h) against the nodal
// equation M q'' + C q' + K q = P with dense Eigen: its right-hand side and
// its implicit solves.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <vector>

#include "runtime/damping/beam_ode.h"
#include "runtime/fem/beam_system.h"
#include "runtime/modal/modal_analysis.h"
#include "tests/runtime/fem/beam_fixtures.h"

namespace mbfe::runtime {
namespace {

// The remainder is a sum of three products of given numbers: exact to a few ulps of its terms.
constexpr double kRemainderRel = 1e-14;
// A dense LU of the nodal matrices against the modal products (20-ish DOFs,
// K's spread of stiff and soft modes): as in beam_ode_test.cpp.
constexpr double kConditionedRoundOff = 1e-9;

constexpr double kAlpha = 0.4, kBeta = 3e-4;                         // 1/s, s
constexpr double kPointMass = 0.5, kSupportMass = 1.0;               // kg
constexpr double kSupportStiffness = 2.0e4, kSupportDamping = 30.0;  // N/m, N s/m

/// The paper's beam cut to 8 elements, pinned at the ends, with a point mass
/// at 0.25 m and a sprung, damped, massive support at midspan.
ir::Beam beam_with_parts() {
  ir::Beam b = test::paper_beam(0.005, 8);
  b.rayleigh_alpha = kAlpha;
  b.rayleigh_beta = kBeta;
  ir::Support spring;
  spring.at = 0.5;
  spring.type = ir::SupportType::kSpring;
  spring.stiffness = kSupportStiffness;
  spring.damping = kSupportDamping;
  spring.mass = kSupportMass;
  b.supports.push_back(spring);
  ir::BeamPointMass m;
  m.at = 0.25;
  m.mass = kPointMass;
  b.masses.push_back(m);
  return b;
}

TEST(DiscreteDamping, RemainderIsEachPartsDamperLessRayleighOfItsMassAndSpring) {
  const BeamSystem sys = assemble_beam(beam_with_parts(), {0.0, 0.0});
  // w of node 2 (0.25 m) and of node 4 (0.5 m), as free DOFs.
  const int w_mass = sys.full_to_free[2 * 2], w_support = sys.full_to_free[2 * 4];
  ASSERT_GE(w_mass, 0);
  ASSERT_GE(w_support, 0);
  ASSERT_EQ(sys.damping_remainder.size(), 2u);
  const double at_mass = -kAlpha * kPointMass;
  const double at_support = kSupportDamping - kAlpha * kSupportMass - kBeta * kSupportStiffness;
  for (const auto& [dof, value] : sys.damping_remainder) {
    const double expected = dof == w_mass ? at_mass : at_support;
    ASSERT_TRUE(dof == w_mass || dof == w_support) << dof;
    EXPECT_NEAR(value, expected, kRemainderRel * (kSupportDamping + kBeta * kSupportStiffness));
  }
  // And it is all that C holds beyond alpha M + beta K.
  const Eigen::MatrixXd rest = Eigen::MatrixXd(sys.C) - kAlpha * Eigen::MatrixXd(sys.M) - kBeta * Eigen::MatrixXd(sys.K);
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(rest.rows(), rest.cols());
  for (const auto& [dof, value] : sys.damping_remainder) expected(dof, dof) = value;
  EXPECT_LT((rest - expected).cwiseAbs().maxCoeff(), kRemainderRel * Eigen::MatrixXd(sys.C).cwiseAbs().maxCoeff());
}

struct Fixture {
  BeamSystem sys = assemble_beam(beam_with_parts(), {0.0, -9.81});
  Eigen::MatrixXd M = Eigen::MatrixXd(sys.M), K = Eigen::MatrixXd(sys.K), C = Eigen::MatrixXd(sys.C);
  ModalBasis basis = modal_dense(sys.M, sys.K);
  int n = static_cast<int>(M.rows());
  std::unique_ptr<ModalBeamOde> ode() const {
    auto out = std::make_unique<ModalBeamOde>(basis, rayleigh_modes(basis.omega, kAlpha, kBeta), sys.M, sys.P);
    out->set_damping_remainder(sys.damping_remainder);
    return out;
  }
};

Eigen::VectorXd nodal_state(int n) {
  std::mt19937 rng(20261127);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd y(2 * n);
  for (int i = 0; i < 2 * n; ++i) y[i] = (i < n ? 1e-3 : 1e-1) * u(rng);
  return y;
}

TEST(DiscreteDamping, ModalFormWithTheRemainderIsTheNodalEquation) {
  const Fixture f;
  ASSERT_TRUE(f.basis.complete);
  const auto ode = f.ode();
  const Eigen::VectorXd y_nodal = nodal_state(f.n);
  Eigen::VectorXd ydot;
  ode->rhs(0.0, ode->from_nodal(y_nodal), ydot);
  const Eigen::VectorXd qdd_oracle =
      f.M.lu().solve(f.sys.P - f.C * y_nodal.tail(f.n) - f.K * y_nodal.head(f.n));
  const Eigen::VectorXd qdd = f.basis.phi * ydot.tail(f.n);
  EXPECT_LT((qdd - qdd_oracle).cwiseAbs().maxCoeff(), kConditionedRoundOff * qdd_oracle.cwiseAbs().maxCoeff());
  // Without the remainder the modal form is another model: the test can tell.
  ModalBeamOde plain(f.basis, rayleigh_modes(f.basis.omega, kAlpha, kBeta), f.sys.M, f.sys.P);
  plain.rhs(0.0, plain.from_nodal(y_nodal), ydot);
  EXPECT_GT((f.basis.phi * ydot.tail(f.n) - qdd_oracle).cwiseAbs().maxCoeff(),
            1e3 * kConditionedRoundOff * qdd_oracle.cwiseAbs().maxCoeff());
}

TEST(DiscreteDamping, ImplicitSolvesInvertTheNodalCombination) {
  const Fixture f;
  const auto ode = f.ode();
  const Eigen::MatrixXd mphi = f.M * f.basis.phi;  // modal = Phi^T (.) Phi; nodal r = M Phi r_modal
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd r(f.n);
  for (int i = 0; i < f.n; ++i) r[i] = u(rng);
  // (a M + b C + c K) in modal coordinates is Phi^T (a M + b C + c K) Phi.
  const double a = 1.0, b = 2e-3, c = 1e-6;
  const Eigen::MatrixXd A = f.basis.phi.transpose() * (a * f.M + b * f.C + c * f.K) * f.basis.phi;
  Eigen::VectorXd x;
  ode->solve_combination(a, b, c, r, x);
  const Eigen::VectorXd x_oracle = A.lu().solve(r);
  EXPECT_LT((x - x_oracle).cwiseAbs().maxCoeff(), kConditionedRoundOff * x_oracle.cwiseAbs().maxCoeff());
  // The first-order shift (I - h J) x = y, J the modal ODE's Jacobian, by its definition.
  const double h = 1e-4;
  Eigen::VectorXd y(2 * f.n);
  for (int i = 0; i < 2 * f.n; ++i) y[i] = u(rng);
  ode->solve_shifted(0.0, y, h, y, x);
  const Eigen::MatrixXd Cm = f.basis.phi.transpose() * f.C * f.basis.phi;
  const Eigen::MatrixXd Km = f.basis.phi.transpose() * f.K * f.basis.phi;  // diag(omega^2)
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2 * f.n, 2 * f.n);
  J.topRightCorner(f.n, f.n).setIdentity();
  J.bottomLeftCorner(f.n, f.n) = -Km;
  J.bottomRightCorner(f.n, f.n) = -Cm;
  const Eigen::VectorXd shifted_oracle = (Eigen::MatrixXd::Identity(2 * f.n, 2 * f.n) - h * J).lu().solve(y);
  EXPECT_LT((x - shifted_oracle).cwiseAbs().maxCoeff(), kConditionedRoundOff * shifted_oracle.cwiseAbs().maxCoeff());
  // mult_c is Phi^T C Phi.
  Eigen::VectorXd out;
  ode->mult_c(r, out);
  EXPECT_LT((out - Cm * r).cwiseAbs().maxCoeff(), kConditionedRoundOff * (Cm * r).cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace mbfe::runtime
