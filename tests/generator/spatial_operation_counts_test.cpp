// Operation counts of spatial solvers: the emitted code of a chain grows
// linearly (as N^1.06 from 20 to 40 joints, the same cost per added joint
// from 10 on), the pair loop of M runs once per
// (ancestor, descendant) pair of velocity coordinates (a quaternion joint's
// three count as three coordinates in series), and the banner says both.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "frontend/parse_model.h"
#include "generator/emit/generate_solver.h"

namespace mbfe {
namespace {

// The target: emitted operations growing at most ~N^1.2 for chains. The code
// is linear in N (a constant number of operations per joint), but the first
// two or three joints of a chain cost less (near the ground the rotations
// are sparse), which bends a power law fitted from 5 joints up (1.22);
// doubling a long chain shows the growth itself (about 2^1.06).
constexpr double kMaxGrowthExponent = 1.2;
// Operations per added joint, from 10 to 20 and from 20 to 40 joints: the
// same within this fraction when the code is linear (6 % today).
constexpr double kMarginalCostSpread = 0.15;
// M's spatial pair loop body: S_j . U_k, 6 products and 5 sums.
constexpr long kOperationsPerPass = 11;

// The chains of scripts/make_spatial_tree.py: hinges about z, y, x in turn.
std::string spatial_chain(int n) {
  std::ostringstream y;
  y << "model: spatial_chain_" << n << "\ndimension: 3\ngravity: [0, 0, -9.81]\nbodies:\n";
  const char* axes[] = {"[0, 0, 1]", "[0, 1, 0]", "[1, 0, 0]"};
  for (int i = 0; i < n; ++i)
    y << "  - {name: link" << i + 1 << ", parent: " << (i == 0 ? "ground" : "link" + std::to_string(i))
      << ", joint: {type: revolute, axis: " << axes[i % 3] << ", at: " << (i == 0 ? "[0, 0, 0]" : "[0, 0, 0.4]")
      << "}, mass: 1.0, inertia: [0.0135417, 0.0135417, 0.000416667, 0, 0, 0], com: [0, 0, 0.2]}\n";
  return y.str();
}

gen::GeneratedSolver generate(const std::string& yaml) {
  return gen::generate_solver(frontend::parse_model_text(yaml, "counts.yaml"));
}

long emitted(const gen::GeneratedSolver& s, const std::string& name) {
  for (const gen::KernelOperations& k : s.operations)
    if (k.kernel == name) return k.emitted;
  ADD_FAILURE() << "no kernel " << name;
  return 0;
}

TEST(SpatialOperationCounts, EmittedOperationsOfChainsGrowLinearly) {
  std::vector<double> ops;
  for (int n : {10, 20, 40}) {
    const gen::GeneratedSolver s = generate(spatial_chain(n));
    ops.push_back(static_cast<double>(s.total_emitted()));
    // M's straight-line part is O(N) too: its pairs are a loop.
    EXPECT_LT(emitted(s, "mass_matrix"), 150L * n) << n << " joints";
  }
  EXPECT_LT(std::log2(ops[2] / ops[1]), kMaxGrowthExponent) << ops[1] << " -> " << ops[2] << " operations";
  const double per_joint_short = (ops[1] - ops[0]) / 10, per_joint_long = (ops[2] - ops[1]) / 20;
  EXPECT_LT(std::fabs(per_joint_long / per_joint_short - 1), kMarginalCostSpread)
      << per_joint_short << " and " << per_joint_long << " operations per joint";
}

TEST(SpatialOperationCounts, PairLoopCountsVelocityCoordinates) {
  // A spherical joint (3 velocity coordinates in series), a revolute below
  // it, and a free body on its own branch (6 in series).
  const gen::GeneratedSolver s = generate(R"(model: pairs
dimension: 3
bodies:
  - {name: ball, parent: ground, joint: {type: spherical}, mass: 1, inertia: [1, 1, 1, 0, 0, 0], com: [0, 0, -1]}
  - {name: arm, parent: ball, joint: {type: revolute, axis: [1, 0, 0], at: [0, 0, -1]}, mass: 1, inertia: [1, 1, 1, 0, 0, 0]}
  - {name: drone, parent: ground, joint: {type: free}, mass: 1, inertia: [1, 1, 1, 0, 0, 0]}
)");
  // Depths of the coordinates: ball 1, 2, 3; arm 4; drone 1..6.
  constexpr long kPairs = 1 + 2 + 3 + 4 + (1 + 2 + 3 + 4 + 5 + 6);
  EXPECT_EQ(s.assembly_pairs, kPairs);
  EXPECT_EQ(s.assembly_operations_per_pass, kOperationsPerPass);
  long mass_executed = 0, mass_emitted = 0;
  for (const gen::KernelOperations& k : s.operations)
    if (k.kernel == "mass_matrix") mass_executed = k.executed, mass_emitted = k.emitted;
  EXPECT_EQ(mass_executed, mass_emitted + (kPairs - 1) * kOperationsPerPass);
  const std::string& source = s.files.at(1).text;
  EXPECT_NE(source.find("constexpr int kParent[kNumVelocities] = {-1, 0, 1, 2, -1, 4, 5, 6, 7, 8};"),
            std::string::npos);
  EXPECT_NE(source.find("pair of velocity coordinates: " + std::to_string(kPairs) + " passes, 11 operations each."),
            std::string::npos);
}

}  // namespace
}  // namespace mbfe
