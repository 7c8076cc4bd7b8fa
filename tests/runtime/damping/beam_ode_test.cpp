// A beam in modal coordinates (runtime/damping/beam_ode.h) against its nodal
// equation assembled by hand with dense Eigen: with Phi the mass-normalised
// modes and m_j, c_j, k_j per mode, the modal ODE is the nodal one
//   M_e q'' + C_e q' + K_e q = P,  M_e = M Phi diag(m) Phi^T M  (C_e, K_e alike)
// (Phi^T M Phi = I, so Phi^T M_e Phi = diag(m)), whose acceleration
// q'' = M_e^-1 (P - C_e q' - K_e q) a dense LU gives; mapped by q = Phi eta it
// must be the modal right-hand side. With m = 1 and Rayleigh c_j, k_j the
// oracle is the textbook M^-1 (P - C q' - K q).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <vector>

#include "runtime/damping/beam_ode.h"
#include "runtime/modal/modal_analysis.h"
#include "tests/runtime/coupled/test_beam.h"

namespace mbfe::runtime {
namespace {

// A 10-element beam, 20 DOF: a dense LU and the modal product sum the same
// terms in another order, through K's spread of stiff and soft modes; 1e-9
// of the largest acceleration is that round-off with a margin, and a wrong
// term (one mode's k or c, or a wrong sign) shows far above it.

constexpr double kConditionedRoundOff = 1e-9;
// eta = Phi^T M (Phi eta): one product with an M-orthonormal basis.
constexpr double kOrthonormalityTol = 1e-10;

struct Fixture {
  testing::TestBeam beam = testing::pinned_pinned_beam("deck", 4.0, 10, 2.0e4, 0.9, -9.81 * 0.9, 0.4, 3e-5);
  Eigen::MatrixXd M = Eigen::MatrixXd(beam.beam.M), K = Eigen::MatrixXd(beam.K), C = Eigen::MatrixXd(beam.C);
  ModalBasis basis = modal_dense(beam.beam.M, beam.K);
  int n = static_cast<int>(M.rows());
};

// A state away from rest (seeded), nodal [q; q'].
Eigen::VectorXd nodal_state(int n) {
  std::mt19937 rng(20261124);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd y(2 * n);
  for (int i = 0; i < 2 * n; ++i) y[i] = (i < n ? 1e-3 : 1e-2) * u(rng);
  return y;
}

TEST(ModalBeamOde, RayleighRightHandSideIsTheNodalAcceleration) {
  const Fixture f;
  ASSERT_TRUE(f.basis.complete);
  const std::vector<ModalDynamics> modes = rayleigh_modes(f.basis.omega, 0.4, 3e-5);
  ModalBeamOde ode(f.basis, modes, f.beam.beam.M, f.beam.beam.P);
  ASSERT_EQ(ode.dof(), f.n);
  const Eigen::VectorXd y_nodal = nodal_state(f.n);
  const Eigen::VectorXd y = ode.from_nodal(y_nodal);
  Eigen::VectorXd q;
  ode.positions(y, q);
  const double q_scale = y_nodal.head(f.n).cwiseAbs().maxCoeff();
  EXPECT_LT((q - y_nodal.head(f.n)).cwiseAbs().maxCoeff(), kOrthonormalityTol * q_scale);

  Eigen::VectorXd ydot;
  ode.rhs(0.0, y, ydot);
  ASSERT_EQ(ydot.size(), 2 * f.n);
  const Eigen::VectorXd qdd_oracle =
      f.M.lu().solve(f.beam.beam.P - f.C * y_nodal.tail(f.n) - f.K * y_nodal.head(f.n));
  const Eigen::VectorXd qdd = f.basis.phi * ydot.tail(f.n);
  const double scale = qdd_oracle.cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.0);
  EXPECT_LT((qdd - qdd_oracle).cwiseAbs().maxCoeff(), kConditionedRoundOff * scale);
  // The first half is the rates: eta' exactly.
  EXPECT_TRUE(ydot.head(f.n) == y.tail(f.n));
}

TEST(ModalBeamOde, ModalMassesAndAdjustedValuesFollowTheEquivalentNodalEquation) {
  const Fixture f;
  std::vector<ModalDynamics> modes = rayleigh_modes(f.basis.omega, 0.4, 3e-5);
  // Some modes adjusted as the policies do: stiffness lowered, damping
  // raised, modal mass raised (the policy mass).
  for (int j = f.n / 2; j < f.n; ++j) {
    modes[j].k *= 0.25;
    modes[j].c *= 3.0;
    modes[j].m = 1.0 + 0.1 * j;
  }
  ModalBeamOde ode(f.basis, modes, f.beam.beam.M, f.beam.beam.P);
  Eigen::VectorXd m(f.n), c(f.n), k(f.n);
  for (int j = 0; j < f.n; ++j) {
    m[j] = modes[j].m;
    c[j] = modes[j].c;
    k[j] = modes[j].k;
  }
  const Eigen::MatrixXd mphi = f.M * f.basis.phi;
  const Eigen::MatrixXd Me = mphi * m.asDiagonal() * mphi.transpose();
  const Eigen::MatrixXd Ce = mphi * c.asDiagonal() * mphi.transpose();
  const Eigen::MatrixXd Ke = mphi * k.asDiagonal() * mphi.transpose();
  const Eigen::VectorXd y_nodal = nodal_state(f.n);
  Eigen::VectorXd ydot;
  ode.rhs(0.0, ode.from_nodal(y_nodal), ydot);
  const Eigen::VectorXd qdd_oracle =
      Me.lu().solve(f.beam.beam.P - Ce * y_nodal.tail(f.n) - Ke * y_nodal.head(f.n));
  const Eigen::VectorXd qdd = f.basis.phi * ydot.tail(f.n);
  const double scale = qdd_oracle.cwiseAbs().maxCoeff();
  EXPECT_LT((qdd - qdd_oracle).cwiseAbs().maxCoeff(), kConditionedRoundOff * scale);
  // The modal load is Phi^T P, to round-off of the sum of |Phi_ij P_i|.
  const Eigen::VectorXd bound = f.basis.phi.cwiseAbs().transpose() * f.beam.beam.P.cwiseAbs();
  EXPECT_LT((ode.modal_load() - f.basis.phi.transpose() * f.beam.beam.P).cwiseAbs().maxCoeff(),
            kOrthonormalityTol * bound.maxCoeff());
}

TEST(ModalBeamOde, RefusesAPartialBasisAndANonPositiveModalMass) {
  const Fixture f;
  std::vector<ModalDynamics> modes = rayleigh_modes(f.basis.omega, 0.4, 3e-5);
  ModalBasis partial = f.basis;
  partial.phi = f.basis.phi.leftCols(f.n - 1);
  partial.complete = false;
  EXPECT_THROW(ModalBeamOde(partial, modes, f.beam.beam.M, f.beam.beam.P), std::invalid_argument);
  modes[3].m = 0.0;
  EXPECT_THROW(ModalBeamOde(f.basis, modes, f.beam.beam.M, f.beam.beam.P), std::invalid_argument);
}

}  // namespace
}  // namespace mbfe::runtime
