// The link force element (LinkForce, docs/catenary.md: a dropper between two
// beams) on gradients written here, without a model: a taut link against
// the closed form T = k (w_b - w_a - rest) + c (w_b - w_a)', pulling a
// towards b and b towards a; the force on any gradient against central
// differences of the spring's energy 1/2 k e^2 and the damper's dissipation
// function 1/2 c e'^2; a slack link carrying nothing under compression (the
// tension, not the extension, deciding); a link inside a joined structure
// adding exactly what the structure's k g g^T leaves out; and the tangent,
// in all four cases, against central differences of the force.
#include "runtime/coupled/link_force.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <random>
#include <string>
#include <vector>

#include "ir/model.h"

namespace mbfe::runtime {
namespace {

constexpr int kNb = 2;   // rigid coordinates ahead of q_c
constexpr int kNc = 10;  // beam coordinates
constexpr int kN = kNb + kNc;

constexpr double kStiffness = 2.0e5;  // N/m, a dropper's order
constexpr double kDamping = 50.0;     // N s/m
constexpr double kRest = 0.02;        // m

// Forces of O(1e3) N from sums of products of k ~ 2e5 N/m and q ~ 1e-2 m:
// round-off ~ 1e-12 N, with a margin of 100.
constexpr double kForceTol = 1e-10;  // N
// V and R are quadratics, whose central differences are exact but for
// round-off, eps V / h ~ 2e-16 * 40 J / 1e-6 m ~ 1e-8 N, against forces of
// O(1e3) N: 1e-9 of the largest leaves a margin of 100.
constexpr double kEnergyDifferenceRelTol = 1e-9;
constexpr double kEnergyStep = 1e-6;  // m or m/s
// The force is linear in q and v on each side of the slack switch, so its
// central differences are exact but for round-off, eps |f| / h ~ 2e-16 *
// 1e3 / 1e-6 = 2e-7 N/m: 1e-10 of k leaves a margin of 100.
constexpr double kTangentRelTol = 1e-10;
// m or m/s: moves T by k |g| h ~ 0.2 N, far from the switch of states with |T| = 500 N.
constexpr double kTangentStep = 1e-6;

ir::Link make_link(bool slack) {
  ir::Link link;
  link.name = "dropper";
  link.stiffness = kStiffness;
  link.damping = kDamping;
  link.slack = slack;
  link.rest = kRest;
  return link;
}

/// A link from the deflection of one node (q_c[1]) to another (q_c[6]): e = q_c[6] - q_c[1] - rest.
LinkGradient nodal_gradient() {
  LinkGradient g;
  g.cols[0] = 1;
  g.values[0] = -1.0;
  g.cols[1] = 6;
  g.values[1] = 1.0;
  g.size = 2;
  return g;
}

/// Both ends inside elements of 0.25 m: -N at xi = 0.6 of one, +N at xi =
/// 0.7 of the next, the two sharing columns 4 and 5 as neighbours on one beam do.
LinkGradient element_gradient() {
  const int cols[8] = {2, 3, 4, 5, 4, 5, 6, 7};
  const double values[8] = {-0.352, -0.024, -0.648, 0.036, 0.216, 0.01575, 0.784, -0.03675};
  LinkGradient g;
  for (int i = 0; i < 8; ++i) {
    g.cols[i] = cols[i];
    g.values[i] = values[i];
  }
  g.size = 8;
  return g;
}

/// g as a dense vector over q_c.
Eigen::VectorXd dense(const LinkGradient& g) {
  Eigen::VectorXd d = Eigen::VectorXd::Zero(kNc);
  for (int i = 0; i < g.size; ++i) d[g.cols[i]] += g.values[i];
  return d;
}

/// The generalized force over [q_b; q_c] at (q, v), both over [q_b; q_c].
Eigen::VectorXd force_of(const LinkForce& link, LinkForce::State& state, const Eigen::VectorXd& q,
                         const Eigen::VectorXd& v) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(kN);
  const ForceArgs x{0.0, q.data(), v.data(), q.data() + kNb, v.data() + kNb};
  ForceSink sink{f.data(), f.data() + kNb};
  link.add_force(x, state, sink);
  return f;
}

/// add_tangent(c_q, c_v) at the state of a force evaluation at (q, v), dense.
Eigen::MatrixXd tangent_of(const LinkForce& link, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double c_q,
                           double c_v) {
  LinkForce::State state;
  force_of(link, state, q, v);
  std::vector<Eigen::Triplet<double>> triplets;
  TangentSink sink(triplets);
  const ForceArgs x{0.0, q.data(), v.data(), q.data() + kNb, v.data() + kNb};
  link.add_tangent(x, state, c_q, c_v, sink);
  Eigen::SparseMatrix<double> t(kN, kN);
  t.setFromTriplets(triplets.begin(), triplets.end());
  return Eigen::MatrixXd(t);
}

/// q and v over [q_b; q_c], seeded, of a catenary's order (cm, cm/s).
void random_state(std::mt19937& rng, Eigen::VectorXd& q, Eigen::VectorXd& v) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  q.resize(kN);
  v.resize(kN);
  for (int i = 0; i < kN; ++i) {
    q[i] = 0.01 * u(rng);
    v[i] = 0.05 * u(rng);
  }
}

/// Shifts q along g until k (g q - rest) + c g v = tension (N): a taut or a compressed state.
void set_tension(const LinkGradient& g, double tension, Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  const Eigen::VectorXd d = dense(g);
  const double e_wanted = (tension - kDamping * d.dot(v.tail(kNc))) / kStiffness + kRest;
  const double e_now = d.dot(q.tail(kNc));
  q.tail(kNc) += (e_wanted - e_now) / d.squaredNorm() * d;
}

TEST(LinkForce, ATautLinkPullsItsTwoEndsTogether) {
  const LinkForce link(make_link(false), kRest, nodal_gradient(), false, kNb);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(kN), v = Eigen::VectorXd::Zero(kN);
  const double w_a = -0.010, w_b = 0.015, v_a = 0.10, v_b = -0.04;  // m, m/s
  q[kNb + 1] = w_a;
  q[kNb + 6] = w_b;
  v[kNb + 1] = v_a;
  v[kNb + 6] = v_b;
  q[0] = 0.3;  // rigid coordinates: not read
  v[1] = -2.0;
  const double extension = w_b - w_a - kRest;                              // 0.005 m
  const double tension = kStiffness * extension + kDamping * (v_b - v_a);  // 993 N
  ASSERT_GT(tension, 0.0);

  // The sink is added to: start it away from zero.
  Eigen::VectorXd f = Eigen::VectorXd::Constant(kN, 1.5);
  LinkForce::State state;
  const ForceArgs x{0.0, q.data(), v.data(), q.data() + kNb, v.data() + kNb};
  ForceSink sink{f.data(), f.data() + kNb};
  link.add_force(x, state, sink);

  Eigen::VectorXd expected = Eigen::VectorXd::Constant(kN, 1.5);
  expected[kNb + 1] += tension;  // a pulled up towards b
  expected[kNb + 6] -= tension;  // b pulled down towards a
  for (int i = 0; i < kN; ++i) EXPECT_NEAR(f[i], expected[i], kForceTol) << "entry " << i;
  EXPECT_NEAR(state.link.extension, extension, kForceTol / kStiffness);
  EXPECT_NEAR(state.link.rate, v_b - v_a, kForceTol / kStiffness);
  EXPECT_NEAR(state.link.tension, tension, kForceTol);
  EXPECT_FALSE(state.link.slack);
}

TEST(LinkForce, ForceIsMinusTheGradientsOfItsEnergyAndDissipation) {
  // V = 1/2 k e^2 and R = 1/2 c e'^2, e = g q - rest: f = -dV/dq - dR/dv.
  const LinkGradient g = element_gradient();
  const Eigen::VectorXd d = dense(g);
  const LinkForce link(make_link(false), kRest, g, false, kNb);
  const auto energy = [&](const Eigen::VectorXd& q) {
    const double e = d.dot(q.tail(kNc)) - kRest;
    return 0.5 * kStiffness * e * e;
  };
  const auto dissipation = [&](const Eigen::VectorXd& v) {
    const double rate = d.dot(v.tail(kNc));
    return 0.5 * kDamping * rate * rate;
  };
  std::mt19937 rng(20250611);
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd q, v;
    random_state(rng, q, v);
    LinkForce::State state;
    const Eigen::VectorXd f = force_of(link, state, q, v);
    Eigen::VectorXd expected(kN);
    for (int j = 0; j < kN; ++j) {
      Eigen::VectorXd qp = q, qm = q, vp = v, vm = v;
      qp[j] += kEnergyStep;
      qm[j] -= kEnergyStep;
      vp[j] += kEnergyStep;
      vm[j] -= kEnergyStep;
      expected[j] =
          -(energy(qp) - energy(qm)) / (2 * kEnergyStep) - (dissipation(vp) - dissipation(vm)) / (2 * kEnergyStep);
    }
    const double scale = expected.cwiseAbs().maxCoeff();
    ASSERT_GT(scale, 0.0);
    for (int j = 0; j < kN; ++j) EXPECT_NEAR(f[j], expected[j], kEnergyDifferenceRelTol * scale) << "entry " << j;
  }
}

TEST(LinkForce, ASlackLinkCarriesNoCompressionAndTheTensionDecides) {
  const LinkGradient g = element_gradient();
  const Eigen::VectorXd d = dense(g);
  const LinkForce slack(make_link(true), kRest, g, false, kNb);
  const LinkForce taut(make_link(false), kRest, g, false, kNb);
  std::mt19937 rng(7);
  Eigen::VectorXd q, v;
  random_state(rng, q, v);

  // Compressed: the slack link lets go, the other one pushes.
  set_tension(g, -400.0, q, v);
  const double e = d.dot(q.tail(kNc)) - kRest, rate = d.dot(v.tail(kNc));
  LinkForce::State state;
  const Eigen::VectorXd f_slack = force_of(slack, state, q, v);
  EXPECT_EQ(f_slack.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_TRUE(state.link.slack);
  EXPECT_EQ(state.link.tension, 0.0);
  EXPECT_NEAR(state.link.extension, e, kForceTol / kStiffness);  // still reported
  EXPECT_NEAR(state.link.rate, rate, kForceTol / kStiffness);
  const Eigen::VectorXd f_taut = force_of(taut, state, q, v);
  EXPECT_FALSE(state.link.slack);
  EXPECT_NEAR(state.link.tension, -400.0, kForceTol);
  for (int j = 0; j < kN; ++j) EXPECT_NEAR(f_taut[j], j < kNb ? 0.0 : 400.0 * d[j - kNb], kForceTol);

  // Shorter than its rest but opening fast: the damper keeps it in tension.
  const double e2 = -0.001, rate2 = 10.0;  // m, m/s
  Eigen::VectorXd q2 = Eigen::VectorXd::Zero(kN), v2 = Eigen::VectorXd::Zero(kN);
  q2.tail(kNc) = (kRest + e2) * d / d.squaredNorm();
  v2.tail(kNc) = rate2 * d / d.squaredNorm();
  const double tension = kStiffness * e2 + kDamping * rate2;  // 300 N
  ASSERT_GT(tension, 0.0);
  const Eigen::VectorXd f_opening = force_of(slack, state, q2, v2);
  EXPECT_FALSE(state.link.slack);
  EXPECT_NEAR(state.link.tension, tension, kForceTol);
  for (int j = kNb; j < kN; ++j) EXPECT_NEAR(f_opening[j], -tension * d[j - kNb], kForceTol);
}

TEST(LinkForce, InsideAStructureItAddsWhatTheStructuresStiffnessLeavesOut) {
  // The joined structure's K holds k g g^T, a force -k g (g q); the link
  // inside it plus that force is the link outside it, taut or slack.
  const LinkGradient g = element_gradient();
  const Eigen::VectorXd d = dense(g);
  std::mt19937 rng(11);
  for (const double tension : {600.0, -300.0}) {
    SCOPED_TRACE(tension > 0 ? "taut" : "slack");
    Eigen::VectorXd q, v;
    random_state(rng, q, v);
    set_tension(g, tension, q, v);
    const LinkForce inside(make_link(true), kRest, g, true, kNb);
    const LinkForce outside(make_link(true), kRest, g, false, kNb);
    LinkForce::State state_in, state_out;
    const Eigen::VectorXd f_in = force_of(inside, state_in, q, v);
    const Eigen::VectorXd f_out = force_of(outside, state_out, q, v);
    const double gq = d.dot(q.tail(kNc)), rate = d.dot(v.tail(kNc));
    // The header's forms: + k rest g - c e' g while taut, + k (g q) g while slack.
    const double along_g = tension > 0 ? kStiffness * kRest - kDamping * rate : kStiffness * gq;
    for (int j = 0; j < kN; ++j) {
      const double gj = j < kNb ? 0.0 : d[j - kNb];
      EXPECT_NEAR(f_in[j] - kStiffness * gq * gj, f_out[j], kForceTol) << "entry " << j;
      EXPECT_NEAR(f_in[j], along_g * gj, kForceTol) << "entry " << j;
    }
    // The state reports the link's own tension, as outside.
    EXPECT_EQ(state_in.link.slack, tension < 0);
    EXPECT_NEAR(state_in.link.tension, tension > 0 ? tension : 0.0, kForceTol);
  }
}

TEST(LinkForce, TangentMatchesCentralDifferencesOfTheForce) {
  const LinkGradient g = element_gradient();
  std::mt19937 rng(3);
  for (const bool inside : {false, true}) {
    for (const double tension : {500.0, -500.0}) {
      SCOPED_TRACE(std::string(inside ? "inside, " : "outside, ") + (tension > 0 ? "taut" : "slack"));
      const LinkForce link(make_link(true), kRest, g, inside, kNb);
      Eigen::VectorXd q, v;
      random_state(rng, q, v);
      set_tension(g, tension, q, v);
      const Eigen::MatrixXd tangent_q = tangent_of(link, q, v, 1.0, 0.0);
      const Eigen::MatrixXd tangent_v = tangent_of(link, q, v, 0.0, 1.0);
      Eigen::MatrixXd fd_q(kN, kN), fd_v(kN, kN);
      LinkForce::State state;
      for (int j = 0; j < kN; ++j) {
        Eigen::VectorXd qp = q, qm = q, vp = v, vm = v;
        qp[j] += kTangentStep;
        qm[j] -= kTangentStep;
        vp[j] += kTangentStep;
        vm[j] -= kTangentStep;
        fd_q.col(j) = -(force_of(link, state, qp, v) - force_of(link, state, qm, v)) / (2 * kTangentStep);
        fd_v.col(j) = -(force_of(link, state, q, vp) - force_of(link, state, q, vm)) / (2 * kTangentStep);
      }
      EXPECT_LT((tangent_q - fd_q).cwiseAbs().maxCoeff(), kTangentRelTol * kStiffness) << tangent_q << "\n\n" << fd_q;
      EXPECT_LT((tangent_v - fd_v).cwiseAbs().maxCoeff(), kTangentRelTol * kStiffness) << tangent_v << "\n\n" << fd_v;
      // Not a comparison of zeros: a taut link outside a structure, or a
      // slack one inside, has the position tangent +-k g g^T, and a taut one
      // the rate tangent c g g^T.
      const double largest_g2 = dense(g).cwiseAbs2().maxCoeff();
      if (tension > 0 ? !inside : inside) {
        EXPECT_GT(fd_q.cwiseAbs().maxCoeff(), 0.5 * kStiffness * largest_g2);
      }
      if (tension > 0) {
        EXPECT_GT(fd_v.cwiseAbs().maxCoeff(), 0.5 * kDamping * largest_g2);
      }
      // c_q and c_v weigh the two parts.
      const Eigen::MatrixXd both = tangent_of(link, q, v, 0.7, 0.3);
      EXPECT_LT((both - 0.7 * tangent_q - 0.3 * tangent_v).cwiseAbs().maxCoeff(), kTangentRelTol * kStiffness);
    }
  }
}

TEST(LinkForce, ReadsTheBeamCoordinatesOfItsGradient) {
  const LinkGradient g = element_gradient();
  const LinkForce link(make_link(false), kRest, g, false, kNb);
  std::vector<int> read = {99};  // appended to
  link.beam_dofs_read(nullptr, read);
  EXPECT_EQ(read, (std::vector<int>{99, 2, 3, 4, 5, 4, 5, 6, 7}));
}

}  // namespace
}  // namespace mbfe::runtime
