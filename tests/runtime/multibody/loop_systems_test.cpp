// Runs of the shipped closed-loop models (a planar four-bar, a spatial
// slider-crank with a ball-jointed rod) in both formulations: the loop
// residual at round-off with the partitioned one, energy conservation
// (kinetic from the kernels' M, potential from the centres of mass placed
// here by hand), the partitioned and augmented runs agreeing, and the
// projection of an initial state that does not close its loop, announced;
// and the four-bar written in space, whose revolute loop repeats three of its
// rows, against the planar one.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "api/mbfe.h"
#include "tests/support/cli.h"
#include "tests/support/process.h"
#include "tests/support/recorded_rows.h"

namespace mbfe {
namespace {

std::string source_path(const std::string& relative) { return std::string(MBFE_SOURCE_DIR) + "/" + relative; }

runtime::SimulationRequest request(double step, double t_end, runtime::CoupledFormulation formulation) {
  runtime::SimulationRequest r;
  r.integrator = runtime::parse_integrator("rk4");
  r.step = step;
  r.t_end = t_end;
  r.every = 10;
  r.formulation = formulation;
  return r;
}

// Newton closes the loops to 1e-13 m at every evaluation: what a row shows.
constexpr double kRoundOffResidual = 1e-12;  // m

// The potential energy (J) of models/four_bar.yaml at q = (crank, coupler,
// rocker), relative joint angles, gravity -9.81 along y.
double four_bar_potential(const std::vector<double>& q) {
  const double g = 9.81;
  const double y_crank = 0.1 * std::sin(q[0]);
  const double y_coupler = 0.2 * std::sin(q[0]) + 0.35 * std::sin(q[0] + q[1]);
  const double y_rocker = 0.25 * std::sin(q[2]);
  return g * (0.4 * y_crank + 1.2 * y_coupler + 0.9 * y_rocker);
}

// models/slider_crank_3d.yaml, q = (crank, rod_qw, rod_qx, rod_qy, rod_qz,
// slider), gravity -9.81 along z: the crank turns about z (its centre of mass
// stays at z = 0) and the slider runs along x at z = 0.1; the rod's centre of
// mass is (0.2, 0, 0) in its frame, turned by the crank (about z, leaving z
// alone) and by its quaternion.
double slider_crank_potential(const std::vector<double>& q) {
  const double g = 9.81;
  const Eigen::Quaterniond rod(q[1], q[2], q[3], q[4]);
  const double z_rod = (rod.normalized().toRotationMatrix() * Eigen::Vector3d(0.2, 0, 0)).z();
  return g * (0.3 * z_rod + 0.5 * 0.1);
}

struct LoopCase {
  const char* file;
  double step, t_end;
  int nq, nv;
  double (*potential)(const std::vector<double>&);
};

// The slider-crank's run passes t = 0.61 s, where its J_d becomes
// ill-conditioned and the partitioned formulation chooses its dependent
// coordinates again (seen by printing each repartition once).
const LoopCase kCases[] = {{"models/four_bar.yaml", 1e-3, 2.0, 3, 3, four_bar_potential},
                           {"models/slider_crank_3d.yaml", 1e-4, 1.0, 6, 5, slider_crank_potential}};

struct RecordedRun {
  test::RecordedRows rows;
  std::vector<double> energy;
};

RecordedRun run_loop(const Model& model, const LoopCase& c, runtime::CoupledFormulation formulation) {
  RecordedRun out;
  const runtime::SimulationReport report = model.simulate(request(c.step, c.t_end, formulation), out.rows);
  EXPECT_EQ(report.message, "");
  for (const std::vector<double>& r : out.rows.values) {
    State s;
    s.q.assign(r.begin() + 1, r.begin() + 1 + c.nq);
    s.qd.assign(r.begin() + 1 + c.nq, r.begin() + 1 + c.nq + c.nv);
    const Evaluation e = model.evaluate(s);
    const Eigen::Map<const Eigen::VectorXd> v(s.qd.data(), c.nv);
    out.energy.push_back(0.5 * v.dot(e.M * v) + c.potential(s.q));
  }
  return out;
}

TEST(LoopSystems, PartitionedRunsKeepTheLoopsClosedAndConserveEnergy) {
  // RK4 on a smooth mechanism: the energy error is O(h^4), measured 6.7e-9 J
  // on the four-bar (h = 1 ms) and 2.5e-14 J on the slider-crank (h = 0.1 ms).
  constexpr double kEnergyTol = 1e-7;  // J
  for (const LoopCase& c : kCases) {
    SCOPED_TRACE(c.file);
    const Model model = Model::load(source_path(c.file));
    const RecordedRun r = run_loop(model, c, runtime::CoupledFormulation::kPartitioned);
    ASSERT_FALSE(r.rows.values.empty());
    EXPECT_EQ(r.rows.columns.back(), "loop_residual");
    EXPECT_EQ(r.rows.units.back(), "m");
    double worst_residual = 0.0, worst_energy = 0.0;
    for (std::size_t k = 0; k < r.rows.values.size(); ++k) {
      worst_residual = std::max(worst_residual, r.rows.values[k].back());
      worst_energy = std::max(worst_energy, std::abs(r.energy[k] - r.energy.front()));
    }
    EXPECT_LT(worst_residual, kRoundOffResidual);
    EXPECT_LT(worst_energy, kEnergyTol);
    // The crank swung through more than half a radian: the loop was exercised.
    const std::vector<double> crank = r.rows.series("crank");
    EXPECT_GT(*std::max_element(crank.begin(), crank.end()) - *std::min_element(crank.begin(), crank.end()), 0.5);
  }
}

TEST(LoopSystems, AugmentedRunsAgreeWithPartitionedOnes) {
  // Two formulations of the same ODE on the constraint manifold, each RK4
  // with its own truncation error: measured 2.5e-8 apart on the four-bar
  // (h = 1 ms), 5.0e-13 on the slider-crank (h = 0.1 ms).
  constexpr double kAgreementTol = 1e-7;
  constexpr double kAugmentedResidual = 1e-12;  // m: projected after each step
  for (const LoopCase& c : kCases) {
    SCOPED_TRACE(c.file);
    const Model model = Model::load(source_path(c.file));
    const RecordedRun partitioned = run_loop(model, c, runtime::CoupledFormulation::kPartitioned);
    const RecordedRun augmented = run_loop(model, c, runtime::CoupledFormulation::kAugmented);
    ASSERT_EQ(partitioned.rows.values.size(), augmented.rows.values.size());
    ASSERT_EQ(partitioned.rows.columns, augmented.rows.columns);
    double worst = 0.0;
    for (std::size_t k = 0; k < partitioned.rows.values.size(); ++k) {
      for (int i = 1; i <= c.nq + c.nv; ++i)
        worst = std::max(worst, std::abs(partitioned.rows.values[k][i] - augmented.rows.values[k][i]));
      EXPECT_LT(augmented.rows.values[k].back(), kAugmentedResidual);
    }
    EXPECT_LT(worst, kAgreementTol);
  }
}

TEST(LoopSystems, AnOpenInitialStateIsProjectedAndAnnounced) {
  const test::TempDir dir;
  const std::string out = (dir / "four_bar.csv").string();
  const test::CliRun r = test::run_cli(
      "simulate models/four_bar.yaml --t-end 0.01 --set initial.q.coupler=-0.5 --out " + out);
  ASSERT_EQ(r.status, 0) << r.all();
  EXPECT_NE(r.err.find("the initial state does not close the loops and was projected onto them: positions: "),
            std::string::npos)
      << r.err;
  const test::Csv csv = test::read_csv(out);
  EXPECT_EQ(csv.header, (std::vector<std::string>{"t", "crank", "coupler", "rocker", "crank_dot", "coupler_dot",
                                                  "rocker_dot", "loop_residual"}));
  ASSERT_FALSE(csv.rows.empty());
  EXPECT_LT(csv.rows.front().back(), kRoundOffResidual);
  // The crank (the largest pivot of J is elsewhere) keeps its angle: the
  // projection moves the dependent coordinates.
  constexpr double kKeptAngleTol = 1e-15;  // rad: written and read back as CSV text, a last bit
  EXPECT_NEAR(csv.rows.front()[1], 1.0, kKeptAngleTol);

  const test::CliRun strict = test::run_cli(
      "simulate models/four_bar.yaml --t-end 0.01 --strict --set initial.q.coupler=-0.5 --out " + out);
  EXPECT_EQ(strict.status, 2) << strict.all();
  EXPECT_NE(strict.err.find("(strict)"), std::string::npos) << strict.err;
}

// models/four_bar.yaml written in space: every joint turns about z, and the
// loop is a spatial revolute constraint about z. Of its five rows the z
// position and the two orientation rows hold whatever the angles (their
// Jacobian rows vanish): the closure leaves them out.
constexpr const char* kSpatialFourBar = R"(model: four_bar_space
dimension: 3
gravity: [0, -9.81, 0]
bodies:
  - {name: crank, parent: ground, joint: {type: revolute, axis: [0, 0, 1]}, mass: 0.4,
     inertia: [0.001, 0.001, 0.0015, 0, 0, 0], com: [0.1, 0, 0], points: {end: [0.2, 0, 0]}}
  - {name: coupler, parent: crank, joint: {type: revolute, axis: [0, 0, 1], at: [0.2, 0, 0]}, mass: 1.2,
     inertia: [0.01, 0.05, 0.05, 0, 0, 0], com: [0.35, 0, 0], points: {end: [0.7, 0, 0]}}
  - {name: rocker, parent: ground, joint: {type: revolute, axis: [0, 0, 1], at: [0.6, 0, 0]}, mass: 0.9,
     inertia: [0.005, 0.019, 0.019, 0, 0, 0], com: [0.25, 0, 0], points: {end: [0.5, 0, 0]}}
constraints:
  - {name: coupler_rocker, type: revolute, a: {body: coupler, point: end}, b: {body: rocker, point: end},
     axis: [0, 0, 1]}
initial: {q: {crank: 1.0, coupler: -0.5357560074605321, rocker: 1.2995365385792519}, qd: {crank: 2.0}}
)";

TEST(LoopSystems, ASpatialLoopWithRepeatedRowsMovesAsThePlanarOne) {
  // The same linkage, the same two position rows closing it, the same
  // partition: the runs differ only by the kernels' round-off, grown over
  // 2 s of a crank turning through 5 rad (measured 1.1e-12 partitioned,
  // 2.3e-12 augmented).
  constexpr double kSameRunTol = 1e-10;  // rad, rad/s
  const test::TempDir dir;
  const std::string path = (dir / "four_bar_space.yaml").string();
  std::ofstream(path) << kSpatialFourBar;
  const LoopCase planar_case = kCases[0];
  const Model planar = Model::load(source_path(planar_case.file));
  const Model spatial = Model::load(path);
  for (const runtime::CoupledFormulation formulation :
       {runtime::CoupledFormulation::kPartitioned, runtime::CoupledFormulation::kAugmented}) {
    test::RecordedRows a, b;
    const runtime::SimulationRequest r = request(planar_case.step, planar_case.t_end, formulation);
    EXPECT_EQ(planar.simulate(r, a).message, "");
    EXPECT_EQ(spatial.simulate(r, b).message, "");
    ASSERT_EQ(a.columns, b.columns);
    ASSERT_EQ(a.values.size(), b.values.size());
    double worst = 0.0, worst_residual = 0.0;
    for (std::size_t k = 0; k < a.values.size(); ++k) {
      for (int i = 1; i <= 6; ++i) worst = std::max(worst, std::abs(a.values[k][i] - b.values[k][i]));
      worst_residual = std::max(worst_residual, b.values[k].back());
    }
    EXPECT_LT(worst, kSameRunTol);
    EXPECT_LT(worst_residual, kRoundOffResidual);  // every row, the left-out ones too
  }
  // The run says which rows it left out.
  const test::CliRun run = test::run_cli("simulate " + path + " --t-end 0.01 --out /dev/null");
  ASSERT_EQ(run.status, 0) << run.all();
  EXPECT_NE(run.err.find("3 rows of loop 'coupler_rocker' repeat the conditions of the others at the initial state"),
            std::string::npos)
      << run.err;

  // Started at its dead point (every link along x) the x row vanishes too,
  // there only: it is not left out, and the run stops at the dead point.
  std::string dead = kSpatialFourBar;
  const std::string angles = "crank: 1.0, coupler: -0.5357560074605321, rocker: 1.2995365385792519";
  dead.replace(dead.find(angles), angles.size(), "crank: 0, coupler: 0, rocker: 0");
  const std::string dead_path = (dir / "four_bar_dead_point.yaml").string();
  std::ofstream(dead_path) << dead;
  const test::CliRun stopped = test::run_cli("simulate " + dead_path + " --t-end 0.01 --out /dev/null");
  EXPECT_EQ(stopped.status, 2) << stopped.all();
  EXPECT_NE(stopped.err.find("the linkage is at a dead point"), std::string::npos) << stopped.err;
}

}  // namespace
}  // namespace mbfe
