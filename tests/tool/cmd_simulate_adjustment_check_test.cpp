// `mbfe simulate --check-adjustment T` through the real binary: the figures in
// the sidecar against the same comparison made here from two CSVs, the
// adjusted run and a separate run of the original model with
// generalized_alpha at the step the check documents, and the reference's
// own change at twice its step; and the estimate written beside every
// adjusted run.
#include <gtest/gtest.h>

#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>

#include "tests/support/cli.h"
#include "tests/support/process.h"

namespace mbfe::test {
namespace {

// Both sides compare the same numbers read back exactly from the CSVs.
constexpr double kSameNumbersRel = 1e-9;
// s: row times of two runs read back from CSV, sums of different steps.
constexpr double kRowTimeTol = 1e-12;

std::string full(double x) {
  std::ostringstream o;
  o << std::setprecision(17) << x;
  return o.str();
}

/// max_t |a(t) - b(t)| / max_t |b(t)| of one column, b's rows at a's times
/// (b has `ratio` rows per row of a).
double relative_difference(const Csv& a, const Csv& b, const std::string& column, int ratio) {
  const int ca = a.column(column), cb = b.column(column);
  EXPECT_GE(ca, 0);
  EXPECT_GE(cb, 0);
  double peak = 0.0, diff = 0.0;
  for (const auto& row : b.rows) peak = std::max(peak, std::abs(row[cb]));
  for (std::size_t k = 0; k < a.rows.size(); ++k) {
    const std::size_t kb = k * static_cast<std::size_t>(ratio);
    if (kb >= b.rows.size()) break;
    EXPECT_NEAR(a.rows[k][0], b.rows[kb][0], kRowTimeTol);  // the same time
    diff = std::max(diff, std::abs(a.rows[k][ca] - b.rows[kb][cb]));
  }
  return diff / peak;
}

TEST(SimulateAdjustmentCheck, TheSidecarHoldsTheDifferenceToTheOriginalModelsImplicitRun) {
  TempDir dir;
  const std::string model = std::string(MBFE_SOURCE_DIR) + "/models/bridge_moving_mass.yaml";
  const fs::path adjusted = dir / "adjusted.csv", original = dir / "original.csv";
  constexpr double kCheck = 0.3;  // s
  // Under the cap, whose wheel force is visibly off (the shipped model is under policy mass).
  const CliRun r = run_cli("simulate " + shell_quote(model) + " --set beams.deck.adjustment.policy=cap --quiet --integrator rk4 --step 1e-3 --t-end 0.4 --every 1 " +
                           "--check-adjustment 0.3 --out " + shell_quote(adjusted.string()));
  ASSERT_EQ(r.status, 0) << r.all();
  EXPECT_NE(r.err.find("mbfe: adjustment check over 0.3 s against the original model (generalized_alpha, step "),
            std::string::npos)
      << r.err;
  const nlohmann::json record = nlohmann::json::parse(read_text(adjusted.string() + ".json"));
  ASSERT_TRUE(record.contains("adjustment_check")) << record.dump();
  const nlohmann::json& check = record["adjustment_check"];
  // The fastest frequency the run keeps: the cap, 2000 rad/s, above the
  // wheel's bounce on its tyre, sqrt(5e6 N/m / 1000 kg) = 70.7 rad/s.
  EXPECT_DOUBLE_EQ(check["omega"].get<double>(), 2000.0);
  // The step: 1e-3 s divided by the smallest whole number giving at least
  // 2000 steps over 0.3 s (7) and h omega <= 0.05 (40).
  constexpr int kRatio = 40;
  const double h = 1e-3 / kRatio;
  EXPECT_DOUBLE_EQ(check["step"].get<double>(), h);
  // The reference against itself at twice its step: far below the
  // adjustment's difference, which it bounds from below.
  ASSERT_EQ(check["reference_change"]["contact_force"]["column"], "force_tyre");
  EXPECT_LT(check["reference_change"]["contact_force"]["relative"].get<double>(),
            0.1 * check["contact_force"]["relative"].get<double>());
  EXPECT_EQ(check["integrator"], "generalized_alpha");
  EXPECT_EQ(check["message"], "");
  ASSERT_EQ(check["contact_force"]["column"], "force_tyre");

  // The same comparison by hand.
  const CliRun o = run_cli("simulate " + shell_quote(model) + " --quiet --adjust off --integrator generalized_alpha --step " +
                           full(h) + " --t-end " + full(kCheck) + " --every 1 --out " + shell_quote(original.string()));
  ASSERT_EQ(o.status, 0) << o.all();
  Csv a = read_csv(adjusted.string());
  const Csv b = read_csv(original.string());
  a.rows.erase(std::remove_if(a.rows.begin(), a.rows.end(), [&](const auto& row) { return row[0] > kCheck + 1e-12; }),
               a.rows.end());
  const double force = relative_difference(a, b, "force_tyre", kRatio);
  EXPECT_NEAR(check["contact_force"]["relative"].get<double>(), force, kSameNumbersRel * force);
  EXPECT_GT(force, 0.01);  // the cap's wheel force is visibly off (docs/accuracy-vs-cost-coupled.md)
  const std::string column = check["displacement"]["column"];
  const double displacement = relative_difference(a, b, column, kRatio);
  EXPECT_NEAR(check["displacement"]["relative"].get<double>(), displacement, kSameNumbersRel * displacement);

  // Every adjusted run records its estimate; this one is above 1 % and says so.
  ASSERT_TRUE(record.contains("adjustment_estimate")) << record.dump();
  EXPECT_EQ(record["adjustment_estimate"]["where"], "contact 'tyre' (slider_spring)");
  EXPECT_GT(record["adjustment_estimate"]["max"].get<double>(), 0.01);
  // By the linearised run (a slider_spring contact, a run of 400 steps):
  // the tyre's force over the run.
  EXPECT_NE(r.err.find("mbfe: adjustment estimate: the adjustment changes the force of contact 'tyre' (slider_spring) "
                       "by "),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(record["adjustment_estimate"].contains("linearised")) << record.dump();
  // The original model's run has no estimate.
  EXPECT_FALSE(nlohmann::json::parse(read_text(original.string() + ".json")).contains("adjustment_estimate"));
}

TEST(SimulateAdjustmentCheck, ACheckWithoutAnAdjustedRunOrBeyondTheRunIsBadInput) {
  TempDir dir;
  const std::string model = std::string(MBFE_SOURCE_DIR) + "/models/bridge_moving_mass.yaml";
  const std::string out = " --out " + shell_quote((dir / "x.csv").string());
  const CliRun off = run_cli("simulate " + shell_quote(model) + " --quiet --adjust off --t-end 0.1 --check-adjustment 0.05" + out);
  EXPECT_EQ(off.status, 2) << off.all();
  EXPECT_NE(off.err.find("--check-adjustment compares an adjusted run with the original model; this run is not adjusted"),
            std::string::npos)
      << off.err;
  const CliRun beyond = run_cli("simulate " + shell_quote(model) + " --quiet --t-end 0.1 --check-adjustment 0.2" + out);
  EXPECT_EQ(beyond.status, 2) << beyond.all();
  EXPECT_NE(beyond.err.find("--check-adjustment: expected a time in s in (0, t_end = 0.1"), std::string::npos)
      << beyond.err;
}

// The check runs the original model after the run, and can take longer: a
// Ctrl-C during it ends the check, not mbfe, and what the run computed stays
// (its rows, and the record beside them with the check's partial figures).
TEST(SimulateAdjustmentCheck, ASignalDuringTheCheckKeepsTheRunsRowsAndRecord) {
  TempDir dir;
  const std::string model = std::string(MBFE_SOURCE_DIR) + "/models/bridge_moving_mass.yaml";
  const fs::path csv = dir / "run.csv";
  constexpr double kTEnd = 5.0;  // s: the check (generalized-alpha, h omega <= 0.05 at 2000 rad/s) takes 2e5 steps
  Spawned run({MBFE_CLI, "simulate", model, "--quiet", "--t-end", "5", "--every", "10", "--check-adjustment", "5",
               "--out", csv.string()},
              {}, dir / "check.stdout", dir / "check.stderr");
  ASSERT_GT(run.pid(), 0);
  // The run has ended when its last row, at t_end, is in the CSV (rows are
  // flushed at the end of the run, before the check starts).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(300);
  bool run_ended = false;
  while (run.running() && std::chrono::steady_clock::now() < deadline && !run_ended) {
    const std::vector<std::string> lines = lines_of(slurp(csv));
    // The last line may be cut (a row being written): strtod reads its start.
    run_ended = lines.size() > 1 && std::abs(std::strtod(lines.back().c_str(), nullptr) - kTEnd) < kRowTimeTol;
    if (!run_ended) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_TRUE(run_ended) << slurp(dir / "check.stderr");
  ASSERT_TRUE(run.running()) << "the check ended before the signal: " << slurp(dir / "check.stderr");
  ASSERT_EQ(::kill(run.pid(), SIGINT), 0);
  const int status = run.wait_for(60);
  ASSERT_NE(status, -1) << "mbfe did not stop within 60 s of the signal";
  const std::string err = slurp(dir / "check.stderr");
  EXPECT_EQ(status, 3) << err;
  EXPECT_NE(err.find("mbfe simulate: the adjustment check was interrupted; the run's "), std::string::npos) << err;
  const std::size_t rows = check_complete_csv(slurp(csv));
  const nlohmann::json record = nlohmann::json::parse(slurp(csv.string() + ".json"), nullptr, false);
  ASSERT_TRUE(record.is_object()) << slurp(csv.string() + ".json");
  EXPECT_EQ(record.value("status", ""), "completed");
  EXPECT_EQ(record.value("rows", -1L), static_cast<long>(rows));
  ASSERT_TRUE(record.contains("adjustment_check"));
  EXPECT_NE(record["adjustment_check"].value("message", "").find("interrupted at t = "), std::string::npos)
      << record["adjustment_check"].dump();
}

}  // namespace
}  // namespace mbfe::test
