// `mbfe stats` end to end: the golden signal of tests/runtime/signal (SciPy's
// filtfilt of a 4th-order Butterworth, its header says how it was made)
// written as a results CSV, its statistics against sums over SciPy's output;
// the filter where one polynomial of order 2 N failed, against closed forms;
// a .npy of mbfe simulate against the CSV of the same run; and the located
// errors of bad input (NaN, times that do not increase, a device).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/cli.h"
#include "tests/support/filter_golden.h"
#include "tests/support/process.h"

namespace mbfe {
namespace {

using test::CliRun;
using test::run_cli;

// SciPy's filtered signal against ours: ~1e-11 N of rounding (see
// butterworth_test.cpp); printed by --json to 17 digits.
constexpr double kSignalTol = 1e-8;
// mean +- 3 sd: the mean's error and three times the standard deviation's.
constexpr double kThreeSigmaTol = 4 * kSignalTol;
// A number printed to JSON and read back, against the same number here.
constexpr double kPrintedRoundOff = 1e-12;

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
  EXPECT_NEAR(j.at("statistical_max").get<double>(), mean + 3 * sd, kThreeSigmaTol);
  EXPECT_NEAR(j.at("statistical_min").get<double>(), mean - 3 * sd, kThreeSigmaTol);
  EXPECT_NEAR(j.at("max").get<double>(), mx, kSignalTol);
  EXPECT_NEAR(j.at("min").get<double>(), mn, kSignalTol);
  EXPECT_NEAR(j.at("loss_percent").get<double>(), 100.0 * lost / n, kPrintedRoundOff);
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

/// A results CSV t, force of n samples at `sample_hz`, force(t).
template <class F>
std::string write_signal(const std::string& name, std::size_t n, double sample_hz, F force) {
  const std::string csv = tmp(name);
  std::ofstream out(csv);
  out.precision(17);
  out << "t,force\n";
  for (std::size_t i = 0; i < n; ++i) out << i / sample_hz << "," << force(i / sample_hz) << "\n";
  return csv;
}

// The cases where the filter, built as one polynomial of order 2 N, printed
// garbage with exit status 0: order 8 at 20 Hz of 10 kHz (a max of 9.3e211),
// order 6 at 5 Hz (1.9e28), order 5 at 20 Hz of 40 kHz (0.17 % off). Oracle:
// a slow sine passes zero-phase with gain 1 / (1 + (f / fc)^(2 order)), here
// 1 to ~1e-12; the window keeps 2 s away from the ends' start-up.
TEST(CmdStats, LowpassOfASlowSineSampledFastKeepsItsMaxAndMean) {
  struct Case {
    int order;
    double cutoff_hz, sample_hz;
  };
  constexpr double kSineHz = 0.5;
  constexpr double kAmplitudeTol = 1e-6;  // of the 10 N amplitude: start-up left, warping, rounding
  for (const Case& c : {Case{8, 20.0, 10000.0}, Case{6, 5.0, 10000.0}, Case{5, 20.0, 40000.0}}) {
    const std::size_t n = static_cast<std::size_t>(6.0 * c.sample_hz);
    const std::string csv = write_signal("stats_sine.csv", n, c.sample_hz,
                                         [&](double t) { return 100.0 + 10.0 * std::sin(2.0 * M_PI * kSineHz * t); });
    const CliRun r = run_cli("stats '" + csv + "' --column force --lowpass " + std::to_string(c.cutoff_hz) +
                             " --order " + std::to_string(c.order) + " --from 2 --to 4 --json");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    // [2, 4] s holds one whole period (2 s): the sine's max, min and zero mean.
    EXPECT_NEAR(j.at("max").get<double>(), 110.0, kAmplitudeTol * 10.0) << "order " << c.order;
    EXPECT_NEAR(j.at("min").get<double>(), 90.0, kAmplitudeTol * 10.0) << "order " << c.order;
    EXPECT_NEAR(j.at("mean").get<double>(), 100.0, kAmplitudeTol * 10.0) << "order " << c.order;
  }
}

TEST(CmdStats, AConstantFilteredAtAHundredthOfAHertzKeepsItsMean) {
  // 5 N at 1 kHz for 3 s, 0.01 Hz: the mean came out 0.0039.
  constexpr double kConstantTol = 1e-6;  // relative; see butterworth_test.cpp
  const std::string csv = write_signal("stats_constant.csv", 3000, 1000.0, [](double) { return 5.0; });
  const CliRun r = run_cli("stats '" + csv + "' --column force --lowpass 0.01 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NEAR(nlohmann::json::parse(r.out).at("mean").get<double>(), 5.0, kConstantTol * 5.0);
  // Below 1e-5 of the sample rate: refused, naming the range.
  const CliRun low = run_cli("stats '" + csv + "' --column force --lowpass 0.001");
  EXPECT_EQ(low.status, 2) << low.all();
  EXPECT_NE(low.err.find("at least 1e-05 of the sample rate"), std::string::npos) << low.err;
}

TEST(CmdStats, TheLargestDoublesKeepTheirMean) {
  // A constant 1e308: the sum overflowed and --json printed "mean": null.
  const std::string csv = write_signal("stats_huge.csv", 1000, 1000.0, [](double) { return 1e308; });
  const CliRun r = run_cli("stats '" + csv + "' --column force --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.at("mean").is_number()) << r.out;
  EXPECT_EQ(j.at("mean").get<double>(), 1e308);
  EXPECT_EQ(j.at("std").get<double>(), 0.0);
}

TEST(CmdStats, NanInfinityAndTimesThatDoNotIncreaseAreRefusedAtTheirLine) {
  // Before: max and min skipped a NaN, mean and std came out null, exit 0.
  const std::string nan = write_signal("stats_nan.csv", 100, 1000.0, [](double t) {
    return t > 0.0405 && t < 0.0415 ? std::nan("") : 10.0;
  });  // the row t = 0.041, line 43
  CliRun r = run_cli("stats '" + nan + "' --column force");
  EXPECT_EQ(r.status, 2) << r.all();
  EXPECT_NE(r.err.find(nan + ":43: column 'force' is nan"), std::string::npos) << r.err;
  const std::string inf = tmp("stats_inf.csv");
  std::ofstream(inf) << "t,force\n0,1\n0.001,inf\n0.002,1\n";
  r = run_cli("stats '" + inf + "' --column force --json");
  EXPECT_EQ(r.status, 2) << r.all();
  EXPECT_NE(r.err.find(inf + ":3: column 'force' is inf"), std::string::npos) << r.err;
  // Equal and backwards times: nulls or garbage before.
  const std::string equal = tmp("stats_equal_t.csv");
  std::ofstream(equal) << "t,force\n0,1\n0.001,2\n0.001,3\n0.002,4\n";
  r = run_cli("stats '" + equal + "' --column force --json");
  EXPECT_EQ(r.status, 2) << r.all();
  EXPECT_NE(r.err.find(equal + ":4: t = 0.001 s is not after the row before"), std::string::npos) << r.err;
  const std::string back = tmp("stats_back_t.csv");
  std::ofstream(back) << "t,force\n0,1\n0.002,2\n0.001,3\n0.003,4\n";
  r = run_cli("stats '" + back + "' --column force --lowpass 20 --json");
  EXPECT_EQ(r.status, 2) << r.all();
  EXPECT_NE(r.err.find(back + ":4: t = 0.001 s is not after the row before"), std::string::npos) << r.err;
}

TEST(CmdStats, ANpyOfSimulateGivesTheStatisticsOfItsCsv) {
  // simulate writes .npy (names in FILE.npy.json); stats read it as CSV and
  // said "no column 't' (it has 5 columns: \x93NUMPY...".
  test::TempDir dir;
  const std::string npy = (dir / "run.npy").string(), csv = (dir / "run.csv").string();
  for (const std::string& out : {npy, csv}) {
    const CliRun sim = run_cli("simulate models/double_pendulum.yaml --t-end 0.5 --every 1 --quiet --out " +
                               test::shell_quote(out));
    ASSERT_EQ(sim.status, 0) << sim.all();
  }
  const CliRun from_npy = run_cli("stats " + test::shell_quote(npy) + " --column link2 --lowpass 20 --json");
  const CliRun from_csv = run_cli("stats " + test::shell_quote(csv) + " --column link2 --lowpass 20 --json");
  ASSERT_EQ(from_npy.status, 0) << from_npy.err;
  ASSERT_EQ(from_csv.status, 0) << from_csv.err;
  // The CSV holds the shortest text that reads back as the same double: the
  // same numbers, the same statistics to the last bit.
  EXPECT_EQ(nlohmann::json::parse(from_npy.out), nlohmann::json::parse(from_csv.out));
  // Without its sidecar the names are unknown: said so.
  std::filesystem::remove(npy + ".json");
  const CliRun bare = run_cli("stats " + test::shell_quote(npy) + " --column link2");
  EXPECT_EQ(bare.status, 2) << bare.all();
  EXPECT_NE(bare.err.find(npy + ".json"), std::string::npos) << bare.err;
}

TEST(CmdStats, ADeviceOrAFolderIsRefusedBeforeReading) {
  // /dev/zero was read until memory ran out.
  const CliRun zero = run_cli("stats /dev/zero --column force", test::bounded_run_prefix());
  EXPECT_EQ(zero.status, 2) << zero.all();
  EXPECT_NE(zero.err.find("/dev/zero: cannot read the results file: not a regular file"), std::string::npos)
      << zero.err;
  const CliRun folder = run_cli("stats models --column force");
  EXPECT_EQ(folder.status, 2) << folder.all();
  EXPECT_NE(folder.err.find("models: cannot read the results file: it is a folder"), std::string::npos) << folder.err;
}

}  // namespace
}  // namespace mbfe

namespace mbfe {
namespace {

/// A results CSV with two deck acceleration probes, a displacement probe
/// and a contact force: a(t) = amplitude sin(2 pi 5 t) at deck@10, half
/// that at deck@5.
std::string acceleration_csv(const std::string& name, double amplitude) {
  const std::string path = tmp(name);
  std::ofstream out(path);
  out.precision(17);
  out << "t,deck@10,deck@10:acc,deck@5:acc,force_tyre\n";
  const double kTwoPi = 6.283185307179586;
  for (int i = 0; i <= 1000; ++i) {
    const double t = i * 1e-3;
    out << t << "," << -1e-3 << "," << amplitude * std::sin(kTwoPi * 5 * t) << ","
        << 0.5 * amplitude * std::sin(kTwoPi * 5 * t) << ",9810\n";
  }
  return path;
}

TEST(CmdStatsDeckAcceleration, PeakOfEveryAccelerationColumnAndTheEn1990Check) {
  // sin(2 pi 5 t) sampled every 1 ms peaks on the sample at t = 0.05 s: |a| = amplitude.
  const std::string csv = acceleration_csv("deck_acc.csv", 4.2);
  const CliRun r = run_cli("stats " + test::shell_quote(csv) + " --en1990 ballasted --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["columns"].size(), 2u);  // the displacement and the force are not accelerations
  EXPECT_EQ(j["columns"][0]["name"], "deck@10:acc");
  EXPECT_NEAR(j["columns"][0]["peak"].get<double>(), 4.2, kPrintedRoundOff);
  EXPECT_NEAR(j["columns"][1]["peak"].get<double>(), 2.1, kPrintedRoundOff);
  EXPECT_NEAR(j["peak"].get<double>(), 4.2, kPrintedRoundOff);
  EXPECT_EQ(j["en1990"]["limit"], 3.5);
  EXPECT_EQ(j["en1990"]["ok"], false);
  // Direct fastening allows 5 m/s^2.
  const CliRun direct = run_cli("stats " + test::shell_quote(csv) + " --en1990 direct");
  ASSERT_EQ(direct.status, 0) << direct.err;
  EXPECT_NE(direct.out.find("direct-fastened track: limit 5 m/s^2; the peak is within it"), std::string::npos)
      << direct.out;
  // One column asked for: that one alone.
  const CliRun one = run_cli("stats " + test::shell_quote(csv) + " --en1990 ballasted --column deck@5:acc --json");
  ASSERT_EQ(one.status, 0) << one.err;
  EXPECT_EQ(nlohmann::json::parse(one.out)["en1990"]["ok"], true);
}

TEST(CmdStatsDeckAcceleration, En1990AloneChecksBallastedAndReportsDirectFastened) {
  const std::string csv = acceleration_csv("deck_acc_bare.csv", 4.2);  // between 3.5 and 5 m/s^2
  const CliRun r = run_cli("stats " + test::shell_quote(csv) + " --en1990 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["en1990"]["track"], "ballasted");
  EXPECT_EQ(j["en1990"]["limit"], 3.5);
  EXPECT_EQ(j["en1990"]["ok"], false);
  ASSERT_EQ(j["en1990"]["checks"].size(), 2u);
  EXPECT_EQ(j["en1990"]["checks"][1]["track"], "direct");
  EXPECT_EQ(j["en1990"]["checks"][1]["limit"], 5.0);
  EXPECT_EQ(j["en1990"]["checks"][1]["ok"], true);
  // Before the file, and before another flag: that flag keeps its value.
  const CliRun text = run_cli("stats --en1990 " + test::shell_quote(csv));
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_NE(text.out.find("ballasted track: limit 3.5 m/s^2; the peak EXCEEDS it"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("direct-fastened track: limit 5 m/s^2; the peak is within it"), std::string::npos)
      << text.out;
  const CliRun filtered = run_cli("stats " + test::shell_quote(csv) + " --en1990 --lowpass 30");
  ASSERT_EQ(filtered.status, 0) << filtered.err;
  EXPECT_NE(filtered.out.find("low-pass 30 Hz"), std::string::npos) << filtered.out;
  EXPECT_NE(filtered.out.find("ballasted track: limit 3.5"), std::string::npos) << filtered.out;
  // Named, one track only, as before.
  const CliRun named = run_cli("stats " + test::shell_quote(csv) + " --en1990 direct --json");
  ASSERT_EQ(named.status, 0) << named.err;
  EXPECT_EQ(nlohmann::json::parse(named.out)["en1990"]["checks"].size(), 1u);
}

TEST(CmdStatsDeckAcceleration, NoAccelerationColumnOrABadTrackIsAnError) {
  const std::string csv = tmp("no_acc.csv");
  {
    std::ofstream out(csv);
    out << "t,deck@10\n0,0\n0.001,1e-3\n";
  }
  const CliRun none = run_cli("stats " + test::shell_quote(csv));
  EXPECT_EQ(none.status, 2);
  EXPECT_NE(none.err.find("--column NAME is required: " + csv + " has no deck acceleration column (BEAM@S:acc"),
            std::string::npos)
      << none.err;
  const CliRun track = run_cli("stats " + test::shell_quote(acceleration_csv("acc2.csv", 1.0)) + " --en1990 slab");
  EXPECT_EQ(track.status, 2);
  EXPECT_NE(track.err.find("--en1990 takes ballasted"), std::string::npos) << track.err;
}

TEST(CmdStats, ANpyIsKnownByItsMagicBytesWhateverItsName) {
  test::TempDir dir;
  const std::string npy = (dir / "run.npy").string(), renamed = (dir / "run.data").string();
  const CliRun sim =
      run_cli("simulate models/double_pendulum.yaml --t-end 0.2 --every 1 --quiet --out " + test::shell_quote(npy));
  ASSERT_EQ(sim.status, 0) << sim.all();
  std::filesystem::copy_file(npy, renamed);
  std::filesystem::copy_file(npy + ".json", renamed + ".json");
  const CliRun a = run_cli("stats " + test::shell_quote(npy) + " --column link2 --json");
  const CliRun b = run_cli("stats " + test::shell_quote(renamed) + " --column link2 --json");
  ASSERT_EQ(b.status, 0) << b.err;
  EXPECT_EQ(nlohmann::json::parse(a.out), nlohmann::json::parse(b.out));
}

}  // namespace
}  // namespace mbfe
