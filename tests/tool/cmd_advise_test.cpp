// `mbfe advise MODEL --tolerance TOL` through the real binary. The oracle is
// the estimate every adjusted `mbfe simulate` writes in its sidecar and the
// step `mbfe stability` reports: the limit advise prints, copied into the
// model with --set, must meet the tolerance by simulate's own estimate, a
// limit a little lower must not, and the RK4 step it prints must be
// stability's at that limit.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <regex>
#include <string>

#include "tests/support/cli.h"
#include "tests/support/process.h"

namespace mbfe::test {
namespace {

constexpr double kTolerance = 0.01;
// The estimate is printed as a percentage to one decimal: half of 0.1 %.
constexpr double kPrintedEstimateTol = 0.0005;
// The step is printed to five significant digits: 1e-4 of it.
constexpr double kPrintedStepRel = 1e-4;
// Just below the chosen limit the estimate must exceed the tolerance: the
// advise contract is "the lowest limit", not "a limit that passes".
constexpr double kLowerBy = 0.97;

const std::string kModel = std::string(MBFE_SOURCE_DIR) + "/models/bridge_moving_mass.yaml";

/// The largest estimate simulate writes in the sidecar at `omega_limit`, over
/// the model's own t_end (advise estimates the run the model file describes:
/// for a slider_spring contact the linearised run over that time).
double simulated_estimate(const TempDir& dir, const std::string& omega_limit) {
  const fs::path out = dir / ("at_" + omega_limit + ".csv");
  const CliRun r = run_cli("simulate " + shell_quote(kModel) + " --quiet --set beams.deck.adjustment.omega_limit=" +
                           omega_limit + " --every 100 --out " + shell_quote(out.string()));
  EXPECT_EQ(r.status, 0) << r.all();
  const nlohmann::json record = nlohmann::json::parse(read_text(out.string() + ".json"));
  return record["adjustment_estimate"]["max"].get<double>();
}

TEST(Advise, TheLimitItPrintsIsTheLowestThatMeetsTheToleranceBySimulatesOwnEstimate) {
  TempDir dir;
  const CliRun r = run_cli("advise " + shell_quote(kModel) + " --tolerance 0.01 --steps 20");
  ASSERT_EQ(r.status, 0) << r.all();
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, std::regex(R"(beam 'deck': omega_limit ([0-9.e+]+) rad/s; estimate ([0-9.]+) %)")))
      << r.out;
  const std::string limit = m[1];
  const double printed_estimate = std::stod(m[2]) / 100.0;
  const double at_limit = simulated_estimate(dir, limit);
  EXPECT_LE(at_limit, kTolerance);
  EXPECT_NEAR(printed_estimate, at_limit, kPrintedEstimateTol);
  EXPECT_GT(simulated_estimate(dir, std::to_string(kLowerBy * std::stod(limit))), kTolerance);

  // The RK4 step it prints is mbfe stability's at that limit.
  ASSERT_TRUE(std::regex_search(r.out, m, std::regex(R"(\nrk4 +([0-9.e+-]+) s)"))) << r.out;
  const double advised_rk4 = std::stod(m[1]);
  const CliRun s =
      run_cli("stability " + shell_quote(kModel) + " --set beams.deck.adjustment.omega_limit=" + limit + " --json");
  ASSERT_EQ(s.status, 0) << s.all();
  const double stable_rk4 = nlohmann::json::parse(s.out)["adjusted"]["rk4"].get<double>();
  EXPECT_NEAR(advised_rk4, stable_rk4, kPrintedStepRel * stable_rk4);
  EXPECT_NE(r.out.find("generalized_alpha   original model, at rk4's"), std::string::npos) << r.out;
}

TEST(Advise, RefusesWhatItCannotAdvise) {
  const CliRun no_tolerance = run_cli("advise " + shell_quote(kModel));
  EXPECT_EQ(no_tolerance.status, 2);
  EXPECT_NE(no_tolerance.err.find("--tolerance TOL is required"), std::string::npos) << no_tolerance.err;
  const CliRun out_of_range = run_cli("advise " + shell_quote(kModel) + " --tolerance 1.5");
  EXPECT_EQ(out_of_range.status, 2);
  EXPECT_NE(out_of_range.err.find("expected a relative change in (0, 1), got '1.5'"), std::string::npos)
      << out_of_range.err;
  const CliRun rigid = run_cli("advise " + shell_quote(std::string(MBFE_SOURCE_DIR) + "/models/double_pendulum.yaml") +
                               " --tolerance 0.01");
  EXPECT_EQ(rigid.status, 2);
  EXPECT_NE(rigid.err.find("has no beam with an active adjustment block"), std::string::npos) << rigid.err;
  // A truncation removes modes: no compliance estimate to choose its limit by.
  const CliRun truncated =
      run_cli("advise " + shell_quote(kModel) + " --tolerance 0.01 --set beams.deck.adjustment.policy=truncate");
  EXPECT_EQ(truncated.status, 2);
  EXPECT_NE(truncated.err.find("bridge_moving_mass.yaml:35:"), std::string::npos) << truncated.err;
  EXPECT_NE(truncated.err.find("beam 'deck' has policy truncate"), std::string::npos) << truncated.err;
}

}  // namespace
}  // namespace mbfe::test
