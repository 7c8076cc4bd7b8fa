// The coupled rigid + beam system against independent oracles:
// - the hand-written contact kernels of tests/reference/double_pendulum_beam.cpp
//   against finite differences of their own Phi (element level and, through
//   ContactConstraints, on the global coordinates next to element boundaries);
// - partitioned against augmented trajectories, |Phi| along the partitioned one;
// - energy conservation with damping off (the contacts do no work);
// - the named errors.
#include "runtime/multibody/augmented_system.h"
#include "runtime/multibody/coordinate_partitioning.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <random>

#include "runtime/multibody/multibody_errors.h"
#include "tests/reference/double_pendulum_beam.h"
#include "tests/runtime/multibody/test_beam.h"

namespace mbfe::runtime {
namespace {

using reference::double_pendulum_beam_model;
using reference::double_pendulum_beam_params;
using reference::double_pendulum_beam_pin_model;

testing::TestBeam make_beam(int elements, bool damping) {
  const reference::DoublePendulumBeamParams& p = double_pendulum_beam_params();
  const double a = p.beam_side;
  const double EI = p.youngs_modulus * a * a * a * a / 12.0;
  const double rhoA = p.density * a * a;
  // Own weight on the transverse direction n = (0, 1) of a beam along x.
  const double qg = rhoA * p.pendulum.gravity.y();
  return testing::pinned_pinned_beam("beam1", p.beam_length, elements, EI, rhoA, qg,
                                     damping ? p.rayleigh_alpha : 0.0,
                                     damping ? p.rayleigh_beta : 0.0);
}

std::shared_ptr<CoupledDynamics> make_dynamics(const mbfe_model_v1& model,
                                               const testing::TestBeam& beam) {
  return std::make_shared<CoupledDynamics>(model, std::vector<CoupledBeam>{beam.beam});
}

// Tip of the pendulum placed at (x, 0) with the knee to the right.
Eigen::Vector2d pendulum_angles_for_tip(double x) {
  const reference::DoublePendulumBeamParams& p = double_pendulum_beam_params();
  const Eigen::Vector2d d = Eigen::Vector2d(x, 0.0) - p.pendulum.hinge;
  const double phi = std::atan2(d.y(), d.x());
  const double b = std::acos(d.norm() / (2.0 * p.pendulum.l1));  // l1 == l2
  return {phi + b, -2.0 * b};
}

void rk4_step(OdeSystem& sys, double t, double h, Eigen::VectorXd& y) {
  Eigen::VectorXd k1, k2, k3, k4;
  sys.rhs(t, y, k1);
  sys.rhs(t + h / 2, y + h / 2 * k1, k2);
  sys.rhs(t + h / 2, y + h / 2 * k2, k3);
  sys.rhs(t + h, y + h * k3, k4);
  y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  sys.after_step(t + h, y);
}

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
// The two formulations solve the same linear system in other orders; the partitioned one also closes Phi to 1e-10 m.
constexpr double kFormulationForceRel = 1e-9;

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

struct Energy {
  const testing::TestBeam& beam;
  double operator()(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const {
    const reference::DoublePendulumParams& p = double_pendulum_beam_params().pendulum;
    const Eigen::Vector2d qb = q.head<2>(), qbd = qd.head<2>();
    const int nc = static_cast<int>(q.size()) - 2;
    const Eigen::VectorXd qc = q.tail(nc), qcd = qd.tail(nc);
    return 0.5 * qbd.dot(reference::mass_matrix(p, qb) * qbd) +
           reference::potential_energy(p, qb) + 0.5 * qcd.dot(beam.beam.M * qcd) +
           0.5 * qc.dot(beam.K * qc) - beam.beam.P.dot(qc);
  }
};

struct RunResult {
  double max_dq = 0.0;        // max over the run of |q_partitioned - q_augmented|
  double max_phi_part = 0.0;  // m
  double max_phi_aug = 0.0;   // m
  double energy_drift = 0.0;  // relative, partitioned
  int repartitions = 0;
  Eigen::VectorXd q_end;
};

RunResult run_both(const mbfe_model_v1& model, const testing::TestBeam& beam,
             const Eigen::VectorXd& q0, const Eigen::VectorXd& qd0, double h, int steps,
             PartitionOptions popt = {}, bool with_augmented = true) {
  auto dyn_p = make_dynamics(model, beam);
  auto dyn_a = make_dynamics(model, beam);
  PartitionedSystem part(dyn_p, popt);
  AugmentedSystem aug(dyn_a);
  Eigen::VectorXd yp = part.initial_state(0.0, q0, qd0);
  Eigen::VectorXd q, qd, qa, qda;
  part.full_state(0.0, yp, q, qd);
  Eigen::VectorXd ya = aug.initial_state(0.0, q, qd);  // the same consistent start
  const Energy energy{beam};
  const double e0 = energy(q, qd);
  RunResult r;
  for (int i = 0; i < steps; ++i) {
    const double t = i * h;
    rk4_step(part, t, h, yp);
    part.full_state(t + h, yp, q, qd);
    ConstraintValues cv;
    dyn_p->constraints().evaluate(t + h, q.data(), q.data() + 2, nullptr, nullptr, cv);
    r.max_phi_part = std::max(r.max_phi_part, cv.phi.cwiseAbs().maxCoeff());
    if (with_augmented) {
      rk4_step(aug, t, h, ya);
      aug.full_state(t + h, ya, qa, qda);
      r.max_dq = std::max(r.max_dq, (q - qa).cwiseAbs().maxCoeff());
      dyn_a->constraints().evaluate(t + h, qa.data(), qa.data() + 2, nullptr, nullptr, cv);
      r.max_phi_aug = std::max(r.max_phi_aug, cv.phi.cwiseAbs().maxCoeff());
    }
    r.energy_drift = std::max(r.energy_drift, std::abs(energy(q, qd) - e0) / std::abs(e0));
  }
  r.repartitions = part.repartitions();
  r.q_end = q;
  std::cout << "[ info     ] " << model.model_name << ": max|q_part - q_aug| = " << r.max_dq
            << ", max|Phi| partitioned = " << r.max_phi_part
            << " m, augmented = " << r.max_phi_aug << " m, energy drift = " << r.energy_drift
            << ", repartitions = " << r.repartitions << "\n";
  return r;
}

Eigen::VectorXd full_q(const Eigen::Vector2d& qb, int nc) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(2 + nc);
  q.head<2>() = qb;
  return q;
}

// RK4 at h = 2e-5 s resolves the coarse beam's highest mode (omega h < 0.3):
// both formulations integrate the same motion to ~1e-9; their difference is
// dominated by the augmented run's constraint drift.
constexpr double kAgreeTol = 1e-7;   // m or rad, over the run
constexpr double kPhiTol = 1e-10;    // m, the closure tolerance
constexpr double kEnergyTol = 1e-6;  // relative, over 1 s (the bound)

TEST(CoupledSystem, SliderPartitionedAgreesWithAugmented) {
  const testing::TestBeam beam = make_beam(6, true);
  const int nc = beam.beam.mesh.num_free;
  const Eigen::VectorXd q0 = full_q(double_pendulum_beam_params().q0, nc);
  const Eigen::VectorXd qd0 = Eigen::VectorXd::Zero(2 + nc);
  const RunResult r = run_both(*double_pendulum_beam_model(), beam, q0, qd0, 2e-5, 10000);
  EXPECT_LT(r.max_dq, kAgreeTol);
  EXPECT_LT(r.max_phi_part, kPhiTol);
  EXPECT_GT(r.max_phi_aug, 0.0);  // drift exists and is reported, not hidden
  EXPECT_GT((r.q_end - q0).head(2).norm(), 0.02);  // the pendulum moved
}

TEST(CoupledSystem, PinPartitionedAgreesWithAugmented) {
  const testing::TestBeam beam = make_beam(6, true);
  const int nc = beam.beam.mesh.num_free;
  const Eigen::VectorXd q0 = full_q(pendulum_angles_for_tip(reference::kPinAt), nc);
  Eigen::VectorXd qd0 = Eigen::VectorXd::Zero(2 + nc);
  const RunResult r = run_both(*double_pendulum_beam_pin_model(), beam, q0, qd0, 2e-5, 10000);
  EXPECT_LT(r.max_dq, kAgreeTol);
  EXPECT_LT(r.max_phi_part, kPhiTol);
  EXPECT_GT((r.q_end - q0).tail(nc).norm(), 1e-4);  // the beam sagged under the load
}

TEST(CoupledSystem, RepartitionKeepsTheTrajectory) {
  const testing::TestBeam beam = make_beam(6, true);
  const int nc = beam.beam.mesh.num_free;
  const Eigen::VectorXd q0 = full_q(double_pendulum_beam_params().q0, nc);
  const Eigen::VectorXd qd0 = Eigen::VectorXd::Zero(2 + nc);
  // Start from the worse of the two choices: the first after_step must switch.
  ContactConstraints cc(*double_pendulum_beam_model(), {beam.beam.mesh});
  ConstraintValues cv;
  cc.evaluate(0.0, q0.data(), q0.data() + 2, nullptr, nullptr, cv);
  const Partition best = choose_partition(cc, cv, 0.0);
  ASSERT_EQ(best.dependent.size(), 1u);
  PartitionOptions opt;
  opt.initial_dependent = {1 - best.dependent[0]};
  opt.repartition_ratio = 0.999;  // switch as soon as the other choice is better
  const RunResult r = run_both(*double_pendulum_beam_model(), beam, q0, qd0, 2e-5, 10000, opt);
  EXPECT_GT(r.repartitions, 0);
  EXPECT_LT(r.max_dq, kAgreeTol);
  EXPECT_LT(r.max_phi_part, kPhiTol);
}

TEST(CoupledSystem, EnergyIsConservedWithoutDamping) {
  const testing::TestBeam beam = make_beam(6, false);
  const int nc = beam.beam.mesh.num_free;
  {
    const Eigen::VectorXd q0 = full_q(double_pendulum_beam_params().q0, nc);
    const RunResult r = run_both(*double_pendulum_beam_model(), beam, q0,
                                 Eigen::VectorXd::Zero(2 + nc), 1e-4, 10000, {}, false);
    EXPECT_LT(r.energy_drift, kEnergyTol) << "slider";
  }
  {
    const Eigen::VectorXd q0 = full_q(pendulum_angles_for_tip(reference::kPinAt), nc);
    const RunResult r = run_both(*double_pendulum_beam_pin_model(), beam, q0,
                                 Eigen::VectorXd::Zero(2 + nc), 1e-4, 10000, {}, false);
    EXPECT_LT(r.energy_drift, kEnergyTol) << "pin";
  }
}

TEST(CoupledSystem, DenseAdjustedOperatorsPlugInUnchanged) {
  const testing::TestBeam beam = make_beam(6, true);
  testing::TestBeam dense = beam;
  dense.beam.force = dense_beam_force(Eigen::MatrixXd(beam.C), Eigen::MatrixXd(beam.K));
  PartitionedSystem a(make_dynamics(*double_pendulum_beam_model(), beam));
  PartitionedSystem b(make_dynamics(*double_pendulum_beam_model(), dense));
  const int nc = beam.beam.mesh.num_free;
  Eigen::VectorXd q0 = full_q(double_pendulum_beam_params().q0, nc);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1e-3, 1e-3);
  for (int i = 0; i < nc; ++i) q0(2 + i) = u(rng);
  Eigen::VectorXd qd0 = Eigen::VectorXd::Zero(2 + nc);
  for (int i = 0; i < 2 + nc; ++i) qd0(i) = 100 * u(rng);
  const Eigen::VectorXd ya = a.initial_state(0.0, q0, qd0);
  const Eigen::VectorXd yb = b.initial_state(0.0, q0, qd0);
  Eigen::VectorXd da, db;
  a.rhs(0.0, ya, da);
  b.rhs(0.0, yb, db);
  EXPECT_LT((da - db).cwiseAbs().maxCoeff(), 1e-9 * da.cwiseAbs().maxCoeff());
  // Multipliers agree between the formulations at the same state.
  AugmentedSystem aug(make_dynamics(*double_pendulum_beam_model(), beam));
  Eigen::VectorXd q, qd;
  a.full_state(0.0, ya, q, qd);
  const ContactReport ra = a.report(0.0, ya);
  const ContactReport rb = aug.report(0.0, aug.initial_state(0.0, q, qd));
  ASSERT_EQ(ra.lambda.size(), 1);
  EXPECT_NEAR(ra.lambda(0), rb.lambda(0), kFormulationForceRel * std::abs(rb.lambda(0)));
  EXPECT_LT(ra.phi_max, kPhiTol);
}

// The closure starts from the last v extrapolated with its v' (error O(h^2)),
// so at a small step one Newton update reaches round-off; from the last v
// alone (error O(h)) it took two. Counted, not timed.
TEST(CoupledSystem, ExtrapolatedNewtonStartNeedsOneIteration) {
  const testing::TestBeam beam = make_beam(6, true);
  PartitionedSystem sys(make_dynamics(*double_pendulum_beam_model(), beam));
  const int nc = beam.beam.mesh.num_free;
  const Eigen::VectorXd q0 = full_q(double_pendulum_beam_params().q0, nc);
  Eigen::VectorXd y = sys.initial_state(0.0, q0, Eigen::VectorXd::Zero(2 + nc));
  Eigen::VectorXd ydot;
  const double h = 1e-5;
  int most = 0;
  for (int i = 0; i < 2000; ++i) {  // forward Euler: rhs at the closed state, then after_step
    sys.rhs(i * h, y, ydot);
    y += h * ydot;
    sys.after_step((i + 1) * h, y);
    if (i >= 10) most = std::max(most, sys.last_newton_iterations());  // v' known by then
  }
  Eigen::VectorXd q, qd;
  sys.full_state(2000 * h, y, q, qd);
  EXPECT_GT(qd.head(2).norm(), 0.05);  // the pendulum swings: v moves every step
  EXPECT_EQ(most, 1);
}

TEST(CoupledSystem, NewtonClosureFailureNamesTheContact) {
  const testing::TestBeam beam = make_beam(6, true);
  PartitionOptions opt;
  opt.max_newton = 1;  // one iteration from a 0.1 rad error cannot reach 1e-10 m
  PartitionedSystem sys(make_dynamics(*double_pendulum_beam_model(), beam), opt);
  const int nc = beam.beam.mesh.num_free;
  Eigen::VectorXd q0 = full_q(double_pendulum_beam_params().q0, nc);
  q0(0) += 0.1;
  q0(1) += 0.1;
  try {
    sys.initial_state(0.75, q0, Eigen::VectorXd::Zero(2 + nc));
    ADD_FAILURE() << "expected NewtonClosureError";
  } catch (const NewtonClosureError& e) {
    EXPECT_EQ(e.contact(), "tip_slider");
    EXPECT_GT(e.value(), 1e-10);
    EXPECT_NE(std::string(e.what()).find("t = 0.75"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mbfe::runtime
