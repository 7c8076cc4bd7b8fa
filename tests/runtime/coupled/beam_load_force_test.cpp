// The time loads of a beam as a force element (BeamLoadForce) on a
// four-element pinned beam built from the IR: a moving force F(t) = F0 + F1 t
// at s(t) goes to the four DOFs of the element under it as F N_j(xi), with
// the Hermite cubics written here (the consistent load vector of a point
// force), summing to F and to its moment F s about s = 0 (the statics of a
// point force); a support's share is dropped; a windowed point load acts on
// its node's deflection in its window only; the loads land at the beam's
// offset in q_c, added to what is there; off the beam nothing is loaded; and
// the element has no tangent and reads no coordinates.
#include "runtime/coupled/beam_load_force.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "ir/expression.h"
#include "ir/model.h"
#include "runtime/fem/beam_system.h"
#include "tests/runtime/fem/beam_fixtures.h"

namespace mbfe::runtime {
namespace {

// Loads of O(1e2) N times shape-function values of O(1): round-off.
constexpr double kLoadTol = 1e-12;  // N or N m

constexpr double kF0 = -80.0;                            // N at t = 0
constexpr double kF1 = 40.0;                             // N/s
constexpr double kSpeed = 2.0;                           // m/s
constexpr double kStart = 0.1;                           // m at t = 0
constexpr double kPointLoad = 25.0;                      // N, at s = 0.5 m
constexpr double kWindowStart = 0.3, kWindowStop = 0.4;  // s

constexpr int kNb = 2;      // rigid coordinates
constexpr int kOffset = 3;  // where the beam's free DOFs start in q_c
constexpr int kFree = 8;    // 10 DOFs of 5 nodes, w0 and w4 pinned
constexpr int kNc = kOffset + kFree + 2;
constexpr double kLe = 0.25;  // m, element length
// full_to_free of the pinned four-element beam, by hand: w0 (0) and w4 (8) fixed.
const std::vector<int> kFullToFree = {-1, 0, 1, 2, 3, 4, 5, 6, -1, 7};
constexpr double kBefore = 1.5;  // N, in every entry of the sink before the call

double force_at(double t) { return kF0 + kF1 * t; }
double position_at(double t) { return kStart + kSpeed * t; }

/// kF0 + kF1 t as an expression tree (postfix: F0 t F1 * +).
ir::Expression linear_in_time() {
  using Kind = ir::ExpressionNode::Kind;
  std::vector<ir::ExpressionNode> nodes(5);
  nodes[0].kind = Kind::kNumber;
  nodes[0].value = kF0;
  nodes[1].kind = Kind::kTime;
  nodes[2].kind = Kind::kNumber;
  nodes[2].value = kF1;
  nodes[3].kind = Kind::kMultiply;
  nodes[4].kind = Kind::kAdd;
  return ir::Expression(nodes);
}

std::shared_ptr<const BeamSystem> loaded_beam() {
  ir::Beam b = test::paper_beam(0.005, 4);  // L = 1 m, pinned at both ends
  ir::BeamMovingLoad moving;
  moving.value = linear_in_time();
  moving.speed = kSpeed;
  moving.start = kStart;
  b.moving_loads = {moving};
  ir::BeamPointLoad point;
  point.at = 0.5;
  point.value = ir::Expression::number(kPointLoad);
  point.window = {kWindowStart, kWindowStop};
  b.loads = {point};
  auto beam = std::make_shared<const BeamSystem>(assemble_beam(b, {0.0, 0.0}));
  EXPECT_EQ(beam->full_to_free, kFullToFree);
  return beam;
}

/// The Hermite cubics at xi on an element of length le: w = N q_e, q_e = [w1, w1', w2, w2'].
std::array<double, 4> hermite(double xi, double le) {
  return {1 - 3 * xi * xi + 2 * xi * xi * xi, le * (xi - 2 * xi * xi + xi * xi * xi), 3 * xi * xi - 2 * xi * xi * xi,
          le * (xi * xi * xi - xi * xi)};
}

/// The moving force's consistent load on the full DOFs at t (10 entries).
Eigen::VectorXd consistent_load(double t) {
  Eigen::VectorXd full = Eigen::VectorXd::Zero(10);
  const double s = position_at(t);
  const int element = std::min(static_cast<int>(s / kLe), 3);
  const std::array<double, 4> n = hermite((s - element * kLe) / kLe, kLe);
  for (int j = 0; j < 4; ++j) full[2 * element + j] = force_at(t) * n[j];
  return full;
}

struct Evaluation {
  Eigen::VectorXd fb, fc;
  BeamLoadForce::State state;
};

Evaluation evaluate(const BeamLoadForce& force, double t) {
  Evaluation e;
  e.fb = Eigen::VectorXd::Constant(kNb, kBefore);
  e.fc = Eigen::VectorXd::Constant(kNc, kBefore);
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(kNb + kNc);  // loads do not depend on q, v
  const ForceArgs x{t, q.data(), q.data(), q.data() + kNb, q.data() + kNb};
  ForceSink sink{e.fb.data(), e.fc.data()};
  force.add_force(x, e.state, sink);
  return e;
}

/// What the sink should hold: kBefore plus the free entries of `full` at the offset.
Eigen::VectorXd expected_sink(const Eigen::VectorXd& full) {
  Eigen::VectorXd fc = Eigen::VectorXd::Constant(kNc, kBefore);
  for (int i = 0; i < 10; ++i)
    if (kFullToFree[i] >= 0) fc[kOffset + kFullToFree[i]] += full[i];
  return fc;
}

TEST(BeamLoadForce, AMovingForceGoesToItsElementByTheHermiteFunctions) {
  const BeamLoadForce force(loaded_beam(), kOffset);
  EXPECT_EQ(force.name(), "loads on 'beam1'");
  // s = 0.44 m: element 1 (0.25 to 0.5 m), xi = 0.76, all four DOFs free.
  const double t = 0.17;
  const Evaluation e = evaluate(force, t);
  const Eigen::VectorXd full = consistent_load(t);
  const Eigen::VectorXd expected = expected_sink(full);
  for (int i = 0; i < kNc; ++i) EXPECT_NEAR(e.fc[i], expected[i], kLoadTol) << "q_c entry " << i;
  EXPECT_EQ(e.fb, Eigen::VectorXd::Constant(kNb, kBefore));  // no rigid part
  // The statics of a point force: the deflection loads sum to F, and with
  // the moments give its moment F s about s = 0.
  double sum = 0.0, moment = 0.0;
  for (int node = 1; node <= 2; ++node) {
    const double w_load = e.fc[kOffset + kFullToFree[2 * node]] - kBefore;
    const double m_load = e.fc[kOffset + kFullToFree[2 * node + 1]] - kBefore;
    sum += w_load;
    moment += node * kLe * w_load + m_load;
  }
  EXPECT_NEAR(sum, force_at(t), kLoadTol);
  EXPECT_NEAR(moment, force_at(t) * position_at(t), kLoadTol);
  // The state holds the loads of this evaluation, on the beam's own DOFs.
  Eigen::VectorXd from_state = Eigen::VectorXd::Constant(kNc, kBefore);
  for (const NodalForce& f : e.state.nodal) from_state[kOffset + f.index] += f.value;
  for (int i = 0; i < kNc; ++i) EXPECT_NEAR(from_state[i], expected[i], kLoadTol) << "q_c entry " << i;
}

TEST(BeamLoadForce, ASupportsShareOfTheLoadIsDropped) {
  const BeamLoadForce force(loaded_beam(), kOffset);
  // s = 0.12 m: element 0, xi = 0.48; its w0 is pinned.
  const double t = 0.01;
  const Eigen::VectorXd full = consistent_load(t);
  ASSERT_GT(std::abs(full[0]), 10.0);  // a share the support takes
  const Evaluation e = evaluate(force, t);
  const Eigen::VectorXd expected = expected_sink(full);
  for (int i = 0; i < kNc; ++i) EXPECT_NEAR(e.fc[i], expected[i], kLoadTol) << "q_c entry " << i;
}

TEST(BeamLoadForce, APointLoadActsOnItsNodeInItsWindowBesideTheMovingForce) {
  const BeamLoadForce force(loaded_beam(), kOffset);
  // s = 0.7, 0.8 and 0.9 m: elements 2 and 3 (the latter holding the pinned
  // w4); the point load on w2 (full DOF 4) on within [0.3, 0.4) s, off after.
  for (const auto& [t, on] : {std::pair{0.3, true}, std::pair{0.35, true}, std::pair{0.4, false}}) {
    SCOPED_TRACE(t);
    Eigen::VectorXd full = consistent_load(t);
    if (on) full[4] += kPointLoad;
    const Evaluation e = evaluate(force, t);
    const Eigen::VectorXd expected = expected_sink(full);
    for (int i = 0; i < kNc; ++i) EXPECT_NEAR(e.fc[i], expected[i], kLoadTol) << "q_c entry " << i;
  }
}

TEST(BeamLoadForce, OffTheBeamNothingIsLoadedAndNothingIsRead) {
  const BeamLoadForce force(loaded_beam(), kOffset);
  for (const double t : {-0.1, 0.46}) {  // s = -0.1 m and 1.02 m
    const Evaluation e = evaluate(force, t);
    EXPECT_EQ(e.fc, Eigen::VectorXd::Constant(kNc, kBefore)) << "t = " << t;
    EXPECT_TRUE(e.state.nodal.empty()) << "t = " << t;
  }
  // Loads in t alone: no tangent, no coordinates read.
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(kNb + kNc);
  const ForceArgs x{0.17, q.data(), q.data(), q.data() + kNb, q.data() + kNb};
  BeamLoadForce::State state;
  std::vector<Eigen::Triplet<double>> triplets;
  TangentSink sink(triplets);
  force.add_tangent(x, state, 1.0, 1.0, sink);
  EXPECT_TRUE(triplets.empty());
  std::vector<int> read;
  force.beam_dofs_read(q.data(), read);
  EXPECT_TRUE(read.empty());
}

}  // namespace
}  // namespace mbfe::runtime
