// The stability advisor's limits against runs: for each case, a run just
// below the reported limit stays bounded and one just above it grows (or, for
// "none", a run at a small step grows all the same).
//
// Nonlinear models do not diverge to infinity above a linear limit: a
// pendulum mode that grows swings wider, its frequency drops, and the growth
// saturates. So growth is read as the amplitude late in the run against its
// amplitude at the start.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "api/mbfe.h"
#include "runtime/simulation/run_diagnosis.h"
#include "tests/support/recorded_rows.h"

namespace mbfe {
namespace {

using Rows = test::RecordedRows;

runtime::SimulationReport run(const Model& model, const char* integrator, double step, double t_end, Rows& rows,
                              long every = 1) {
  runtime::SimulationRequest r;
  r.integrator = runtime::parse_integrator(integrator);
  r.step = step;
  r.t_end = t_end;
  r.every = every;
  return model.simulate(r, rows);
}

runtime::StepLimit limit(const Model& model, const char* integrator) {
  for (const runtime::StepLimitRow& row : model.step_limits())
    if (row.integrator.name == integrator) return row.original;
  ADD_FAILURE() << "no row " << integrator;
  return {};
}

/// Largest |column - centre| over rows with t <= t_until, and over the last tenth of the rows.
std::pair<double, double> start_and_end_amplitude(const Rows& rows, int column, double centre, double t_until) {
  double start = 0.0, end = 0.0;
  const std::size_t tail = rows.values.size() - rows.values.size() / 10;
  for (std::size_t i = 0; i < rows.values.size(); ++i) {
    const double a = std::abs(rows.values[i][column] - centre);
    if (rows.values[i][0] <= t_until) start = std::max(start, a);
    if (i >= tail) end = std::max(end, a);
  }
  return {start, end};
}

// The shipped double pendulum, released 0.05 rad from its stable equilibrium:
// small swings, where the linearisation holds.
std::string small_swing_pendulum() {
  return R"yaml(model: double_pendulum_small
gravity: [0, -9.81]
bodies:
  - {name: link1, parent: ground, joint: {type: revolute, at: [0, 0]}, mass: 1.0, inertia: 0.08333333333333333,
     com: [0.5, 0], points: {tip: [1.0, 0]}}
  - {name: link2, parent: link1, joint: {type: revolute, at: [1.0, 0]}, mass: 1.0, inertia: 0.08333333333333333,
     com: [0.5, 0]}
initial: {q: {link1: -1.5207963267948966}}
)yaml";
}

// Growth factors read as "bounded" and "grows": well apart from 1 so that
// neither the start-up nor the saturation decides.
constexpr double kGrows = 3.0;

TEST(AdvisorRuns, DoublePendulumHasNoForwardEulerStepAndRk4HoldsJustBelowItsLimit) {
  const Model model = Model::parse(small_swing_pendulum(), "double_pendulum_small.yaml");
  // link2's angle relative to link1: 0 at the equilibrium and at the start.
  constexpr int kLink2 = 2;
  const runtime::StepLimit fe = limit(model, "forward_euler");
  EXPECT_EQ(fe.kind, runtime::StepLimit::Kind::kNone);
  EXPECT_EQ(fe.critical.real(), 0.0);  // an undamped mode, the reason
  {
    // "none": even at a step 40x below RK4's limit the swing grows.
    Rows rows;
    run(model, "forward_euler", 0.01, 30.0, rows);
    const auto [start, end] = start_and_end_amplitude(rows, kLink2, 0.0, 3.0);
    EXPECT_GT(end, kGrows * start);
  }
  const runtime::StepLimit rk4 = limit(model, "rk4");
  ASSERT_EQ(rk4.kind, runtime::StepLimit::Kind::kFinite);
  // The swing's amplitude in the first 3 s of the run below the limit is the
  // scale both runs are read against (above the limit it grows within 3 s).
  double start = 0.0;
  {
    Rows rows;
    run(model, "rk4", 0.95 * rk4.h, 400.0, rows);
    double end = 0.0;
    std::tie(start, end) = start_and_end_amplitude(rows, kLink2, 0.0, 3.0);
    EXPECT_LT(end, start) << "h = 0.95 x " << rk4.h;
  }
  {
    Rows rows;
    run(model, "rk4", 1.05 * rk4.h, 400.0, rows);
    const double end = start_and_end_amplitude(rows, kLink2, 0.0, 3.0).second;
    EXPECT_GT(end, kGrows * start) << "h = 1.05 x " << rk4.h;
  }
}

TEST(AdvisorRuns, ARigidModelAwayFromEquilibriumIsJudgedAtItsEquilibrium) {
  // The shipped double pendulum starts near horizontal: at that state the
  // linearisation has +-sigma pairs, and the mirror image -sigma alone once
  // gave forward Euler 0.51 s, where a run at 0.1 s diverges.
  const Model model = Model::load(std::string(MBFE_SOURCE_DIR) + "/models/double_pendulum.yaml");
  const runtime::ModelSpectrum spectrum = model.spectrum(false);
  EXPECT_TRUE(spectrum.at_equilibrium);
  EXPECT_EQ(spectrum.growing_at_start, 2);
  EXPECT_EQ(limit(model, "forward_euler").kind, runtime::StepLimit::Kind::kNone);
  Rows rows;
  const runtime::SimulationReport report = run(model, "forward_euler", 0.1, 10.0, rows);
  EXPECT_FALSE(report.message.empty()) << "forward Euler at 0.1 s should diverge";
}

TEST(AdvisorRuns, AVehicleReleasedFromItsStaticEquilibriumHasNoGrowingEigenvalue) {
  // At their static start the difference linearisation's zero modes (the
  // driven carriage) and undamped modes came out with Re up to +6.7e-9
  // max |lambda| (differencing noise), and `mbfe stability` once said 4 or 5
  // of them make "the motion leave the initial state". They are now
  // linearised from their tangents (runtime/coupled/coupled_tangents.h), the
  // driven pair exactly zero; runtime/coupled/linearization.h tells what noise
  // remains from growth.
  for (const char* name :
       {"bridge_moving_mass", "bridge_two_axle_vehicle", "vehicle_bridge_30m", "vehicle_random_track"}) {
    const Model model = Model::load(std::string(MBFE_SOURCE_DIR) + "/models/" + name + ".yaml");
    ASSERT_TRUE(model.ir().initial.static_start) << name;
    for (bool adjusted : {false, true}) {
      const runtime::ModelSpectrum s = model.spectrum(adjusted);
      EXPECT_EQ(s.growing, 0) << name << (adjusted ? " adjusted" : " original");
      // The driven carriage's zero pair is exactly zero.
      EXPECT_GE(std::count(s.full.eigenvalues.begin(), s.full.eigenvalues.end(), std::complex<double>(0.0, 0.0)), 2)
          << name;
    }
  }
}

TEST(AdvisorRuns, ADivergedVehicleRunNamesItsUndampedModeNotRoundOff) {
  // Forward Euler on the adjusted moving-mass bridge has no stable step: the
  // deck's first bending mode is undamped (zeta_min 0, the tyre over a
  // support at the start). The diagnosis of the diverged run names that mode,
  // omega_1 = (pi / L)^2 sqrt(E I / (rho A)) = 12.762 rad/s (closed form for a
  // simply supported beam). The difference linearisation blamed the step
  // instead: "exceeds forward_euler's stable limit 6.5118e-12 (fastest
  // eigenvalue -1.1007e-5 + 1.8387e3i)", an undamped mode whose Re is
  // differencing noise.
  const Model model = Model::load(std::string(MBFE_SOURCE_DIR) + "/models/bridge_moving_mass.yaml");
  const double omega1 = std::pow(M_PI / 20.0, 2) * std::sqrt(2.1e11 * 1.0e-4 / (7850.0 * 0.01));
  Rows rows;
  const runtime::SimulationReport report = run(model, "forward_euler", 1e-4, 0.3, rows);
  ASSERT_EQ(report.run.status, runtime::SimulationStatus::kDiverged) << report.message;
  EXPECT_NE(report.message.find("forward_euler has no stable step for this model (eigenvalue " +
                                runtime::eigenvalue_text({0.0, omega1}) + ")"),
            std::string::npos)
      << report.message;
}

TEST(AdvisorRuns, CoupledChainOnACantileverDivergesJustAboveTheLimitOnly) {
  // Three links hinged in a zig-zag, the last one's tip pinned to the free end
  // of a clamped cantilever (10 elements, Rayleigh damping): the limit is set
  // by a damped beam mode, the motion starts away from equilibrium.
  const Model model = Model::parse(R"yaml(model: cantilever_chain
gravity: [0, -9.81]
bodies:
  - {name: link1, parent: ground, joint: {type: revolute, at: [0.9469032985320074, 1.3510876690304123]},
     mass: 1.0, inertia: 0.02, com: [0.25, 0], points: {tip: [0.5, 0]}}
  - {name: link2, parent: link1, joint: {type: revolute, at: [0.5, 0]}, mass: 1.0, inertia: 0.02,
     com: [0.25, 0], points: {tip: [0.5, 0]}}
  - {name: link3, parent: link2, joint: {type: revolute, at: [0.5, 0]}, mass: 1.0, inertia: 0.02,
     com: [0.25, 0], points: {tip: [0.5, 0]}}
beams:
  - name: cantilever
    origin: [0.0, 0.0]
    angle: 0.0
    length: 1.0
    elements: 10
    section: {shape: square, side: 0.01}
    material: {youngs_modulus: 2.1e11, density: 7860}
    supports: [{at: 0.0, type: clamped}]
    damping: {rayleigh: {alpha: 1.0e-2, beta: 2.0e-5}}
contacts:
  - {name: tip_pin, type: pin, body: link3, point: tip, beam: cantilever, at: 1.0}
initial: {q: {link1: -1.0, link2: -0.5, link3: -0.6}}
)yaml",
                                   "cantilever_chain.yaml");
  const runtime::StepLimit fe = limit(model, "forward_euler");
  ASSERT_EQ(fe.kind, runtime::StepLimit::Kind::kFinite);
  {
    Rows rows;
    const runtime::SimulationReport below = run(model, "forward_euler", 0.9 * fe.h, 0.3, rows);
    EXPECT_TRUE(below.message.empty()) << below.message;
  }
  {
    Rows rows;
    const runtime::SimulationReport above = run(model, "forward_euler", 1.1 * fe.h, 0.3, rows);
    EXPECT_EQ(above.run.status, runtime::SimulationStatus::kDiverged);
  }
}

// The two-span catenary's spectrum is partial (3,846 states: Arnoldi's two
// ends); forward Euler's limit is set in its middle, by a lightly damped wire
// mode just below the cap (about -85 + 1497i 1/s), which the ends miss: they
// gave 6.4e-4 s, where a run at 3e-4 s diverges within 0.12 s.
TEST(AdvisorRuns, TwoSpanCatenaryAdjustedForwardEulerLimitIsSetInTheMiddleOfItsSpectrum) {
  const Model model = Model::load(std::string(MBFE_SOURCE_DIR) + "/models/pantograph_catenary_2span.yaml");
  std::optional<runtime::StepLimit> fe;
  for (const runtime::StepLimitRow& row : model.step_limits())
    if (row.integrator.name == "forward_euler") fe = row.adjusted;
  ASSERT_TRUE(fe && fe->kind == runtime::StepLimit::Kind::kFinite);
  // A run much shorter than the model's 1.39 s: the critical mode grows by a
  // factor of about 1.025 a step at twice the limit (diverged within 0.1 s),
  // and 0.9 of an 8-fold overstated limit diverges as fast.
  constexpr double kRun = 0.4;  // s
  constexpr long kEvery = 1000;  // rows are not read: the status is the check
  {
    Rows rows;
    const runtime::SimulationReport below = run(model, "forward_euler", 0.9 * fe->h, kRun, rows, kEvery);
    EXPECT_EQ(below.run.status, runtime::SimulationStatus::kCompleted) << below.message;
  }
  {
    Rows rows;
    const runtime::SimulationReport above = run(model, "forward_euler", 2.0 * fe->h, kRun, rows, kEvery);
    EXPECT_EQ(above.run.status, runtime::SimulationStatus::kDiverged);
  }
}

}  // namespace
}  // namespace mbfe
