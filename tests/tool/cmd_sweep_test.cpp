// `mbfe sweep` through the real binary: a six-point speed sweep run locally on
// two jobs (each point's statistics against its own run.csv and against
// `mbfe simulate` of its model file), resumed, a failing point recorded while
// the others go on, a bad sweep file refused, and the Slurm scripts of a dry run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "tests/support/cli.h"
#include "tests/support/process.h"

namespace mbfe::test {
namespace {

std::string source(const std::string& relative) { return std::string(MBFE_SOURCE_DIR) + "/" + relative; }

int column(const Csv& c, const std::string& name) {
  const auto it = std::find(c.header.begin(), c.header.end(), name);
  EXPECT_NE(it, c.header.end()) << name;
  return static_cast<int>(it - c.header.begin());
}

TEST(Sweep, SixSpeedsLocallyRepeatableAndResumed) {
  TempDir dir;
  const std::string out = (dir / "speeds").string();
  const CliRun r = run_cli("sweep " + shell_quote(source("tests/sweep/six_speeds.yaml")) + " --out " +
                           shell_quote(out) + " --jobs 2");
  ASSERT_EQ(r.status, 0) << r.all();
  EXPECT_NE(r.err.find("6 done, 0 failed"), std::string::npos) << r.err;
  // summary.csv has no numbers-only reader here: read_csv keeps numeric cells; the
  // statistics are columns 4.. of each row.
  const Csv summary = read_csv(out + "/summary.csv");
  ASSERT_EQ(summary.rows.size(), 6u);
  const int lowest = column(summary, "midspan_lowest"), force = column(summary, "tyre_force_max");
  for (int i = 0; i < 6; ++i) {
    // The statistics of the point's own rows...
    const Csv run = read_csv(out + "/points/" + std::to_string(i) + "/run.csv");
    const int mid = column(run, "deck@10"), tyre = column(run, "force_tyre");
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& row : run.rows) {
      lo = std::min(lo, row[mid]);
      hi = std::max(hi, row[tyre]);
    }
    EXPECT_EQ(summary.rows[i][lowest], lo) << "point " << i;
    EXPECT_EQ(summary.rows[i][force], hi) << "point " << i;
    EXPECT_EQ(run.rows.back()[0], 0.6);
  }
  // ...and the same run by hand from the point's model file.
  const std::string csv = (dir / "by_hand.csv").string();
  const CliRun hand = run_cli("simulate " + shell_quote(out + "/points/2/model.yaml") +
                              " --integrator rk4 --step 1e-3 --t-end 0.6 --probe deck@10 --quiet --out " + shell_quote(csv));
  ASSERT_EQ(hand.status, 0) << hand.all();
  const Csv by_hand = read_csv(csv);
  double lo = INFINITY;
  for (const auto& row : by_hand.rows) lo = std::min(lo, row[column(by_hand, "deck@10")]);
  EXPECT_EQ(summary.rows[2][lowest], lo);
  // Speeds differ, so do the peaks.
  EXPECT_NE(summary.rows[0][lowest], summary.rows[5][lowest]);

  // Resumed: nothing runs again, the results stay as they were.
  const auto stamp = fs::last_write_time(out + "/points/3/result.json");
  const CliRun again = run_cli("sweep " + shell_quote(source("tests/sweep/six_speeds.yaml")) + " --out " +
                               shell_quote(out) + " --jobs 2");
  ASSERT_EQ(again.status, 0) << again.all();
  EXPECT_NE(again.err.find("6 points, 6 already done, 0 to run"), std::string::npos) << again.err;
  EXPECT_EQ(fs::last_write_time(out + "/points/3/result.json"), stamp);
}

TEST(Sweep, AFailingPointIsRecordedAndTheOthersGoOn) {
  TempDir dir;
  const fs::path sweep = dir / "masses.yaml";
  spit(sweep, "sweep: masses\nmodel: " + source("models/bridge_moving_mass.yaml") +
                  "\nvary:\n  - {path: bodies.wheel.mass, values: [1000.0, 0.0, 500.0]}\n"
                  "simulate: {t_end: 0.05}\n"
                  "collect:\n  - {name: tyre, column: force_tyre, stat: max}\n");
  const std::string out = (dir / "out").string();
  const CliRun r = run_cli("sweep " + shell_quote(sweep.string()) + " --out " + shell_quote(out) + " --jobs 2");
  EXPECT_EQ(r.status, 3) << r.all();
  EXPECT_NE(r.err.find("2 done, 1 failed"), std::string::npos) << r.err;
  const std::string summary = slurp(out + "/summary.csv");
  EXPECT_NE(summary.find("\n1,0.0,failed,"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\n0,1000.0,done,0,"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\n2,500.0,done,0,"), std::string::npos) << summary;
  EXPECT_NE(slurp(out + "/summary.json").find("\"failed\": 1"), std::string::npos);
}

TEST(Sweep, BadSweepFileIsRefusedBeforeAnythingRuns) {
  TempDir dir;
  const fs::path sweep = dir / "bad.yaml";
  spit(sweep, "sweep: bad\nmodel: " + source("models/bridge_moving_mass.yaml") +
                  "\nvary:\n  - {path: bodies.wheel.mas, values: [1.0]}\n");
  const std::string out = (dir / "out").string();
  const CliRun r = run_cli("sweep " + shell_quote(sweep.string()) + " --out " + shell_quote(out));
  EXPECT_EQ(r.status, 2) << r.all();
  EXPECT_NE(r.err.find("bad.yaml:4:12: path 'bodies.wheel.mas': 'wheel' has no key 'mas'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out + "/points"));
}

TEST(Sweep, SlurmDryRunWritesTheArrayAndTheCollectJob) {
  TempDir dir;
  const std::string out = (dir / "out").string();
  const CliRun r = run_cli("sweep " + shell_quote(source("tests/sweep/six_speeds.yaml")) + " --out " + shell_quote(out) +
                           " --slurm --dry-run --array-limit 2 --partition local --time 5:00 --quiet");
  ASSERT_EQ(r.status, 0) << r.all();
  const std::string points = slurp(out + "/slurm/points.sbatch");
  EXPECT_NE(points.find("#SBATCH --array=0-5%2\n"), std::string::npos) << points;
  EXPECT_NE(points.find("#SBATCH --partition=local\n"), std::string::npos) << points;
  EXPECT_NE(points.find("#SBATCH --time=5:00\n"), std::string::npos) << points;
  EXPECT_NE(points.find("--point \"$SLURM_ARRAY_TASK_ID\""), std::string::npos) << points;
  EXPECT_NE(points.find("export MBFE_CACHE_DIR="), std::string::npos) << points;
  EXPECT_NE(slurp(out + "/slurm/collect.sbatch").find(" --collect"), std::string::npos);
  EXPECT_NE(r.out.find("sbatch --dependency=afterany:"), std::string::npos) << r.out;
  // The solvers were compiled into DIR/cache for the nodes.
  EXPECT_TRUE(fs::exists(out + "/cache"));
}

}  // namespace
}  // namespace mbfe::test
