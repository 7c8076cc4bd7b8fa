// Coupled simulations: partitioned versus augmented, |Phi| of the
// partitioned formulation, and the paper's coupled result (Section 7): the
// adjusted platform model steps stably with forward Euler at 0.95 x the limit
// of its linearised, partitioned spectrum and diverges at 1.05 x; the original
// model diverges at 1.6e-8 s.
#include <gtest/gtest.h>

#include <cmath>
#include <Eigen/SparseCholesky>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>

#include "tests/support/cli.h"
#include "api/mbfe.h"
#include "runtime/simulation/assembled_model.h"
#include "api/solver_cache.h"
#include "runtime/integrators/integrator.h"
#include "runtime/coupled/augmented_system.h"
#include "runtime/coupled/coordinate_partitioning.h"
#include "runtime/integrators/simulation_driver.h"
#include "frontend/parse_model.h"
#include "runtime/coupled/linearization.h"
#include "runtime/stability/step_limits.h"
#include "runtime/structure/adjusted_structures.h"

namespace mbfe::coupled_test {
namespace {

using runtime::SimulationStatus;

std::string model_path(const std::string& name) { return std::string(MBFE_SOURCE_DIR) + "/models/" + name; }

// A coupled model with the dynamics of one run and its initial coordinates.
struct CoupledModel {
  std::shared_ptr<runtime::AssembledModel> assembled;
  std::shared_ptr<runtime::CoupledDynamics> dynamics;
  Eigen::VectorXd q0, qd0;
};

CoupledModel load_coupled(const ir::Model& model, bool adjusted) {
  CoupledModel cm;
  cm.assembled = std::make_shared<runtime::AssembledModel>(model, load_solver(model, /*quiet=*/true).model);
  cm.dynamics = cm.assembled->make_dynamics(adjusted);
  cm.assembled->initial_coordinates(cm.q0, cm.qd0);
  return cm;
}

runtime::StateSpectrum coupled_spectrum(const ir::Model& model, bool adjusted) {
  return runtime::model_spectrum(*load_coupled(model, adjusted).assembled, adjusted).full;
}

struct Final {
  Eigen::VectorXd q, qd;
  runtime::ContactReport report;
  runtime::SimulationResult result;
  double phi_max_seen = 0.0;
};

Final simulate(CoupledModel& cm, bool augmented, const std::string& integrator, double h, double t_end) {
  std::unique_ptr<runtime::CoupledSystem> sys;
  if (augmented)
    sys = std::make_unique<runtime::AugmentedSystem>(cm.dynamics);
  else
    sys = std::make_unique<runtime::PartitionedSystem>(cm.dynamics);
  const Eigen::VectorXd y0 = sys->initial_state(0.0, cm.q0, cm.qd0);
  runtime::SimulationOptions opt;
  opt.step = h;
  opt.t_end = t_end;
  opt.divergence_factor = 1e4;
  opt.every = 1;
  Final f;
  Eigen::VectorXd y_last = y0;
  double t_last = 0.0;
  f.result = runtime::run_simulation(*sys, runtime::parse_integrator(integrator), y0, opt,
                                     [&](double t, const Eigen::VectorXd& y) {
                                       y_last = y;
                                       t_last = t;
                                       if (!augmented) f.phi_max_seen = std::max(f.phi_max_seen, sys->report(t, y).phi_max);
                                     });
  if (f.result.status == SimulationStatus::kCompleted) {
    sys->full_state(t_last, y_last, f.q, f.qd);
    f.report = sys->report(t_last, y_last);
  }
  return f;
}

// Partitioned and augmented formulations integrate the same ODE in different
// coordinates; with RK4 at 1e-5 s (inside its limit 2.0e-5 s for the adjusted
// beam) both carry local errors ~h^5 |y^(5)|, and the augmented one a drift of
// |Phi| of the same order. Over 0.05 s the rigid angles must agree to 1e-7 rad
// (three orders above the ~1e-10 the two error sources amount to) and the
// contact force to 1e-5 relative.
constexpr double kFormulationAngleTol = 1e-7;
constexpr double kFormulationForceRelTol = 1e-5;
// The partitioned formulation closes v by Newton to below 1e-10 m at every
// evaluation: |Phi| of every accepted state stays below that.
constexpr double kClosureTol = 1e-10;

TEST(CoupledSimulation, PartitionedAndAugmentedAgreeOnDoublePendulumBeam) {
  const ir::Model model = frontend::load_model_file(model_path("double_pendulum_beam.yaml"));
  CoupledModel cm = load_coupled(model, true);
  const Final p = simulate(cm, false, "rk4", 1e-5, 0.05);
  const Final a = simulate(cm, true, "rk4", 1e-5, 0.05);
  ASSERT_EQ(p.result.status, SimulationStatus::kCompleted) << p.result.message;
  ASSERT_EQ(a.result.status, SimulationStatus::kCompleted) << a.result.message;
  for (int i = 0; i < cm.dynamics->nb(); ++i) EXPECT_NEAR(p.q[i], a.q[i], kFormulationAngleTol) << "q_b " << i;
  // Beam coordinates (m, rad): the same scale of agreement relative to their size.
  const double beam_scale = p.q.tail(cm.dynamics->nc()).cwiseAbs().maxCoeff();
  EXPECT_LT((p.q - a.q).tail(cm.dynamics->nc()).cwiseAbs().maxCoeff(), 1e-5 * beam_scale);
  ASSERT_EQ(p.report.lambda.size(), 1);
  EXPECT_NEAR(p.report.lambda[0], a.report.lambda[0], kFormulationForceRelTol * std::abs(p.report.lambda[0]));
  // The tip moved: the comparison is not of two states at rest.
  EXPECT_GT(std::abs(p.q[0] - cm.q0[0]), 1e-3);
  std::printf("[ coupled  ] after 0.05 s: q_b partitioned %.12f %.12f, augmented %.12f %.12f; lambda %.9g / %.9g N\n",
              p.q[0], p.q[1], a.q[0], a.q[1], p.report.lambda[0], a.report.lambda[0]);
}

TEST(CoupledSimulation, PartitionedKeepsConstraintsClosed) {
  for (const char* name : {"double_pendulum_beam.yaml", "paper_platform.yaml"}) {
    SCOPED_TRACE(name);
    const ir::Model model = frontend::load_model_file(model_path(name));
    CoupledModel cm = load_coupled(model, true);
    const Final p = simulate(cm, false, "rk4", 1e-5, 0.02);
    ASSERT_EQ(p.result.status, SimulationStatus::kCompleted) << p.result.message;
    EXPECT_LT(p.phi_max_seen, kClosureTol);
    std::printf("[ coupled  ] %s: max |Phi| over 2000 rk4 steps = %.3g m\n", name, p.phi_max_seen);
  }
}

// The paper's coupled result. Stable at 0.95 x the predicted limit over 0.1 s
// (7,000 steps: the fastest mode, |1 + h lambda| = 0.9, is damped 1e-300 times
// over); at 1.05 x, |1 + h lambda| = 1.1 amplifies round-off (1e-16) past the
// divergence bound within ~500 steps (7 ms of simulated time), so 0.05 s is
// ample. The original model at 1.6e-8 s: its limit is ~1.5e-8 s.
TEST(CoupledSimulation, PaperPlatformAdjustedStableAtLimitAndOriginalDivergesAt1p6e8) {
  const ir::Model model = frontend::load_model_file(model_path("paper_platform.yaml"));
  const runtime::IntegratorSpec fe = runtime::parse_integrator("forward_euler");
  const runtime::StateSpectrum adj = coupled_spectrum(model, true);
  const runtime::StateSpectrum orig = coupled_spectrum(model, false);
  const runtime::StepLimit h_adj = runtime::stable_step(fe, adj.eigenvalues);
  const runtime::StepLimit h_orig = runtime::stable_step(fe, orig.eigenvalues);
  ASSERT_EQ(h_adj.kind, runtime::StepLimit::Kind::kFinite);
  ASSERT_EQ(h_orig.kind, runtime::StepLimit::Kind::kFinite);
  // The limits are set by the beams' fastest (capped / original) eigenvalues,
  // not by the mechanism: the beam-only values 1.45969e-5 and 1.52098e-8 s of
  // docs/reference-values.md (6 digits); the contacts touch the low modes, not these.
  constexpr double kReferenceDigits = 1e-5;  // relative: 6 printed digits
  EXPECT_NEAR(h_adj.h, 1.45969e-5, kReferenceDigits * 1.45969e-5);
  EXPECT_NEAR(h_orig.h, 1.52098e-8, kReferenceDigits * 1.52098e-8);
  EXPECT_LT(h_orig.h, 1.6e-8);
  std::printf("[ coupled  ] paper_platform forward Euler limits: original %s s (eigenvalue %.6g%+.6gi), "
              "adjusted %s s (eigenvalue %.6g%+.6gi); gain %.1fx\n",
              h_orig.text().c_str(), h_orig.critical.real(), h_orig.critical.imag(), h_adj.text().c_str(),
              h_adj.critical.real(), h_adj.critical.imag(), h_adj.h / h_orig.h);

  // `mbfe stability --json` predicts the same limits (the same linearisation).
  const test::CliRun st = test::run_cli("stability models/paper_platform.yaml --json");
  ASSERT_EQ(st.status, 0) << st.all();
  const nlohmann::json limits = nlohmann::json::parse(st.out);
  EXPECT_DOUBLE_EQ(limits.at("adjusted").at("forward_euler").get<double>(), h_adj.h);
  EXPECT_DOUBLE_EQ(limits.at("original").at("forward_euler").get<double>(), h_orig.h);
  const test::CliRun md = test::run_cli("modal models/paper_platform.yaml --json");
  ASSERT_EQ(md.status, 0) << md.all();
  EXPECT_EQ(nlohmann::json::parse(md.out).at("coupled").at("states").get<int>(), 402);

  CoupledModel adjusted = load_coupled(model, true);
  const Final stable = simulate(adjusted, false, "forward_euler", 0.95 * h_adj.h, 0.1);
  EXPECT_EQ(stable.result.status, SimulationStatus::kCompleted) << stable.result.message;
  EXPECT_LT(stable.phi_max_seen, kClosureTol);
  const Final unstable = simulate(adjusted, false, "forward_euler", 1.05 * h_adj.h, 0.05);
  EXPECT_NE(unstable.result.status, SimulationStatus::kCompleted);
  std::printf("[ coupled  ] adjusted, forward Euler: 0.95 x limit %s to t = %.4g s; 1.05 x limit stopped at t = %.4g s\n",
              stable.result.status == SimulationStatus::kCompleted ? "completed" : "FAILED", stable.result.t,
              unstable.result.t);

  CoupledModel original = load_coupled(model, false);
  const Final orig_run = simulate(original, false, "forward_euler", 1.6e-8, 4e-5);
  EXPECT_NE(orig_run.result.status, SimulationStatus::kCompleted);
  std::printf("[ coupled  ] original, forward Euler at 1.6e-8 s: stopped at t = %.4g s (%lld steps)\n",
              orig_run.result.t, static_cast<long long>(orig_run.result.steps));
}

TEST(CoupledSimulation, CliWritesContactColumnsAndExitsThreeOnDivergence) {
  const std::string csv = std::string(MBFE_BINARY_DIR) + "/coupled_cli_test.csv";
  test::CliRun r = test::run_cli("simulate models/paper_platform.yaml --integrator forward_euler --step 1.4e-5 --t-end 0.01 --quiet "
                     "--probe beam1@0.5,beam2@0.5 --out '" + csv + "'");
  ASSERT_EQ(r.status, 0) << r.all();
  test::Csv c = test::read_csv(csv);
  ASSERT_FALSE(c.rows.empty());
  for (const char* col : {"t", "carrier_x", "arm", "beam1@0.5", "beam2@0.5", "carrier_x_dot", "beam2@0.5_dot",
                          "lambda_arm_pin_1", "lambda_arm_pin_2", "lambda_cp2_slider", "phi_abs"})
    EXPECT_GE(c.column(col), 0) << col;
  for (const auto& row : c.rows) EXPECT_LT(row[c.column("phi_abs")], kClosureTol);
  // Diverging: exit 3, the message names t, the step, the integrator and the limit; rows kept.
  r = test::run_cli("simulate models/paper_platform.yaml --integrator forward_euler --step 1.6e-5 --t-end 0.05 --quiet "
              "--out '" + csv + "'");
  EXPECT_EQ(r.status, 3) << r.all();
  EXPECT_NE(r.all().find("diverged at t = "), std::string::npos) << r.all();
  EXPECT_NE(r.all().find("forward_euler's stable limit"), std::string::npos) << r.all();
  c = test::read_csv(csv);
  EXPECT_GT(c.rows.size(), 1u);
  // Formulation flag.
  EXPECT_EQ(test::run_cli("simulate models/paper_platform.yaml --formulation lagrange --quiet").status, 2);
  EXPECT_EQ(test::run_cli("simulate models/double_pendulum.yaml --formulation augmented --quiet").status, 2);
}

}  // namespace
}  // namespace mbfe::coupled_test

namespace mbfe::coupled_test {
namespace {

// The adjusted beams of the paper platform as the coupled model holds them
// (runtime/structure/adjusted_structures.h): their free acceleration, a
// closed form without a solve with M_adj, equals M^-1 (P - C_adj q' - K_adj q)
// by a sparse LDLT solve. Both are exact identities in exact arithmetic; the
// difference is rounding in sums of terms up to |K q| / |M| ~ 1e12 |q|, so it
// is judged relative to the largest term (1e-9 leaves ~3 orders over double
// rounding).
constexpr double kAccelerationRelTol = 1e-9;

TEST(CoupledSimulation, AdjustedBeamAccelerationMatchesForceAndSolve) {
  const ir::Model model = frontend::load_model_file(model_path("paper_platform.yaml"));
  const runtime::BeamModel beams = runtime::analyse_beams(model);
  const runtime::CoupledBeams coupled = runtime::coupled_beams(beams, true);
  ASSERT_EQ(coupled.structures.size(), beams.beams.size());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const auto& s : coupled.structures) {
    const int n = s->size(), off = s->ranges().front().offset;
    const int nc = static_cast<int>(beams.dof);
    Eigen::VectorXd q = Eigen::VectorXd::Zero(nc), qd = q, f = q, a = q;
    for (int i = off; i < off + n; ++i) {
      q[i] = 1e-3 * u(rng);
      qd[i] = 1e-1 * u(rng);
    }
    const runtime::BeamPart& part = beams.beams[static_cast<std::size_t>(&s - coupled.structures.data())];
    runtime::LowRankStructure::Workspace ws = s->make_workspace();
    s->free_acceleration(q.data(), qd.data(), nullptr, a.data(), ws);
    s->add_internal_force(q.data(), qd.data(), f.data(), ws);
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(part.system.M);
    const Eigen::VectorXd ref = ldlt.solve(part.system.P - f.segment(off, n));
    EXPECT_LT((a.segment(off, n) - ref).cwiseAbs().maxCoeff(), kAccelerationRelTol * ref.cwiseAbs().maxCoeff())
        << s->name();
  }
  // Without --adjust (or without an adjustment) a beam keeps its own C and K.
  const runtime::CoupledBeams original = runtime::coupled_beams(beams, false);
  EXPECT_TRUE(original.structures.empty());
  EXPECT_EQ(original.beams.front().structure, -1);
}

}  // namespace
}  // namespace mbfe::coupled_test

namespace mbfe::coupled_test {
namespace {

// A slider that runs off its beam: the double pendulum on a short beam
// (0.6 .. 1.0 m) whose tip swings left past the beam's start. Exit 3, the
// message names the contact, t and s; the rows up to there are in the file.
TEST(CoupledSimulation, SliderOffTheBeamNamesContactTimeAndValue) {
  std::ifstream in(model_path("double_pendulum_beam.yaml"));
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = yaml.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    yaml.replace(at, from.size(), to);
  };
  replace("model: double_pendulum_beam", "model: slider_off_test");
  replace("origin: [0.0, 0.0]", "origin: [0.6, 0.0]");
  replace("length: 1.0", "length: 0.4");
  replace("{at: 1.0, type: pinned}", "{at: 0.4, type: pinned}");
  const std::string dir = std::string(MBFE_BINARY_DIR);
  const std::string path = dir + "/coupled_slider_off_test.yaml";
  std::ofstream(path) << yaml;
  const std::string csv = dir + "/coupled_slider_off_test.csv";
  const test::CliRun r = test::run_cli("simulate '" + path + "' --integrator rk4 --step 1e-5 --t-end 0.5 --quiet --out '" + csv + "'");
  EXPECT_EQ(r.status, 3) << r.all();
  // One time, the contact, s and the beam's interval.
  EXPECT_NE(r.all().find("contact 'tip_slider' left beam 'beam1' at t = "), std::string::npos) << r.all();
  EXPECT_EQ(r.all().find("failed at t = "), std::string::npos) << r.all();
  EXPECT_NE(r.all().find("s = -"), std::string::npos) << r.all();
  EXPECT_NE(r.all().find("outside the beam's [0, 0.4] m"), std::string::npos) << r.all();
  const test::Csv c = test::read_csv(csv);
  ASSERT_GT(c.rows.size(), 100u);
  EXPECT_GT(c.rows.back()[0], 0.1);  // the run got well under way before the tip left
}

}  // namespace
}  // namespace mbfe::coupled_test
