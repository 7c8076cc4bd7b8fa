// `mbfe stats` end to end: the golden signal of tests/runtime/signal (SciPy's
// filtfilt of a 4th-order Butterworth, its header says how it was made)
// written as a results CSV, its statistics against sums over SciPy's output,
// and the located errors of bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/cli.h"
#include "tests/support/filter_golden.h"

namespace mbfe {
namespace {

using test::CliRun;
using test::run_cli;

// SciPy's filtered signal against ours: ~1e-11 N of rounding (see
// butterworth_test.cpp); printed by --json to 17 digits.
constexpr double kSignalTol = 1e-8;

using Golden = test::FilterGolden;

std::string tmp(const std::string& name) { return ::testing::TempDir() + "/" + name; }

TEST(CmdStats, JsonOfAFilteredWindowMatchesScipysSignal) {
  const Golden g = test::read_filter_golden();
  const std::string csv = tmp("stats_force.csv");
  {
    std::ofstream out(csv);
    out.precision(17);
    out << "t,other,force_contact\n";
    for (std::size_t i = 0; i < g.t.size(); ++i) out << g.t[i] << ",0," << g.x[i] << "\n";
  }
  const CliRun r = run_cli("stats '" + csv + "' --column force_contact --lowpass 20 --from 0.5 --to 1.5 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  // Exactly the contract's keys.
  EXPECT_EQ(j.size(), 7u);
  double sum = 0, mx = -1e300, mn = 1e300;
  int n = 0, lost = 0;
  for (std::size_t i = 0; i < g.t.size(); ++i) {
    if (g.t[i] < 0.5 || g.t[i] > 1.5) continue;
    ++n;
    sum += g.y[i];
    mx = std::max(mx, g.y[i]);
    mn = std::min(mn, g.y[i]);
    lost += g.x[i] <= 0.0;
  }
  const double mean = sum / n;
  double sum2 = 0;
  for (std::size_t i = 0; i < g.t.size(); ++i)
    if (g.t[i] >= 0.5 && g.t[i] <= 1.5) sum2 += (g.y[i] - mean) * (g.y[i] - mean);
  const double sd = std::sqrt(sum2 / n);
  EXPECT_NEAR(j.at("mean").get<double>(), mean, kSignalTol);
  EXPECT_NEAR(j.at("std").get<double>(), sd, kSignalTol);
  EXPECT_NEAR(j.at("statistical_max").get<double>(), mean + 3 * sd, 4 * kSignalTol);
  EXPECT_NEAR(j.at("statistical_min").get<double>(), mean - 3 * sd, 4 * kSignalTol);
  EXPECT_NEAR(j.at("max").get<double>(), mx, kSignalTol);
  EXPECT_NEAR(j.at("min").get<double>(), mn, kSignalTol);
  EXPECT_NEAR(j.at("loss_percent").get<double>(), 100.0 * lost / n, 1e-12);
  // The text form says the same, with names.
  const CliRun text = run_cli("stats '" + csv + "' --column force_contact --lowpass 20");
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_NE(text.out.find("statistical_max"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("2000 samples"), std::string::npos) << text.out;
}

TEST(CmdStats, BadInputIsLocated) {
  const std::string csv = tmp("stats_bad.csv");
  std::ofstream(csv) << "t,force\n0,1\n0.001,2\n0.002,x3\n";
  CliRun r = run_cli("stats '" + csv + "' --column force");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find(csv + ":4: column 'force' (field 2): 'x3' is not a number"), std::string::npos) << r.err;
  r = run_cli("stats '" + csv + "' --column nope");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find(csv + ":1: no column 'nope'"), std::string::npos) << r.err;
  r = run_cli("stats '" + csv + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--column NAME is required"), std::string::npos) << r.err;
  const std::string uneven = tmp("stats_uneven.csv");
  std::ofstream u(uneven);
  u << "t,force\n";
  for (int i = 0; i < 100; ++i) u << (i == 50 ? 0.0505 : i * 1e-3) << ",1\n";
  u.close();
  r = run_cli("stats '" + uneven + "' --column force --lowpass 20");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("not evenly spaced"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace mbfe
