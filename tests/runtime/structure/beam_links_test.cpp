// A link's gradient g on beam meshes (link_gradient, beam_links.h) against
// hand computations on two small meshes written here: a three-element beam
// pinned at both ends and a two-element cantilever. Inside elements g holds
// -N on a's element and +N on b's, the Hermite values worked out by hand
// below, at the coordinates the offsets and supports give; on a node it is
// that node's deflection alone; and g q is w_b(s_b) - w_a(s_a) exactly for
// any cubic deflection the supports allow (Hermite elements reproduce
// cubics), at nodes, inside elements and at the beams' ends.
#include "runtime/structure/beam_links.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <vector>

#include "ir/model.h"
#include "runtime/structure/beam_mesh.h"

namespace mbfe::runtime {
namespace {

// Shape-function values of O(1) from a few products: round-off.
constexpr double kShapeTol = 1e-14;
// g q against cubics of O(1e-2) m evaluated here: sums of eight products,
// round-off of the deflections.
constexpr double kDeflectionTol = 1e-15;  // m

constexpr int kOffsetA = 3;  // a's free DOFs start here (something ahead of them)
constexpr int kOffsetB = 9;  // b's: right after a's six

/// Beam a: 3 elements of 0.5 m, pinned at s = 0 and s = 1.5 m. Full DOFs
/// [w0, w0', w1, w1', w2, w2', w3, w3']; w0 and w3 fixed.
BeamMesh pinned_beam() {
  BeamMesh m;
  m.name = "contact";
  m.num_elements = 3;
  m.element_length = 0.5;
  m.full_to_free = {-1, 0, 1, 2, 3, 4, -1, 5};
  m.num_free = 6;
  return m;
}

/// Beam b: 2 elements of 0.75 m, clamped at s = 0 (w0 and w0' fixed), free at s = 1.5 m.
BeamMesh cantilever() {
  BeamMesh m;
  m.name = "messenger";
  m.num_elements = 2;
  m.element_length = 0.75;
  m.full_to_free = {-1, -1, 0, 1, 2, 3};
  m.num_free = 4;
  return m;
}

const std::vector<BeamMesh> kMeshes = {pinned_beam(), cantilever()};
const std::vector<int> kOffsets = {kOffsetA, kOffsetB};
constexpr int kSize = kOffsetB + 4;  // the vector g indexes

ir::Link link_between(int beam_a, double s_a, int beam_b, double s_b) {
  ir::Link link;
  link.name = "dropper";
  link.a = {beam_a, s_a};
  link.b = {beam_b, s_b};
  link.stiffness = 1e5;
  return link;
}

/// g as a dense vector (repeated columns summed); every column in range.
Eigen::VectorXd dense(const LinkGradient& g) {
  Eigen::VectorXd d = Eigen::VectorXd::Zero(kSize);
  for (int i = 0; i < g.size; ++i) {
    EXPECT_GE(g.cols[i], 0);
    EXPECT_LT(g.cols[i], kSize);
    if (g.cols[i] >= 0 && g.cols[i] < kSize) d[g.cols[i]] += g.values[i];
  }
  return d;
}

TEST(BeamLinks, InsideElementsTheGradientIsEachEndsShapeFunctions) {
  // a at s = 0.8 m: element 1 (0.5 to 1.0 m), xi = 0.6, le = 0.5:
  //   N1 = 1 - 3 (0.36) + 2 (0.216)   = 0.352
  //   N2 = 0.5 (0.6 - 2 (0.36) + 0.216) = 0.048
  //   N3 = 3 (0.36) - 2 (0.216)        = 0.648
  //   N4 = 0.5 (0.216 - 0.36)          = -0.072
  // on full DOFs 2..5 = free 1..4 of a, columns 4..7, with the sign -.
  // b at s = 0.3 m: element 0, xi = 0.4, le = 0.75:
  //   N1 = 0.648, N2 = 0.75 (0.4 - 0.32 + 0.064) = 0.108, N3 = 0.352,
  //   N4 = 0.75 (0.064 - 0.16) = -0.072
  // on full DOFs 0..3, of which 0 and 1 are clamped: N3, N4 on free 0, 1
  // of b, columns 9, 10.
  const LinkGradient g = link_gradient(link_between(0, 0.8, 1, 0.3), kMeshes, kOffsets);
  EXPECT_EQ(g.size, 6);  // the clamped DOFs' entries are left out, not stored as zeros
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(kSize);
  expected[4] = -0.352;
  expected[5] = -0.048;
  expected[6] = -0.648;
  expected[7] = 0.072;
  expected[9] = 0.352;
  expected[10] = -0.072;
  const Eigen::VectorXd d = dense(g);
  for (int i = 0; i < kSize; ++i) EXPECT_NEAR(d[i], expected[i], kShapeTol) << "column " << i;
}

TEST(BeamLinks, OnANodeTheGradientIsThatNodesDeflection) {
  // a at node 2 (s = 1.0 m, w2 = free 3 of a, column 6); b at its free end
  // (s = 1.5 m, w2 = free 2 of b, column 11).
  const LinkGradient g = link_gradient(link_between(0, 1.0, 1, 1.5), kMeshes, kOffsets);
  ASSERT_EQ(g.size, 2);
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(kSize);
  expected[6] = -1.0;
  expected[11] = 1.0;
  EXPECT_EQ(dense(g), expected);
  // At a's pinned end nothing of a moves: only b's entry is left.
  const LinkGradient at_support = link_gradient(link_between(0, 1.5, 1, 1.5), kMeshes, kOffsets);
  ASSERT_EQ(at_support.size, 1);
  EXPECT_EQ(at_support.cols[0], 11);
  EXPECT_EQ(at_support.values[0], 1.0);
}

/// Nodal coordinates of a cubic deflection w(s) (and its slope dw) on `mesh`,
/// written at `offset` into q (fixed DOFs must be zero for w and dw).
void write_cubic(const BeamMesh& mesh, int offset, double (*w)(double), double (*dw)(double), Eigen::VectorXd& q) {
  for (int node = 0; node <= mesh.num_elements; ++node) {
    const double s = node * mesh.element_length;
    for (int k = 0; k < 2; ++k) {
      const int f = mesh.full_to_free[2 * node + k];
      const double value = k == 0 ? w(s) : dw(s);
      if (f < 0)
        EXPECT_EQ(value, 0.0) << "the cubic moves a fixed DOF";
      else
        q[offset + f] = value;
    }
  }
}

// Cubics the supports allow: zero at both ends of a (pinned, slopes free),
// zero with zero slope at b's clamp.
double w_a(double s) { return s * (1.5 - s) * (0.012 - 0.007 * s); }
double dw_a(double s) { return (1.5 - 2 * s) * (0.012 - 0.007 * s) - 0.007 * s * (1.5 - s); }
double w_b(double s) { return s * s * (-0.02 + 0.009 * s); }
double dw_b(double s) { return 2 * s * (-0.02 + 0.009 * s) + 0.009 * s * s; }

TEST(BeamLinks, TheGradientTimesQIsTheDifferenceOfTheDeflections) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(kSize);
  q.head(kOffsetA).setConstant(7.0);  // ahead of the offsets: never read
  write_cubic(kMeshes[0], kOffsets[0], w_a, dw_a, q);
  write_cubic(kMeshes[1], kOffsets[1], w_b, dw_b, q);
  // Both ends, at a beam's start, at nodes, inside elements and at its end.
  for (const double s_a : {0.0, 0.2, 0.5, 0.8, 1.0, 1.37, 1.5}) {
    for (const double s_b : {0.0, 0.3, 0.75, 1.1, 1.5}) {
      const LinkGradient g = link_gradient(link_between(0, s_a, 1, s_b), kMeshes, kOffsets);
      EXPECT_LE(g.size, 8);
      EXPECT_NEAR(dense(g).dot(q), w_b(s_b) - w_a(s_a), kDeflectionTol) << "s_a = " << s_a << ", s_b = " << s_b;
      // Reversed: the same link seen from the other end.
      const LinkGradient r = link_gradient(link_between(1, s_b, 0, s_a), kMeshes, kOffsets);
      EXPECT_NEAR(dense(r).dot(q), w_a(s_a) - w_b(s_b), kDeflectionTol) << "s_a = " << s_a << ", s_b = " << s_b;
    }
  }
  // Both ends on one beam, in one element: columns repeat and add up.
  const LinkGradient same = link_gradient(link_between(0, 0.6, 0, 0.9), kMeshes, kOffsets);
  EXPECT_EQ(same.size, 8);
  EXPECT_NEAR(dense(same).dot(q), w_a(0.9) - w_a(0.6), kDeflectionTol);
}

}  // namespace
}  // namespace mbfe::runtime
