// `mbfe stability`, `mbfe simulate` (beams), `mbfe plot` and `mbfe modal`'s
// adjusted block end to end: runs the built binary (MBFE_CLI).
#include <gtest/gtest.h>
#include <unistd.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <utility>

#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/cli.h"

namespace mbfe {
namespace {

using test::CliRun;
using test::run_cli;

std::string tmp(const std::string& name) {
  return std::string(MBFE_BINARY_DIR) + "/cli_test_" + std::to_string(::getpid()) + "_" + name;
}

// docs/reference-values.md prints 6 significant digits.
constexpr double kReferenceRel = 5e-6;

// The root 1.370156e5 is known to 7 digits, the constant 2.785293563 to 10.
constexpr double kPrintedRel = 1e-5;
// At t = 1 s mode 1 (5 % damping) has decayed to ~1e-3 of the static deflection.
constexpr double kSettledTol = 1e-3;
// -3.6817 is printed with four decimals.
constexpr double kFourDecimals = 5e-5;

TEST(CmdStability, JsonContract) {
  const CliRun r = run_cli("stability models/paper_beam.yaml --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j.at("original").at("forward_euler").get<double>(), 1.52098e-8, kReferenceRel * 1.52098e-8);
  EXPECT_NEAR(j.at("adjusted").at("forward_euler").get<double>(), 1.45969e-5, kReferenceRel * 1.45969e-5);
  // RK4's real-axis limit 2.785293563 / 1.370156e5.
  EXPECT_NEAR(j.at("adjusted").at("rk4").get<double>(), 2.785293563 / 1.370156e5, kPrintedRel * 2.0328e-5);
  EXPECT_EQ(j.at("adjusted").at("explicit_midpoint"), "none");
  for (const char* a : {"backward_euler", "trapezoid", "generalized_alpha", "bdf2"}) {
    EXPECT_EQ(j.at("original").at(a), "unconditional") << a;
    EXPECT_EQ(j.at("adjusted").at(a), "unconditional") << a;
  }
}

TEST(CmdStability, PolicyMassKeepsTheCapsFastestRoot) {
  // The vehicle and bridge models ship with policy mass: their capped modes'
  // roots are the cap's, (zeta + sqrt(zeta^2 - 1)) omega_l with zeta = 1 +
  // margin / 2, so RK4's limit is its real-axis reach 2.785293563 over that
  // root: a beam-only model (modal spectrum), a coupled one in split
  // coordinates and one with a 1e9 N/m wheel-rail spring (linearised).
  const double zeta = 1.05, omega_l = 2000.0;
  const double rk4_limit = 2.785293563405282 / ((zeta + std::sqrt(zeta * zeta - 1.0)) * omega_l);
  // Dense eigenvalues of the modal matrices: round-off.
  constexpr double kModalRel = 1e-12;
  // The coupled linearisation (difference quotients) and the contact's
  // coupling move the root by 2e-8 on the moving mass, 5e-15 on the 30 m bridge.
  constexpr double kCoupledRel = 1e-6;
  for (const auto& [model, tol] : {std::pair{"bridge_moving_force", kModalRel}, std::pair{"bridge_moving_mass", kCoupledRel},
                                   std::pair{"vehicle_bridge_30m", kCoupledRel}}) {
    const CliRun r = run_cli(std::string("stability models/") + model + ".yaml --json");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_NEAR(j.at("adjusted").at("rk4").get<double>(), rk4_limit, tol * rk4_limit) << model;
  }
}

TEST(CmdStability, TextAndHelp) {
  const CliRun r = run_cli("stability models/paper_beam.yaml");
  ASSERT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("forward_euler       1.521e-08 s       1.4597e-05 s      (960x)"), std::string::npos) << r.out;
  EXPECT_EQ(run_cli("stability --help").status, 0);
  EXPECT_EQ(run_cli("stability models/double_pendulum.yaml").status, 0);  // rigid: tests/tool/cmd_stability_rigid_test.cpp
  EXPECT_EQ(run_cli("stability").status, 2);
}

TEST(CmdStability, AVehicleAtItsStaticEquilibriumGetsNoGrowthNotice) {
  const CliRun r = run_cli("stability models/bridge_two_axle_vehicle.yaml");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.find("Re > 0"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("a local estimate"), std::string::npos) << r.out;
}

TEST(CmdSimulateBeam, PaperResultFromTheCommandLine) {
  const std::string ok = tmp("ok.csv"), bad = tmp("bad.csv");
  const CliRun good = run_cli("simulate models/paper_beam.yaml --integrator forward_euler --step 1.4e-5 --t-end 1 "
                              "--probe beam1@0.5 --quiet --out '" + ok + "'");
  ASSERT_EQ(good.status, 0) << good.err;
  const CliRun div = run_cli("simulate models/paper_beam.yaml --integrator forward_euler --step 1.5e-5 --t-end 1 "
                             "--probe beam1@0.5 --quiet --out '" + bad + "'");
  EXPECT_EQ(div.status, 3);
  EXPECT_NE(div.err.find("step 1.5e-05 exceeds forward_euler's stable limit 1.4597e-05 (fastest eigenvalue "
                         "-1.3702e5)"),
            std::string::npos)
      << div.err;
  // Everything up to the divergence stays in the file: header + rows, finite.
  std::ifstream in(bad);
  std::string line, last;
  int lines = 0;
  while (std::getline(in, line)) {
    ++lines;
    last = line;
  }
  EXPECT_GT(lines, 10);
  EXPECT_EQ(last.find("nan"), std::string::npos);
  EXPECT_EQ(last.find("inf"), std::string::npos);
  // The stable run ends at t = 1 near the static deflection (2.134e-2 m down,
  // docs/reference-values.md; the 5 % floor has damped mode 1 to ~1e-3 of it).
  std::ifstream okin(ok);
  while (std::getline(okin, line)) last = line;
  const double w = std::stod(last.substr(last.find(',') + 1));
  EXPECT_EQ(last.substr(0, 2), "1,");
  EXPECT_NEAR(w, -2.134e-2, kSettledTol);
}

TEST(CmdSimulateBeam, OriginalAtThePapersFig5aSteps) {
  EXPECT_EQ(run_cli("simulate models/paper_beam.yaml --adjust off --integrator forward_euler --step 1.6e-8 "
                    "--t-end 2e-4 --quiet --out '" + tmp("o1.csv") + "'")
                .status,
            3);
  EXPECT_EQ(run_cli("simulate models/paper_beam.yaml --adjust off --integrator forward_euler --step 1.5e-8 "
                    "--t-end 2e-4 --quiet --out '" + tmp("o2.csv") + "'")
                .status,
            0);
}

TEST(CmdSimulateBeam, ColumnsAreTheBeamCoordinates) {
  const CliRun r = run_cli("simulate models/paper_beam.yaml --integrator generalized_alpha --step 1e-3 --t-end 0.01 "
                           "--quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string header = r.out.substr(0, r.out.find('\n'));
  // Pinned ends: node 0 keeps only w', node 50 only w'.
  EXPECT_EQ(header.substr(0, 28), "t,beam1_dw0,beam1_w1,beam1_d");
  EXPECT_NE(header.find(",beam1_dw50"), std::string::npos);
  EXPECT_EQ(run_cli("simulate models/paper_beam.yaml --probe beam9@0.5 --quiet").status, 2);
  EXPECT_EQ(run_cli("simulate models/paper_beam.yaml --integrator nope --quiet").status, 2);
}

TEST(CmdPlot, DrawsOrExplains) {
  const std::string csv = tmp("plot.csv"), png = tmp("plot.png");
  ASSERT_EQ(run_cli("simulate models/paper_beam.yaml --integrator rk4 --step 2e-5 --t-end 0.1 --probe beam1@0.5 "
                    "--quiet --out '" + csv + "'")
                .status,
            0);
  std::remove(png.c_str());
  // Without gnuplot on PATH: a clear message and exit 2, never a crash.
  const CliRun missing = run_cli("plot '" + csv + "' -o '" + png + "'", "PATH=/nonexistent");
  EXPECT_EQ(missing.status, 2);
  EXPECT_NE(missing.err.find("gnuplot was not found"), std::string::npos) << missing.err;
  EXPECT_EQ(run_cli("plot '" + csv + "' -o '" + png + "' --columns nope").status, 2);
  if (system("command -v gnuplot > /dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot not installed";
  const CliRun r = run_cli("plot '" + csv + "' -o '" + png + "'");
  EXPECT_EQ(r.status, 0) << r.err;
  std::ifstream f(png, std::ios::binary);
  char magic[4] = {};
  f.read(magic, 4);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
}

TEST(CmdModal, CoupledPlotDrawsEveryEigenvalueWithoutPlotterWarnings) {
  // The double pendulum on the beam starts away from equilibrium: two
  // eigenvalues with Re > 0, which the log axis of -Re cannot hold. They go on
  // the marked line; gnuplot used to say "Skipping data file with no valid
  // points" on the terminal.
  if (system("command -v gnuplot > /dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot not installed";
  const std::string png = tmp("coupled_spectrum.png");
  std::remove(png.c_str());
  const CliRun r = run_cli("modal models/double_pendulum_beam.yaml --plot '" + png + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("mbfe modal: wrote"), std::string::npos) << r.err;
  for (const char* leak : {"Skipping", "warning", "Warning", "gnuplot>"})
    EXPECT_EQ(r.err.find(leak), std::string::npos) << leak << " in: " << r.err;
  std::ifstream f(png, std::ios::binary);
  char magic[4] = {};
  f.read(magic, 4);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
  // A beam without damping: every eigenvalue has Re = 0 (gnuplot once failed
  // on the empty log range).
  const std::string yaml = tmp("undamped_beam.yaml");
  std::ofstream(yaml) << "model: undamped_beam\nbeams:\n  - {name: b, origin: [0, 0], angle: 0, length: 1.0, "
                         "elements: 6, section: {shape: square, side: 0.01},\n     material: {youngs_modulus: 2.1e11, "
                         "density: 7860}, supports: [{at: 0, type: pinned}, {at: 1.0, type: pinned}]}\n";
  const CliRun undamped = run_cli("modal '" + yaml + "' --plot '" + png + "'");
  ASSERT_EQ(undamped.status, 0) << undamped.err;
  for (const char* leak : {"Skipping", "warning", "range"})
    EXPECT_EQ(undamped.err.find(leak), std::string::npos) << leak << " in: " << undamped.err;
}

TEST(CmdModal, AdjustedBlock) {
  const CliRun r = run_cli("modal models/paper_beam.yaml --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& a = j.at("beams").at(0).at("adjusted");
  EXPECT_EQ(a.at("policy"), "cap");
  EXPECT_EQ(a.at("eigenvalues").size(), 200u);
  EXPECT_EQ(a.at("oscillatory_pairs"), 13);
  EXPECT_NEAR(a.at("h_max").at("forward_euler").get<double>(), 1.45969e-5, kReferenceRel * 1.45969e-5);
  EXPECT_NEAR(a.at("eigenvalues").at(0).at(0).get<double>(), -3.6817, kFourDecimals);
  const CliRun text = run_cli("modal models/paper_beam.yaml");
  EXPECT_NE(text.out.find("adjusted (Table 1, right half)"), std::string::npos);
  EXPECT_NE(text.out.find("gain: 960x"), std::string::npos);
}

}  // namespace
}  // namespace mbfe
