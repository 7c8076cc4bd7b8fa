// The linearised moving-contact run (runtime/simulation/linearised_run.h)
// against oracles written here: Newmark's average-acceleration rule on the
// assembled nodal equations of a two-DOF structure and a body on a contact
// spring (the same discretisation, so agreement to round-off), with links
// and dashpots on the beam, a link going slack and taut, a body thrown
// off a unilateral contact (free flight, which Newmark integrates exactly),
// and the static compliance of a spring in series with the modes.
#include "runtime/simulation/linearised_run.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>
#include <vector>

namespace mbfe::runtime {
namespace {

// Modal and nodal forms of the same linear system, solved by different
// factorisations: round-off of forces of ~1e4 N over a few hundred steps.
constexpr double kSameDiscretisationRel = 1e-9;
// Newmark integrates a constant acceleration exactly: round-off of a
// parabola of ~0.05 m.
constexpr double kFreeFlightAbs = 1e-12;
// A static solve through a dense LU: round-off, relative.
constexpr double kStaticRel = 1e-12;

constexpr double kBodyMass = 2.0, kSpring = 4.0e4, kWeight = 50.0;

/// Two nodal DOFs with M = I and K below; mass-normalised modes and Rayleigh damping.
struct TwoDofBeam {
  Eigen::Matrix2d K;
  Eigen::MatrixXd phi;
  Eigen::Vector2d omega2;
  double alpha = 0.5, beta = 2e-5;
  TwoDofBeam() {
    K << 3.0e4, -1.0e4, -1.0e4, 9.0e4;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(K);
    phi = eig.eigenvectors();
    omega2 = eig.eigenvalues();
  }
  ModalDynamicsSet modes() const {
    ModalDynamicsSet d;
    d.m = Eigen::VectorXd::Ones(2);
    d.k = omega2;
    d.c = (alpha + beta * omega2.array()).matrix();
    d.kind.assign(2, ModalDynamicsSet::kDynamic);
    return d;
  }
};

/// The beam, one body on one contact spring (x = offset + w^T q - y), no fixed element.
LinearisedStructure structure_of(const TwoDofBeam& beam, const ElementLaw& law) {
  LinearisedStructure s;
  s.blocks.push_back({&beam.phi, 0, 0});
  s.modes = 2;
  s.dofs = 2;
  s.mass = Eigen::MatrixXd::Constant(1, 1, kBodyMass);
  s.damping = Eigen::MatrixXd::Zero(1, 1);
  s.stiffness = Eigen::MatrixXd::Zero(1, 1);
  s.contact_names = {"tyre"};
  s.contact_laws = {law};
  return s;
}

/// The grid: the contact at s(t) in [0, 1] between DOF 0 and DOF 1 (weights
/// 1 - s, s), offset(t), the body's load f(t).
template <class S, class O, class F>
LinearisedExcitation excitation_of(double step, int steps, S s_of, O offset_of, F load_of) {
  LinearisedExcitation x;
  x.step = step;
  x.steps = steps;
  x.constant_load = Eigen::VectorXd::Zero(2);
  x.geometry.resize(static_cast<std::size_t>(steps) + 1);
  x.rigid_gradients = Eigen::MatrixXd::Constant(1, steps + 1, -1.0);
  x.rigid_loads.resize(1, steps + 1);
  for (int k = 0; k <= steps; ++k) {
    const double t = k * step, s = s_of(t);
    ContactGeometry& g = x.geometry[static_cast<std::size_t>(k)];
    g.active = true;
    g.dofs[0] = 0;
    g.dofs[1] = 1;
    g.weights[0] = 1.0 - s;
    g.weights[1] = s;
    g.offset = offset_of(t);
    x.rigid_loads(0, k) = load_of(t);
  }
  return x;
}

/// The oracle: Newmark's average acceleration on u = [q0, q1, y] with the
/// contact's spring assembled into K(t) (a linear bilateral law, damping
/// only where its place is fixed) and the fixed elements' springs and
/// dashpots into K and C, from the static equilibrium at t = 0. A fixed
/// element with no_pull is assembled while its force k x + c x' is not
/// negative: each step is solved with the last step's set and re-solved
/// with an element switched until the set agrees with the forces.
/// Returns the contact force at every step.
std::vector<double> nodal_newmark(const TwoDofBeam& beam, const ElementLaw& law, const LinearisedExcitation& x,
                                  const std::vector<FixedElement>& fixed = {}) {
  const double h = x.step;
  const auto g_of = [&](int k) {
    const ContactGeometry& g = x.geometry[static_cast<std::size_t>(k)];
    Eigen::Vector3d v(g.weights[0], g.weights[1], -1.0);
    return v;
  };
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero(), Cs = Eigen::Matrix3d::Zero(), Ks = Eigen::Matrix3d::Zero();
  M.topLeftCorner<2, 2>().setIdentity();
  M(2, 2) = kBodyMass;
  Ks.topLeftCorner<2, 2>() = beam.K;
  Cs.topLeftCorner<2, 2>() = beam.alpha * Eigen::Matrix2d::Identity() + beam.beta * beam.K;
  std::vector<Eigen::Vector3d> w(fixed.size(), Eigen::Vector3d::Zero());
  for (std::size_t e = 0; e < fixed.size(); ++e)
    for (const auto& [dof, weight] : fixed[e].dofs) w[e][dof] += weight;
  std::vector<bool> on(fixed.size(), true);
  const auto system = [&](int k, Eigen::Matrix3d& K, Eigen::Matrix3d& C, Eigen::Vector3d& f) {
    const Eigen::Vector3d g = g_of(k);
    const double off = x.geometry[static_cast<std::size_t>(k)].offset;
    K = Ks + law.stiffness * g * g.transpose();
    C = Cs + law.damping * g * g.transpose();
    f = -law.stiffness * off * g;
    for (std::size_t e = 0; e < fixed.size(); ++e) {
      if (!on[e]) continue;
      K += fixed[e].law.stiffness * w[e] * w[e].transpose();
      C += fixed[e].law.damping * w[e] * w[e].transpose();
      f -= fixed[e].law.stiffness * fixed[e].offset * w[e];
    }
    f[2] += x.rigid_loads(0, k);
  };
  // The elements whose on-state disagrees with their force at (u, v): switched; true when none.
  const auto agree = [&](const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
    bool same = true;
    for (std::size_t e = 0; e < fixed.size(); ++e) {
      if (!fixed[e].law.no_pull) continue;
      const ElementLaw& l = fixed[e].law;
      const double force = l.stiffness * (fixed[e].offset + w[e].dot(u)) + l.damping * w[e].dot(v);
      if ((force < 0.0) == on[e]) {
        on[e] = !on[e];
        same = false;
      }
    }
    return same;
  };
  Eigen::Matrix3d K, C;
  Eigen::Vector3d f;
  system(0, K, C, f);
  Eigen::Vector3d u = K.partialPivLu().solve(f), v = Eigen::Vector3d::Zero(), a = Eigen::Vector3d::Zero();
  std::vector<double> force{law.stiffness * (x.geometry[0].offset + g_of(0).dot(u))};
  for (int k = 1; k <= x.steps; ++k) {
    Eigen::Vector3d u1, v1;
    for (int pass = 0; pass < 10; ++pass) {
      system(k, K, C, f);
      const Eigen::Matrix3d A = K + (2.0 / h) * C + (4.0 / (h * h)) * M;
      const Eigen::Vector3d rhs = f + M * ((4.0 / (h * h)) * u + (4.0 / h) * v + a) + C * ((2.0 / h) * u + v);
      u1 = A.partialPivLu().solve(rhs);
      v1 = (2.0 / h) * (u1 - u) - v;
      if (agree(u1, v1)) break;
    }
    a = (4.0 / (h * h)) * (u1 - u) - (4.0 / h) * v - a;
    u = u1;
    v = v1;
    const Eigen::Vector3d g = g_of(k);
    force.push_back(law.stiffness * (x.geometry[static_cast<std::size_t>(k)].offset + g.dot(u)) +
                    law.damping * g.dot(v));
  }
  return force;
}

/// max_k |a[k] - b[k]| over the shorter of the two.
double largest_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (std::size_t k = 0; k < a.size() && k < b.size(); ++k) d = std::max(d, std::abs(a[k] - b[k]));
  return d;
}

double peak(const std::vector<double>& f) {
  double p = 0.0;
  for (double v : f) p = std::max(p, std::abs(v));
  return p;
}

TEST(LinearisedRun, ABodyOnADampedSpringOverTheModesIsNewmarkOnTheNodalEquations) {
  const TwoDofBeam beam;
  ElementLaw law;
  law.stiffness = kSpring;
  law.damping = 30.0;
  // Fixed place (s = 0.3), the body's weight and a harmonic push at 90 rad/s.
  const LinearisedExcitation x = excitation_of(
      1e-3, 400, [](double) { return 0.3; }, [](double) { return 0.0; },
      [](double t) { return -kWeight - 20.0 * std::sin(90.0 * t); });
  const LinearisedStructure s = structure_of(beam, law);
  const LinearisedHistory run = run_linearised(s, beam.modes(), x, LinearisedStart{});
  const std::vector<double> oracle = nodal_newmark(beam, law, x);
  ASSERT_EQ(run.force.size(), 1u);
  ASSERT_EQ(run.force[0].size(), oracle.size());
  EXPECT_EQ(run.unconverged_steps, 0);
  EXPECT_NEAR(run.force[0][0], kWeight, kSameDiscretisationRel * kWeight);  // the static start carries the weight
  const double scale = peak(oracle);
  EXPECT_GT(scale, 1.2 * kWeight);  // the push is felt
  for (std::size_t k = 0; k < oracle.size(); ++k)
    ASSERT_NEAR(run.force[0][k], oracle[k], kSameDiscretisationRel * scale) << "step " << k;
}

TEST(LinearisedRun, AContactMovingAcrossTheDofsIsNewmarkWithTheSpringWhereItIsAtEachStep) {
  const TwoDofBeam beam;
  ElementLaw law;
  law.stiffness = kSpring;
  // The contact crosses from DOF 0 to DOF 1 and back over a bump in its path.
  const LinearisedExcitation x = excitation_of(
      5e-4, 800, [](double t) { return 0.5 - 0.5 * std::cos(15.0 * t); },
      [](double t) { return 1e-3 * std::sin(40.0 * t); }, [](double) { return -kWeight; });
  const LinearisedHistory run = run_linearised(structure_of(beam, law), beam.modes(), x, LinearisedStart{});
  const std::vector<double> oracle = nodal_newmark(beam, law, x);
  const double scale = peak(oracle);
  for (std::size_t k = 0; k < oracle.size(); ++k)
    ASSERT_NEAR(run.force[0][k], oracle[k], kSameDiscretisationRel * scale) << "step " << k;
}

/// A link from both DOFs to the ground, preloaded (offset), and a dashpot on
/// DOF 0, as a catenary's droppers and its discrete parts' dashpots are.
std::vector<FixedElement> link_and_dashpot(bool link_slack) {
  FixedElement link{"link", {{0, 0.4}, {1, 0.6}}, 2e-3, ElementLaw{}};
  link.law.stiffness = 2.0e4;
  link.law.damping = 15.0;
  link.law.no_pull = link_slack;
  FixedElement dashpot{"dashpot", {{0, 1.0}}, 0.0, ElementLaw{}};
  dashpot.law.damping = 40.0;
  return {link, dashpot};
}

TEST(LinearisedRun, FixedElementsBesideAMovingContactAreNewmarkWithTheirSpringsAndDashpotsAssembled) {
  const TwoDofBeam beam;
  ElementLaw law;
  law.stiffness = kSpring;  // no damper: the oracle assembles a damper only where its place is fixed
  const LinearisedExcitation x = excitation_of(
      5e-4, 800, [](double t) { return 0.5 - 0.5 * std::cos(15.0 * t); },
      [](double t) { return 1e-3 * std::sin(40.0 * t); }, [](double) { return -kWeight; });
  LinearisedStructure s = structure_of(beam, law);
  s.fixed = link_and_dashpot(false);
  const LinearisedHistory run = run_linearised(s, beam.modes(), x, LinearisedStart{});
  const std::vector<double> oracle = nodal_newmark(beam, law, x, link_and_dashpot(false));
  EXPECT_EQ(run.unconverged_steps, 0);
  const double scale = peak(oracle);
  for (std::size_t k = 0; k < oracle.size(); ++k)
    ASSERT_NEAR(run.force[0][k], oracle[k], kSameDiscretisationRel * scale) << "step " << k;
  // The fixed elements change the answer (they are not ignored).
  EXPECT_GT(largest_difference(nodal_newmark(beam, law, x), oracle), 1e-3 * scale);
}

TEST(LinearisedRun, ALinkThatGoesSlackIsNewmarkWithTheLinkAssembledWhileItPulls) {
  // A push near the body's bounce makes the preloaded link go slack and
  // come back, so the fixed elements' block is refactored both ways.
  const TwoDofBeam beam;
  ElementLaw law;
  law.stiffness = kSpring;
  const LinearisedExcitation x = excitation_of(
      2e-4, 1500, [](double) { return 0.5; }, [](double) { return 0.0; },
      [](double t) { return -kWeight - 400.0 * std::sin(140.0 * t); });
  LinearisedStructure s = structure_of(beam, law);
  s.fixed = link_and_dashpot(true);
  const LinearisedHistory run = run_linearised(s, beam.modes(), x, LinearisedStart{});
  const std::vector<double> oracle = nodal_newmark(beam, law, x, link_and_dashpot(true));
  EXPECT_EQ(run.unconverged_steps, 0);
  const double scale = peak(oracle);
  for (std::size_t k = 0; k < oracle.size(); ++k)
    ASSERT_NEAR(run.force[0][k], oracle[k], kSameDiscretisationRel * scale) << "step " << k;
  // The link did go slack: a bilateral link gives another history.
  EXPECT_GT(largest_difference(nodal_newmark(beam, law, x, link_and_dashpot(false)), oracle), 1e-2 * scale);
}

TEST(LinearisedRun, ABodyThrownOffAUnilateralContactFliesFreelyAndLandsWithoutPulling) {
  const TwoDofBeam beam;
  ElementLaw law;
  law.stiffness = kSpring;
  law.compression_only = law.no_pull = true;
  const double g = kWeight / kBodyMass, speed = 0.5, flight = 2.0 * speed / g;  // 0.04 s
  const double h = 1e-4;
  const LinearisedExcitation x = excitation_of(
      h, 800, [](double) { return 0.5; }, [](double) { return 0.0; }, [](double) { return -kWeight; });
  LinearisedStart start;
  start.static_start = false;
  start.eta = start.eta_dot = Eigen::VectorXd::Zero(2);
  start.y = Eigen::VectorXd::Zero(1);
  start.y_dot = Eigen::VectorXd::Constant(1, speed);  // upward, off the contact
  const LinearisedHistory run = run_linearised(structure_of(beam, law), beam.modes(), x, start);
  bool landed = false;
  for (int k = 1; k <= x.steps; ++k) {
    const double t = k * h, f = run.force[0][static_cast<std::size_t>(k)];
    ASSERT_GE(f, 0.0) << "a unilateral contact pulled at step " << k;
    if (t < flight - h) {
      // Apart: no force, the beam at rest, the body on its parabola.
      ASSERT_EQ(f, 0.0) << "step " << k;
      ASSERT_NEAR(run.compression[0][static_cast<std::size_t>(k)], -(speed * t - 0.5 * g * t * t), kFreeFlightAbs)
          << "step " << k;
    }
    landed = landed || f > 0.0;
  }
  EXPECT_TRUE(landed);
}

TEST(LinearisedRun, QuasiStaticModesCarryTheStaticCompliance) {
  // The body's weight on the spring in series with the beam at s = 0.3:
  // force W, compression W / k_s, both held at rest whatever the modes' kind.
  const TwoDofBeam beam;
  ElementLaw law;
  law.stiffness = kSpring;
  const LinearisedExcitation x = excitation_of(
      1e-3, 50, [](double) { return 0.3; }, [](double) { return 0.0; }, [](double) { return -kWeight; });
  ModalDynamicsSet modes = beam.modes();
  modes.kind[1] = ModalDynamicsSet::kQuasiStatic;
  const LinearisedHistory run = run_linearised(structure_of(beam, law), modes, x, LinearisedStart{});
  for (int k = 0; k <= x.steps; ++k) {
    ASSERT_NEAR(run.force[0][static_cast<std::size_t>(k)], kWeight, kStaticRel * kWeight) << "step " << k;
    ASSERT_NEAR(run.compression[0][static_cast<std::size_t>(k)], kWeight / kSpring, kStaticRel * kWeight / kSpring);
  }
  // An absent mode (policy truncate) stiffens the structure, not the spring:
  // the force is still the weight.
  modes.kind[1] = ModalDynamicsSet::kAbsent;
  const LinearisedHistory stiff = run_linearised(structure_of(beam, law), modes, x, LinearisedStart{});
  EXPECT_NEAR(stiff.force[0][0], kWeight, kStaticRel * kWeight);
}

TEST(LinearisedRun, SizesThatDoNotFitAreRefused) {
  const TwoDofBeam beam;
  ElementLaw law;
  law.stiffness = kSpring;
  LinearisedExcitation x = excitation_of(
      1e-3, 10, [](double) { return 0.3; }, [](double) { return 0.0; }, [](double) { return -kWeight; });
  ModalDynamicsSet modes = beam.modes();
  modes.kind.pop_back();
  EXPECT_THROW(run_linearised(structure_of(beam, law), modes, x, LinearisedStart{}), std::invalid_argument);
  x.geometry.pop_back();
  EXPECT_THROW(run_linearised(structure_of(beam, law), beam.modes(), x, LinearisedStart{}), std::invalid_argument);
}

TEST(LinearisedRun, ABodyHeldByNothingIsASingularStart) {
  const TwoDofBeam beam;
  ElementLaw law;
  law.stiffness = kSpring;
  law.compression_only = law.no_pull = true;
  // The contact 1 m apart: nothing holds the body under its weight.
  const LinearisedExcitation x = excitation_of(
      1e-3, 10, [](double) { return 0.3; }, [](double) { return -1.0; }, [](double) { return -kWeight; });
  EXPECT_THROW(run_linearised(structure_of(beam, law), beam.modes(), x, LinearisedStart{}), std::runtime_error);
}

}  // namespace
}  // namespace mbfe::runtime
