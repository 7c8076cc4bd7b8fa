// The coupled rigid + beam system (the double pendulum on a beam) against
// independent oracles: partitioned against augmented trajectories, |Phi|
// along the partitioned one, energy conservation with damping off (the
// contacts do no work), an adjusted structure over every mode, the Newton start, and
// the named error of a failed closure.
#include "runtime/coupled/augmented_system.h"
#include "runtime/coupled/coordinate_partitioning.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <iostream>
#include <memory>
#include <random>

#include "runtime/errors/multibody_errors.h"
#include "tests/runtime/coupled/pendulum_on_beam.h"

namespace mbfe::runtime {
namespace {

using namespace pendulum_on_beam;


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

// The two formulations solve the same linear system in other orders; the partitioned one also closes Phi to 1e-10 m.
constexpr double kFormulationForceRel = 1e-9;
// The beam as an adjusted structure over every mode (eq (27)) with its own
// Rayleigh modal values is the beam itself: same right-hand side as its
// sparse C and K.
/// `m_scale` != 1 gives the structure another M than the beam's.
std::shared_ptr<CoupledDynamics> every_mode_dynamics(const testing::TestBeam& beam, double m_scale = 1.0) {
  const Eigen::MatrixXd M(beam.beam.M), K(beam.K), C(beam.C);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M);
  const int n = static_cast<int>(M.rows());
  LowRankStructure::Parts p;
  p.name = beam.beam.mesh.name;
  p.ranges = {{0, n}};
  p.M = beam.beam.M * m_scale;
  p.K = beam.K;
  p.P = beam.beam.P;
  p.phi = eig.eigenvectors();
  p.k = eig.eigenvalues();
  p.mass = {1.0, Eigen::VectorXd::Zero(n)};
  p.damping = {0.0, (eig.eigenvectors().transpose() * C * eig.eigenvectors()).diagonal()};
  p.stiffness = {0.0, eig.eigenvalues()};
  p.every_mode = true;
  CoupledBeams beams;
  beams.beams.push_back(beam.beam);
  beams.beams.back().structure = 0;
  beams.structures.push_back(std::make_shared<const LowRankStructure>(p));
  return std::make_shared<CoupledDynamics>(
      std::make_shared<const CoupledModel>(*double_pendulum_beam_model(), std::move(beams)));
}

TEST(CoupledSystem, EveryModeStructureIsTheBeamItself) {
  const testing::TestBeam beam = make_beam(6, true);
  PartitionedSystem a(make_dynamics(*double_pendulum_beam_model(), beam));
  PartitionedSystem b(every_mode_dynamics(beam));
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
  // The beam is a structure of its own on its M: one factorisation of M,
  // the structure's, serves both (not a second one of the same matrix).
  const std::shared_ptr<CoupledDynamics> one = every_mode_dynamics(beam);
  EXPECT_EQ(&one->model().mass_factor(0), &one->model().structures()[0]->base_factor());
  // A structure on another M than the beam's: the beam factors its own.
  const std::shared_ptr<CoupledDynamics> other = every_mode_dynamics(beam, 2.0);
  EXPECT_NE(&other->model().mass_factor(0), &other->model().structures()[0]->base_factor());
  EXPECT_EQ(other->model().mass_factor(0).rows(), beam.beam.M.rows());
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
