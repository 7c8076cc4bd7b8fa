// Assembled beams: DOF order, supports, loads and static deflections against
// closed forms (Hermite elements are exact at the nodes for these loads).
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <stdexcept>

#include "tests/runtime/fem/beam_fixtures.h"
#include "runtime/errors/invalid_input.h"
#include "runtime/fem/beam_system.h"

namespace mbfe::runtime {
namespace {

using test::bending_stiffness;
using test::mass_per_length;

// Static solutions of 100 DOF with cond(K) ~ 1e8: about 1e-16 * 1e8.
constexpr double kStaticTol = 1e-7;
constexpr double kRoundoffTol = 1e-12;

Eigen::VectorXd solve_static(const BeamSystem& s) {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(s.K);
  EXPECT_EQ(ldlt.info(), Eigen::Success);
  return ldlt.solve(s.P);
}

// A sum of 50 consistent nodal loads of O(1e-2) N: round-off ~1e-16 each.
constexpr double kLoadSumTol = 1e-12;
// Gravity along the axis loads only through cos(pi/2) = 6e-17.
constexpr double kAxialGravityTol = 1e-15;

TEST(BeamAssembly, PinnedBeamDropsTheEndDeflectionsInContractOrder) {
  const BeamSystem s = assemble_beam(test::paper_beam(), {0.0, 0.0});
  ASSERT_EQ(s.M.rows(), 100);  // 51 nodes x 2 - 2
  ASSERT_EQ(s.free_dof.size(), 100u);
  EXPECT_EQ(s.free_dof.front(), 1);   // w'(0)
  EXPECT_EQ(s.free_dof[1], 2);        // w at node 1
  EXPECT_EQ(s.free_dof.back(), 101);  // w'(L); w(L) = full DOF 100 is fixed
  EXPECT_EQ(s.full_to_free[0], -1);
  EXPECT_EQ(s.full_to_free[100], -1);
  EXPECT_EQ((Eigen::MatrixXd(s.K) - Eigen::MatrixXd(s.K).transpose()).norm(), 0.0);  // symmetric bit for bit
  const Eigen::MatrixXd C_expected = 3e-3 * Eigen::MatrixXd(s.M) + 1.5e-4 * Eigen::MatrixXd(s.K);
  EXPECT_LE((Eigen::MatrixXd(s.C) - C_expected).norm(), kRoundoffTol * C_expected.norm());
}

TEST(BeamAssembly, MidspanPointLoadMatchesClosedForm) {
  ir::Beam b = test::paper_beam();
  b.loads = {{0.5, ir::Expression::number(-10.0), -1, {}, {}}};
  const BeamSystem s = assemble_beam(b, {0.0, 0.0});
  const Eigen::VectorXd q = solve_static(s);
  const double expected = -10.0 / (48.0 * bending_stiffness(b));  // P L^3 / (48 EI)
  EXPECT_NEAR(deflection_at(s, q, 0.5) / expected, 1.0, kStaticTol);
  // Between the nodes the cubic is exact too (no distributed load).
  const double x = 0.237;
  const double exact = -10.0 * x * (3.0 - 4.0 * x * x) / (48.0 * bending_stiffness(b));
  EXPECT_NEAR(deflection_at(s, q, x) / exact, 1.0, kStaticTol);
}

TEST(BeamAssembly, CantileverTipLoadMatchesClosedForm) {
  ir::Beam b = test::cantilever_beam(20);
  b.loads = {{1.0, ir::Expression::number(3.0), -1, {}, {}}};
  const BeamSystem s = assemble_beam(b, {0.0, 0.0});
  EXPECT_EQ(s.M.rows(), 40);  // clamped: w and w' at node 0 removed
  const Eigen::VectorXd q = solve_static(s);
  const double EI = bending_stiffness(b);
  EXPECT_NEAR(deflection_at(s, q, 1.0) / (3.0 / (3.0 * EI)), 1.0, kStaticTol);  // P L^3/(3 EI)
  EXPECT_NEAR(q[q.size() - 1] / (3.0 / (2.0 * EI)), 1.0, kStaticTol);         // slope P L^2/(2 EI)
}

TEST(BeamAssembly, OwnWeightUsesTheTransverseComponentOfGravity) {
  const ir::Beam b = test::paper_beam();
  const double q_down = -9.81 * mass_per_length(b);  // N/m along +n = (0, 1)
  {
    const BeamSystem s = assemble_beam(b, {0.0, -9.81});
    const double expected = 5.0 * q_down / (384.0 * bending_stiffness(b));  // 5 q L^4 / (384 EI)
    EXPECT_NEAR(deflection_at(s, solve_static(s), 0.5) / expected, 1.0, kStaticTol);
    // Total transverse force on the free DOFs + the two reactions = weight.
    double sum_w = 0.0;
    for (size_t k = 0; k < s.free_dof.size(); ++k)
      if (s.free_dof[k] % 2 == 0) sum_w += s.P[k];
    EXPECT_NEAR(sum_w, q_down * (1.0 - 1.0 / 50.0), kLoadSumTol);
  }
  {
    // A vertical beam (axis +y): n = (-1, 0); gravity along -y loads nothing,
    // gravity along -x loads it along +n.
    ir::Beam v = b;
    v.angle = test::kPi / 2;
    EXPECT_NEAR(assemble_beam(v, {0.0, -9.81}).P.norm(), 0.0, kAxialGravityTol);
    const BeamSystem s = assemble_beam(v, {-9.81, 0.0});
    EXPECT_GT(deflection_at(s, solve_static(s), 0.5), 0.0);
  }
}

TEST(BeamAssembly, ConsistentNodalMomentsAreExactForUniformLoad) {
  // Clamped-clamped under own weight: w(L/2) = q L^4 / (384 EI); needs the
  // moment terms of the consistent load (plain nodal forces give 5x this).
  ir::Beam b = test::paper_beam(0.005, 10);
  b.supports = {{0.0, ir::SupportType::kClamped, -1, {}},
                {1.0, ir::SupportType::kClamped, -1, {}}};
  const BeamSystem s = assemble_beam(b, {0.0, -9.81});
  const double expected = -9.81 * mass_per_length(b) / (384.0 * bending_stiffness(b));
  EXPECT_NEAR(deflection_at(s, solve_static(s), 0.5) / expected, 1.0, kStaticTol);
}

TEST(BeamAssembly, RejectsSupportsAndLoadsOffTheNodes) {
  ir::Beam b = test::paper_beam();
  b.loads = {{0.51, ir::Expression::number(-10.0), -1, {}, {}}};
  EXPECT_THROW(assemble_beam(b, {0.0, 0.0}), std::invalid_argument);
  b = test::paper_beam();
  b.supports.push_back({1.5, ir::SupportType::kPinned, -1, {}});
  EXPECT_THROW(assemble_beam(b, {0.0, 0.0}), std::invalid_argument);
  b = test::paper_beam();
  b.second_moment = 0.0;
  EXPECT_THROW(assemble_beam(b, {0.0, 0.0}), std::invalid_argument);
}

TEST(BeamAssembly, PointWeightsSkipFixedDofs) {
  const BeamSystem s = assemble_beam(test::paper_beam(), {0.0, 0.0});
  const BeamPointWeights w0 = point_weights(s, 0.0);
  EXPECT_EQ(w0.free_index[0], -1);  // w(0) fixed
  EXPECT_EQ(w0.free_index[1], 0);
  const BeamPointWeights wl = point_weights(s, 1.0);
  EXPECT_EQ(wl.free_index[2], -1);  // w(L) fixed
  EXPECT_NEAR(wl.w[2], 1.0, kRoundoffTol);
  EXPECT_THROW(point_weights(s, 1.01), std::invalid_argument);
}

TEST(BeamAssembly, LumpedMassKeepsTheTotalMass) {
  ir::Beam b = test::paper_beam();
  b.supports.clear();
  for (const auto lumping : {ir::MassLumping::kConsistent, ir::MassLumping::kLumped}) {
    b.mass = lumping;
    const BeamSystem s = assemble_beam(b, {0.0, 0.0});
    Eigen::VectorXd translation = Eigen::VectorXd::Zero(s.M.rows());
    for (Eigen::Index i = 0; i < translation.size(); i += 2) translation[i] = 1.0;
    EXPECT_NEAR(translation.dot(s.M * translation), mass_per_length(b) * b.length,
                kRoundoffTol * mass_per_length(b));
  }
}

TEST(BeamAssembly, ABeamItsSupportsHoldEverywhereIsRefusedByName) {
  // One element clamped at both ends: all four degrees of freedom fixed. The
  // coupled runtime once read past its empty matrices (a segmentation fault).
  ir::Beam b = test::paper_beam(0.005, 1);
  b.supports = {{0.0, ir::SupportType::kClamped, -1, {}}, {1.0, ir::SupportType::kClamped, -1, {}}};
  try {
    assemble_beam(b, {0.0, 0.0});
    FAIL() << "assembled a beam with no free degree of freedom";
  } catch (const InvalidInput& e) {
    EXPECT_STREQ(e.what(), "beam 'beam1': its supports hold every node (4 degrees of freedom, none free), so it "
                           "cannot move; give it more elements or fewer supports");
  }
}

}  // namespace
}  // namespace mbfe::runtime
