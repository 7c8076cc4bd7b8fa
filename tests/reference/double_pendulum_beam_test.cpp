// The hand-coded reference of models/double_pendulum_beam.yaml: its numbers
// against the model file, and (when the generated solver is linked) the
// generated M, F, Q and contact kernels against it at random states.
#include "tests/reference/double_pendulum_beam.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "frontend/parse_model.h"

#ifdef MBFE_HAVE_GENERATED_DOUBLE_PENDULUM_BEAM
extern "C" const mbfe_model_v1* mbfe_model_double_pendulum_beam(void);
#endif

namespace mbfe::reference {
namespace {

// The model file writes m l^2 / 12 as a decimal; the reference computes it.
constexpr double kInertiaTol = 1e-15;

TEST(DoublePendulumBeamReference, NumbersMatchTheModelFile) {
  const ir::Model m = frontend::load_model_file(std::string(MBFE_SOURCE_DIR) +
                                                "/models/double_pendulum_beam.yaml");
  const DoublePendulumBeamParams& p = double_pendulum_beam_params();
  ASSERT_EQ(m.bodies.size(), 2u);
  ASSERT_EQ(m.beams.size(), 1u);
  ASSERT_EQ(m.contacts.size(), 1u);
  const ir::Body& b1 = m.bodies[0];
  const ir::Body& b2 = m.bodies[1];
  EXPECT_EQ(b1.joint.at[0], p.pendulum.hinge.x());
  EXPECT_EQ(b1.joint.at[1], p.pendulum.hinge.y());
  EXPECT_EQ(b2.joint.at[0], p.pendulum.l1);
  EXPECT_EQ(b1.mass, p.pendulum.m1);
  EXPECT_EQ(b2.mass, p.pendulum.m2);
  EXPECT_NEAR(b1.inertia, p.pendulum.I1, kInertiaTol);
  EXPECT_NEAR(b2.inertia, p.pendulum.I2, kInertiaTol);
  EXPECT_EQ(b1.com[0], p.pendulum.c1);
  EXPECT_EQ(b2.com[0], p.pendulum.c2);
  const ir::Contact& c = m.contacts[0];
  EXPECT_EQ(c.name, "tip_slider");
  EXPECT_EQ(c.type, ir::ContactType::kSliderPin);
  EXPECT_EQ(c.body, 1);
  EXPECT_EQ(b2.points.at(c.point).position[0], p.l2);
  const ir::Beam& beam = m.beams[0];
  EXPECT_EQ(beam.length, p.beam_length);
  EXPECT_EQ(beam.elements, p.beam_elements);
  EXPECT_EQ(beam.angle, p.beam_angle);
  EXPECT_EQ(beam.origin[0], p.beam_origin.x());
  EXPECT_EQ(beam.rayleigh_alpha, p.rayleigh_alpha);
  EXPECT_EQ(beam.rayleigh_beta, p.rayleigh_beta);
  EXPECT_EQ(m.gravity[1], p.pendulum.gravity.y());
  ASSERT_EQ(m.initial.q.size(), 2u);
  EXPECT_EQ(m.initial.q[0], p.q0(0));
  EXPECT_EQ(m.initial.q[1], p.q0(1));
  // The initial tip lies on the undeformed beam.
  double phi = 0.0;
  const double qe[4] = {0, 0, 0, 0};
  double_pendulum_beam_model()->contacts[0].phi(p.q0.data(), qe, 0.0, 0.02, &phi);
  EXPECT_LT(std::abs(phi), 1e-15);
}

#ifdef MBFE_HAVE_GENERATED_DOUBLE_PENDULUM_BEAM

// Both sides evaluate closed forms in double precision in different orders;
// the bound for generated versus hand-coded contact kernels.
constexpr double kRelTol = 1e-10;

double rel_err(const double* got, const double* want, int n) {
  double err = 0.0, scale = 1e-300;
  for (int i = 0; i < n; ++i) {
    err = std::max(err, std::abs(got[i] - want[i]));
    scale = std::max(scale, std::abs(want[i]));
  }
  return err / scale;
}

TEST(DoublePendulumBeamGenerated, MatchesReferenceAtRandomStates) {
  const mbfe_model_v1& gen = *mbfe_model_double_pendulum_beam();
  const mbfe_model_v1& ref = *double_pendulum_beam_model();
  ASSERT_EQ(gen.num_coordinates, 2);
  ASSERT_EQ(gen.num_contacts, 1);
  const mbfe_contact_kernels_v1& kg = gen.contacts[0];
  const mbfe_contact_kernels_v1& kr = ref.contacts[0];
  EXPECT_EQ(kg.type, kr.type);
  EXPECT_EQ(kg.rows, kr.rows);
  EXPECT_EQ(kg.beam, 0);
  std::mt19937 rng(31337);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double le = 0.02;
  for (int trial = 0; trial < 200; ++trial) {
    const double q[2] = {double_pendulum_beam_params().q0(0) + 0.3 * u(rng),
                         double_pendulum_beam_params().q0(1) + 0.3 * u(rng)};
    const double qd[2] = {3 * u(rng), 3 * u(rng)};
    const double qe[4] = {0.01 * u(rng), 0.05 * u(rng), 0.01 * u(rng), 0.05 * u(rng)};
    const double qed[4] = {u(rng), 5 * u(rng), u(rng), 5 * u(rng)};
    double a[4], b[4], fa[2], fb[2];
    gen.mass_matrix(q, a);
    ref.mass_matrix(q, b);
    EXPECT_LT(rel_err(a, b, 4), kRelTol) << "M, trial " << trial;
    gen.inertial_forces(q, qd, fa);
    ref.inertial_forces(q, qd, fb);
    EXPECT_LT(rel_err(fa, fb, 2), kRelTol) << "F, trial " << trial;
    gen.generalized_forces(q, qd, 0.0, fa);
    ref.generalized_forces(q, qd, 0.0, fb);
    EXPECT_LT(rel_err(fa, fb, 2), kRelTol) << "Q, trial " << trial;
    const double sg = kg.position(q), sr = kr.position(q);
    EXPECT_LT(std::abs(sg - sr), kRelTol * (1.0 + std::abs(sr))) << "s, trial " << trial;
    // The element holding s, or a neighbour (xi outside [0, 1]: still the same polynomial).
    const double s0 = (std::floor(sr / le) + (trial % 3 - 1)) * le;
    double pg, pr, jbg[2], jbr[2], jeg[4], jer[4], gg, gr;
    kg.phi(q, qe, s0, le, &pg);
    kr.phi(q, qe, s0, le, &pr);
    EXPECT_LT(std::abs(pg - pr), kRelTol * (1.0 + std::abs(pr))) << "Phi, trial " << trial;
    kg.jacobians(q, qe, s0, le, jbg, jeg);
    kr.jacobians(q, qe, s0, le, jbr, jer);
    EXPECT_LT(rel_err(jbg, jbr, 2), kRelTol) << "J_b, trial " << trial;
    EXPECT_LT(rel_err(jeg, jer, 4), kRelTol) << "J_e, trial " << trial;
    kg.gamma(q, qd, qe, qed, s0, le, &gg);
    kr.gamma(q, qd, qe, qed, s0, le, &gr);
    EXPECT_LT(std::abs(gg - gr), kRelTol * (1.0 + std::abs(gr))) << "gamma, trial " << trial;
  }
}

#endif  // MBFE_HAVE_GENERATED_DOUBLE_PENDULUM_BEAM

}  // namespace
}  // namespace mbfe::reference
