// The contact constraints of the double pendulum on a beam against
// independent oracles: the hand-written contact kernels of
// tests/reference/double_pendulum_beam.cpp against finite differences of their
// own Phi (element level and, through ContactConstraints, on the global
// coordinates next to element boundaries), and the named errors of a slider
// off its beam and of a dead point.
#include "runtime/coupled/contact_constraints.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <random>

#include "runtime/coupled/coordinate_partitioning.h"
#include "runtime/errors/multibody_errors.h"
#include "tests/runtime/coupled/pendulum_on_beam.h"

namespace mbfe::runtime {
namespace {

using namespace pendulum_on_beam;

// ---------------------------------------------------------------------------
// Kernels against finite differences of Phi (element fixed: the kernels are
// polynomials in xi, valid on either side of the element's ends).

struct KernelEval {
  Eigen::VectorXd phi;
  Eigen::MatrixXd jb, je;
  Eigen::VectorXd gamma;
};

KernelEval eval_kernel(const mbfe_contact_kernels_v1& k, const Eigen::Vector2d& q,
                       const Eigen::Vector4d& qe, const Eigen::Vector2d& qd,
                       const Eigen::Vector4d& qed, double s0, double le) {
  KernelEval out;
  out.phi.resize(k.rows);
  out.gamma.resize(k.rows);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> jb(k.rows, 2),
      je(k.rows, 4);
  k.phi(q.data(), qe.data(), s0, le, out.phi.data());
  k.jacobians(q.data(), qe.data(), s0, le, jb.data(), je.data());
  k.gamma(q.data(), qd.data(), qe.data(), qed.data(), s0, le, out.gamma.data());
  out.jb = jb;
  out.je = je;
  return out;
}

void check_kernels_by_fd(const mbfe_model_v1& model) {
  // Central differences, step 1e-6 on O(1) smooth functions: truncation
  // ~1e-12 x third derivative, round-off ~1e-10. gamma by the second
  // difference of Phi with step 2e-5: truncation ~4e-10 x fourth derivative
  // (w''' = O(qe / le^3) ~ 1e3 times s'^3 ~ 10), round-off ~1e-16 / 4e-10.
  constexpr double kJacTol = 1e-7;
  constexpr double kGammaTolJ = 1e-6;    // relative, from J's central difference
  constexpr double kGammaTolPhi = 1e-4;  // relative, from Phi's second difference
  const mbfe_contact_kernels_v1& k = model.contacts[0];
  const double le = 0.02;  // the model file's 1 m / 50 elements
  std::mt19937 rng(4242);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double xis[] = {0.0, 1e-9, 0.37, 1.0 - 1e-9, 1.0};
  int checked = 0;
  for (int trial = 0; trial < 120; ++trial) {
    const Eigen::Vector2d q = pendulum_angles_for_tip(0.55 + 0.25 * u(rng)) +
                              Eigen::Vector2d(0.05 * u(rng), 0.05 * u(rng));
    const Eigen::Vector4d qe(0.01 * u(rng), 0.05 * u(rng), 0.01 * u(rng), 0.05 * u(rng));
    const Eigen::Vector2d qd(2.0 * u(rng), 2.0 * u(rng));
    const Eigen::Vector4d qed(0.5 * u(rng), 2.0 * u(rng), 0.5 * u(rng), 2.0 * u(rng));
    const double s = k.position(q.data());
    const double s0 = s - xis[trial % 5] * le;
    const KernelEval e = eval_kernel(k, q, qe, qd, qed, s0, le);
    const double h = 1e-6;
    for (int j = 0; j < 2; ++j) {
      const Eigen::Vector2d dq = Eigen::Vector2d::Unit(j) * h;
      const Eigen::VectorXd fd = (eval_kernel(k, q + dq, qe, qd, qed, s0, le).phi -
                                  eval_kernel(k, q - dq, qe, qd, qed, s0, le).phi) /
                                 (2 * h);
      EXPECT_LT((e.jb.col(j) - fd).cwiseAbs().maxCoeff(), kJacTol)
          << "J_b column " << j << " at trial " << trial;
    }
    for (int j = 0; j < 4; ++j) {
      const Eigen::Vector4d dqe = Eigen::Vector4d::Unit(j) * h;
      const Eigen::VectorXd fd = (eval_kernel(k, q, qe + dqe, qd, qed, s0, le).phi -
                                  eval_kernel(k, q, qe - dqe, qd, qed, s0, le).phi) /
                                 (2 * h);
      EXPECT_LT((e.je.col(j) - fd).cwiseAbs().maxCoeff(), kJacTol)
          << "J_e column " << j << " at trial " << trial;
    }
    // gamma = -(d/dt J) [qd; qed] along the straight path x + tau [qd; qed].
    auto jv = [&](double tau) {
      const KernelEval a = eval_kernel(k, q + tau * qd, qe + tau * qed, qd, qed, s0, le);
      return Eigen::VectorXd(a.jb * qd + a.je * qed);
    };
    const double tau = 1e-6;
    const Eigen::VectorXd gamma_j = -(jv(tau) - jv(-tau)) / (2 * tau);
    EXPECT_LT((e.gamma - gamma_j).cwiseAbs().maxCoeff(),
              kGammaTolJ * (1.0 + e.gamma.cwiseAbs().maxCoeff()))
        << "gamma vs dJ/dt at trial " << trial;
    auto phi_at = [&](double tau2) {
      return eval_kernel(k, q + tau2 * qd, qe + tau2 * qed, qd, qed, s0, le).phi;
    };
    const double t2 = 2e-5;
    const Eigen::VectorXd gamma_phi = -(phi_at(t2) - 2.0 * e.phi + phi_at(-t2)) / (t2 * t2);
    EXPECT_LT((e.gamma - gamma_phi).cwiseAbs().maxCoeff(),
              kGammaTolPhi * (1.0 + e.gamma.cwiseAbs().maxCoeff()))
        << "gamma vs Phi'' at trial " << trial;
    ++checked;
  }
  EXPECT_EQ(checked, 120);
}

TEST(ContactKernels, SliderMatchesFiniteDifferences) {
  check_kernels_by_fd(*double_pendulum_beam_model());
}

TEST(ContactKernels, PinMatchesFiniteDifferences) {
  check_kernels_by_fd(*double_pendulum_beam_pin_model());
}

// Global assembly: J_b and J_c (scattered through full_to_free) against central
// differences of the stacked Phi, with the slider within 1e-9 m of a node so
// that the differences cross into the neighbouring element.
// Newton on s(q) = target, 1 m beam: converged to round-off.
constexpr double kSliderPositionTol = 1e-12;

TEST(ContactConstraints, GlobalJacobiansMatchFiniteDifferencesAtElementBoundaries) {
  // Phi is only C1 across a node (w'' jumps): central differences with step
  // 1e-7 then err by ~step x |jump of Phi''| ~ 1e-7 x O(10); a wrong column
  // mapping errs by O(1).
  constexpr double kTol = 1e-5;
  const testing::TestBeam beam = make_beam(10, true);
  const mbfe_model_v1& model = *double_pendulum_beam_model();
  ContactConstraints cc(model, {beam.beam.mesh});
  const int nc = cc.num_beam_dofs();
  const double le = beam.beam.mesh.element_length;
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    // A node near the middle of the beam, approached from either side.
    const int node = 3 + trial % 5;
    const double target = node * le + (trial % 2 ? 1e-9 : -1e-9);
    Eigen::Vector2d q = pendulum_angles_for_tip(target);
    q(1) += 0.02 * u(rng);
    // Newton on s(q) = target in q1.
    for (int it = 0; it < 20; ++it) {
      const double s = model.contacts[0].position(q.data());
      const double h = 1e-7;
      Eigen::Vector2d q2 = q;
      q2(0) += h;
      const double ds = (model.contacts[0].position(q2.data()) - s) / h;
      q(0) -= (s - target) / ds;
    }
    Eigen::VectorXd qc(nc);
    for (int i = 0; i < nc; ++i) qc(i) = 0.01 * u(rng);
    ConstraintValues cv;
    cc.evaluate(0.0, q.data(), qc.data(), nullptr, nullptr, cv);
    ASSERT_NEAR(cv.s[0], target, kSliderPositionTol);
    const Eigen::MatrixXd jc = cv.jc_dense(nc);
    const double h = 1e-7;
    auto phi = [&](const Eigen::Vector2d& qq, const Eigen::VectorXd& qqc) {
      ConstraintValues c2;
      cc.evaluate(0.0, qq.data(), qqc.data(), nullptr, nullptr, c2);
      return c2.phi;
    };
    for (int j = 0; j < 2; ++j) {
      const Eigen::Vector2d dq = Eigen::Vector2d::Unit(j) * h;
      const Eigen::VectorXd fd = (phi(q + dq, qc) - phi(q - dq, qc)) / (2 * h);
      EXPECT_LT((cv.jb.col(j) - fd).cwiseAbs().maxCoeff(), kTol) << "trial " << trial;
    }
    for (int j = 0; j < nc; ++j) {
      const Eigen::VectorXd dqc = Eigen::VectorXd::Unit(nc, j) * h;
      const Eigen::VectorXd fd = (phi(q, qc + dqc) - phi(q, qc - dqc)) / (2 * h);
      EXPECT_LT((jc.col(j) - fd).cwiseAbs().maxCoeff(), kTol)
          << "J_c column " << j << " trial " << trial;
    }
  }
}

TEST(ContactConstraints, SliderOffTheBeamNamesContactTimeAndPosition) {
  const testing::TestBeam beam = make_beam(10, true);
  const mbfe_model_v1& model = *double_pendulum_beam_model();
  ContactConstraints cc(model, {beam.beam.mesh});
  const Eigen::Vector2d q(-M_PI / 2 - 0.9, 0.0);  // stretched, tip far to the left
  Eigen::VectorXd qc = Eigen::VectorXd::Zero(cc.num_beam_dofs());
  ConstraintValues cv;
  try {
    cc.evaluate(0.125, q.data(), qc.data(), nullptr, nullptr, cv);
    ADD_FAILURE() << "expected SliderOffBeamError";
  } catch (const SliderOffBeamError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.contact(), "tip_slider");
    EXPECT_LT(e.value(), 0.0);
    EXPECT_NE(msg.find("tip_slider"), std::string::npos) << msg;
    EXPECT_NE(msg.find("t = 0.125"), std::string::npos) << msg;
    EXPECT_NE(msg.find("s = -"), std::string::npos) << msg;
  }
}

TEST(ContactConstraints, DeadPointIsASingularJacobianNamingTheContact) {
  const testing::TestBeam beam = make_beam(10, true);
  const mbfe_model_v1& model = *double_pendulum_beam_pin_model();
  ContactConstraints cc(model, {beam.beam.mesh});
  // Links aligned (q2 = 0): both columns of J_b are parallel.
  const Eigen::Vector2d q(-1.4, 0.0);
  Eigen::VectorXd qc = Eigen::VectorXd::Zero(cc.num_beam_dofs());
  ConstraintValues cv;
  cc.evaluate(0.5, q.data(), qc.data(), nullptr, nullptr, cv);
  try {
    choose_partition(cc, cv, 0.5);
    ADD_FAILURE() << "expected SingularConstraintError";
  } catch (const SingularConstraintError& e) {
    EXPECT_EQ(e.contact(), "tip_pin");
    EXPECT_NE(std::string(e.what()).find("t = 0.5"), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------------------
// Trajectories.

}  // namespace
}  // namespace mbfe::runtime
