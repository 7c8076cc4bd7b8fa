// `mbfe sweep` through the real binary: a six-point speed sweep run locally on
// two jobs (each point's statistics against its own run.csv and against
// `mbfe simulate` of its model file), resumed, a failing point recorded while
// the others go on, a bad sweep file refused, and the Slurm scripts of a dry run;
// a resume after the simulate: or collect: block changed runs the points again,
// the sweep file's set: in every point (a --set of the same path wins),
// a sweep of a spatial model with a closed loop,
// a message with non-ASCII text stays a result, devices and arguments a Slurm
// script cannot carry are refused.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "frontend/parse_model.h"
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

TEST(Sweep, TheSweepFilesSetReachesEveryPointAndACommandLineSetWins) {
  TempDir dir;
  const std::string file = (dir / "set.yaml").string();
  spit(file, "sweep: set_masses\nmodel: " + source("models/double_pendulum.yaml") +
                 "\nset: {bodies.link1.mass: 3.5}\n"
                 "vary:\n  - {path: bodies.link2.mass, values: [1.5, 2.5]}\n"
                 "simulate: {t_end: 0.01}\ncollect:\n  - {name: last, column: link1, stat: final}\n");
  for (const std::string& extra : {std::string(), std::string(" --set bodies.link1.mass=4.5")}) {
    SCOPED_TRACE(extra);
    const std::string out = (dir / (extra.empty() ? "a" : "b")).string();
    const CliRun r = run_cli("sweep " + shell_quote(file) + " --out " + shell_quote(out) + " --jobs 2" + extra);
    ASSERT_EQ(r.status, 0) << r.all();
    for (int i = 0; i < 2; ++i) {
      const ir::Model m = frontend::load_model_file(out + "/points/" + std::to_string(i) + "/model.yaml");
      EXPECT_EQ(m.bodies[0].mass, extra.empty() ? 3.5 : 4.5) << "point " << i;
      EXPECT_EQ(m.bodies[1].mass, i == 0 ? 1.5 : 2.5) << "point " << i;
    }
  }
}

TEST(Sweep, SpatialLoopModelPointsRunAndCollect) {
  constexpr double kRoundOffResidual = 1e-12;  // m: the partitioned formulation's closure
  TempDir dir;
  const std::string out = (dir / "masses").string();
  const CliRun r = run_cli("sweep " + shell_quote(source("tests/sweep/slider_crank_masses.yaml")) + " --out " +
                           shell_quote(out) + " --jobs 2");
  ASSERT_EQ(r.status, 0) << r.all();
  EXPECT_NE(r.err.find("3 done, 0 failed"), std::string::npos) << r.err;
  const Csv summary = read_csv(out + "/summary.csv");
  ASSERT_EQ(summary.rows.size(), 3u);
  const int residual = column(summary, "residual_max"), spin = column(summary, "rod_spin_final");
  for (int i = 0; i < 3; ++i) {
    const Csv run = read_csv(out + "/points/" + std::to_string(i) + "/run.csv");
    EXPECT_LT(summary.rows[i][residual], kRoundOffResidual) << "point " << i;
    EXPECT_EQ(summary.rows[i][spin], run.rows.back()[column(run, "rod_wx")]) << "point " << i;
  }
  // A heavier slider changes the motion.
  EXPECT_NE(summary.rows[0][spin], summary.rows[2][spin]);
}

TEST(Sweep, RunCsvKeepsTheBeamStateOnlyWhenAskedFor) {
  // No probes: a point's rows hold every beam coordinate, which run.csv
  // leaves out by default; the statistics still see them, and equal those
  // of `mbfe simulate` of the point's model (which writes every coordinate).
  TempDir dir;
  const auto run_sweep = [&](const std::string& name, const std::string& extra) {
    const fs::path sweep = dir / (name + ".yaml");
    spit(sweep, "sweep: " + name + "\nmodel: " + source("models/bridge_moving_mass.yaml") +
                    "\nvary:\n  - {path: bodies.wheel.mass, values: [1000.0, 500.0]}\n"
                    "simulate: {t_end: 0.05" + extra + "}\n"
                    "collect:\n  - {name: node20, column: deck_w20, stat: min}\n"
                    "  - {name: node20_rate, column: deck_w20_dot, stat: max}\n");
    const std::string out = (dir / name).string();
    const CliRun r = run_cli("sweep " + shell_quote(sweep.string()) + " --out " + shell_quote(out) + " --jobs 2");
    EXPECT_EQ(r.status, 0) << r.all();
    return out;
  };
  const std::string lean = run_sweep("lean", ""), full = run_sweep("full", ", full_state: true");
  const Csv run = read_csv(lean + "/points/1/run.csv");
  EXPECT_EQ(run.header, (std::vector<std::string>{"t", "carriage", "wheel", "carriage_dot", "wheel_dot", "phi_abs",
                                                  "force_tyre", "deflection_tyre", "carriage_drive"}));
  const Csv kept = read_csv(full + "/points/1/run.csv");
  ASSERT_GE(kept.column("deck_w20"), 0);
  ASSERT_GE(kept.column("deck_dw3_dot"), 0);
  const std::string csv = (dir / "by_hand.csv").string();
  const CliRun hand =
      run_cli("simulate " + shell_quote(lean + "/points/1/model.yaml") + " --t-end 0.05 --quiet --out " + shell_quote(csv));
  ASSERT_EQ(hand.status, 0) << hand.all();
  const Csv by_hand = read_csv(csv);
  double lo = INFINITY;
  for (const auto& row : by_hand.rows) lo = std::min(lo, row[by_hand.column("deck_w20")]);
  for (const std::string& out : {lean, full}) {
    const Csv summary = read_csv(out + "/summary.csv");
    EXPECT_EQ(summary.rows[1][column(summary, "node20")], lo) << out;
  }
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

/// A two-point sweep of the double pendulum whose simulate: and collect:
/// blocks are given; the final t of each run is collected as `t_last`.
void write_pendulum_sweep(const fs::path& file, const std::string& simulate, const std::string& stat = "final") {
  spit(file, "sweep: pendulum\nmodel: " + source("models/double_pendulum.yaml") +
                 "\nvary:\n  - {path: bodies.link1.mass, values: [1.0, 2.0]}\n"
                 "simulate: " + simulate + "\n"
                 "collect:\n  - {name: t_last, column: t, stat: " + stat + "}\n");
}

TEST(Sweep, AResumeAfterTheSimulateOrCollectBlockChangedRunsThePointsAgain) {
  TempDir dir;
  const fs::path sweep = dir / "pendulum.yaml";
  const std::string out = (dir / "out").string();
  const std::string command = "sweep " + shell_quote(sweep.string()) + " --out " + shell_quote(out) + " --jobs 2";
  write_pendulum_sweep(sweep, "{t_end: 0.05}");
  CliRun r = run_cli(command);
  ASSERT_EQ(r.status, 0) << r.all();
  EXPECT_NE(slurp(out + "/summary.csv").find("\n0,1.0,done,0,0.050000000000000003,"), std::string::npos) << slurp(out + "/summary.csv");
  // t_end changed: the old points (t_last 0.05) were kept and summarised as
  // done, without a word.
  write_pendulum_sweep(sweep, "{t_end: 0.1}");
  r = run_cli(command);
  ASSERT_EQ(r.status, 0) << r.all();
  EXPECT_NE(r.err.find("2 points hold results of another request"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("2 points, 0 already done, 2 to run"), std::string::npos) << r.err;
  std::string summary = slurp(out + "/summary.csv");
  EXPECT_NE(summary.find("\n0,1.0,done,0,0.10000000000000001,"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\n1,2.0,done,0,0.10000000000000001,"), std::string::npos) << summary;
  // The same request again: nothing runs.
  r = run_cli(command);
  EXPECT_NE(r.err.find("2 points, 2 already done, 0 to run"), std::string::npos) << r.err;
  // The collect entry's statistic changed (final to initial): the stored
  // number is of the other statistic.
  write_pendulum_sweep(sweep, "{t_end: 0.1}", "initial");
  const CliRun collect = run_cli("sweep " + shell_quote(sweep.string()) + " --out " + shell_quote(out) + " --collect");
  EXPECT_EQ(collect.status, 3) << collect.all();
  EXPECT_NE(collect.err.find("0 done, 0 failed, 2 missing (2 with a result of another request)"), std::string::npos)
      << collect.err;
  EXPECT_NE(slurp(out + "/summary.csv").find("its result is of another request"), std::string::npos);
  r = run_cli(command);
  ASSERT_EQ(r.status, 0) << r.all();
  summary = slurp(out + "/summary.csv");
  EXPECT_NE(summary.find("\n0,1.0,done,0,0,"), std::string::npos) << summary;
}

TEST(Sweep, AMessageCutInTheMiddleOfLongNonAsciiTextIsStillARecordedFailure) {
  // A value of 30 euro signs (3 bytes each) where a number goes: the message
  // quotes 40 bytes of it. Cut in the middle of a character, it made the
  // point's result.json throw (nlohmann type_error.316): no result, the point
  // "missing" for ever.
  TempDir dir;
  const fs::path sweep = dir / "euro.yaml";
  std::string euros;
  for (int i = 0; i < 30; ++i) euros += "\xE2\x82\xAC";
  spit(sweep, "sweep: euro\nmodel: " + source("models/double_pendulum.yaml") +
                  "\nvary:\n  - {path: bodies.link1.mass, values: [1.0, \"" + euros + "\"]}\n"
                  "simulate: {t_end: 0.01}\n");
  const std::string out = (dir / "out").string();
  const CliRun r = run_cli("sweep " + shell_quote(sweep.string()) + " --out " + shell_quote(out) + " --jobs 1");
  EXPECT_EQ(r.status, 3) << r.all();
  EXPECT_NE(r.err.find("1 done, 1 failed"), std::string::npos) << r.err;
  const std::string result = slurp(out + "/points/1/result.json");
  EXPECT_NE(result.find("\"exit_status\": 2"), std::string::npos) << result;
  EXPECT_NE(result.find("mass"), std::string::npos) << result;
  EXPECT_NE(slurp(out + "/summary.json").find("\"failed\": 1"), std::string::npos);
}

TEST(Sweep, ADeviceAsTheModelTheSweepFileOrAResultIsNeverRead) {
  // `model: /dev/zero` was read until memory ran out.
  TempDir dir;
  const fs::path sweep = dir / "zero.yaml";
  spit(sweep, "sweep: zero\nmodel: /dev/zero\nvary:\n  - {path: bodies.a.mass, values: [1.0]}\n");
  const std::string out = (dir / "out").string();
  CliRun r = run_cli("sweep " + shell_quote(sweep.string()) + " --out " + shell_quote(out), bounded_run_prefix());
  EXPECT_EQ(r.status, 2) << r.all();
  EXPECT_NE(r.err.find("zero.yaml:2:8: model file '/dev/zero': cannot read: not a regular file"), std::string::npos)
      << r.err;
  r = run_cli("sweep /dev/zero --out " + shell_quote(out), bounded_run_prefix());
  EXPECT_EQ(r.status, 2) << r.all();
  EXPECT_NE(r.err.find("/dev/zero: cannot read: not a regular file"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  // A point's result.json replaced by a pipe that nobody writes (as a device,
  // it was read without end; a pipe blocked for ever): the point counts as
  // not run, and the summary is written.
  const fs::path pendulum = dir / "pendulum.yaml";
  write_pendulum_sweep(pendulum, "{t_end: 0.01}");
  r = run_cli("sweep " + shell_quote(pendulum.string()) + " --out " + shell_quote(out) + " --jobs 1 --quiet");
  ASSERT_EQ(r.status, 0) << r.all();
  fs::remove(out + "/points/0/result.json");
  ASSERT_EQ(::mkfifo((out + "/points/0/result.json").c_str(), 0600), 0);
  r = run_cli("sweep " + shell_quote(pendulum.string()) + " --out " + shell_quote(out) + " --collect",
              bounded_run_prefix());
  EXPECT_EQ(r.status, 3) << r.all();
  EXPECT_NE(r.err.find("1 done, 0 failed, 1 missing"), std::string::npos) << r.err;
}

TEST(Sweep, SlurmScriptsQuoteEveryPathAndRefuseControlCharacters) {
  TempDir dir;
  // One solver for both points (the initial angle is no constant of the
  // generated code): --slurm compiles it into DIR/cache first.
  const fs::path sweep = dir / "angles.yaml";
  spit(sweep, "sweep: angles\nmodel: " + source("models/double_pendulum.yaml") +
                  "\nvary:\n  - {path: initial.q.link1, values: [0.1, 0.2]}\nsimulate: {t_end: 0.01}\n");
  // A newline in --out wrote a line of its own into points.sbatch.
  const std::string injected = (dir / "out\n#SBATCH --wrap=evil").string();
  CliRun r = run_cli("sweep " + shell_quote(sweep.string()) + " --out " +
                     shell_quote(injected) + " --slurm --dry-run --quiet");
  EXPECT_EQ(r.status, 2) << r.all();
  EXPECT_NE(r.err.find("holds the control character \\x0A"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(injected));
  r = run_cli("sweep " + shell_quote(sweep.string()) + " --out " +
              shell_quote((dir / "o").string()) + " --slurm --dry-run --quiet --partition " + shell_quote("a\nb"));
  EXPECT_EQ(r.status, 2) << r.all();
  // A space broke --output=; a % would be taken for one of Slurm's patterns.
  const std::string out = (dir / "runs of 50% \"load\"").string();
  r = run_cli("sweep " + shell_quote(sweep.string()) + " --out " + shell_quote(out) +
              " --slurm --dry-run --quiet");
  ASSERT_EQ(r.status, 0) << r.all();
  const std::string points = slurp(out + "/slurm/points.sbatch");
  // sbatch reads an #SBATCH value in double quotes with \ escaping; %% is a
  // literal %, %a the task.
  const std::string folder = (dir / "runs of 50%% \\\"load\\\"").string();
  EXPECT_NE(points.find("#SBATCH --output=\"" + folder + "/slurm/point-%a.out\"\n"), std::string::npos) << points;
  EXPECT_NE(points.find("--out " + shell_quote(out) + " --point"), std::string::npos) << points;
  EXPECT_NE(points.find("export MBFE_CACHE_DIR=" + shell_quote(out + "/cache") + "\n"), std::string::npos) << points;
  EXPECT_NE(slurp(out + "/slurm/collect.sbatch").find("#SBATCH --output=\"" + folder + "/slurm/collect.out\"\n"),
            std::string::npos);
}

}  // namespace
}  // namespace mbfe::test

namespace mbfe::test {
namespace {

/// A two-point sweep of `model` (the double pendulum's starting angle).
std::string pendulum_sweep(const TempDir& dir, const std::string& model) {
  const std::string path = (dir / "pend.yaml").string();
  std::ofstream(path) << "sweep: pend\nmodel: " << model
                      << "\nvary:\n  - {path: initial.q.link1, values: [0.1, 0.2]}\n"
                         "simulate: {t_end: 0.2}\ncollect:\n  - {name: final_link2, column: link2, stat: final}\n";
  return path;
}

TEST(CmdSweepSet, ASetRunsEveryPointAsTheEditedModelAndReachesTheSlurmScripts) {
  TempDir dir;
  const std::string shipped = std::string(MBFE_SOURCE_DIR) + "/models/double_pendulum.yaml";
  std::string text = read_text(shipped);
  const auto at = text.find("    mass: 1.0\n", text.find("  - name: link2"));
  text.replace(at, 14, "    mass: 2.5\n");
  const std::string edited = (dir / "edited.yaml").string();
  std::ofstream(edited) << text;
  TempDir other;
  const std::string out_set = (dir / "set").string(), out_edited = (other / "edited").string();
  const CliRun a = run_cli("sweep " + shell_quote(pendulum_sweep(dir, shipped)) + " --out " + shell_quote(out_set) +
                           " --jobs 2 --quiet --set bodies.link2.mass=2.5");
  ASSERT_EQ(a.status, 0) << a.all();
  const CliRun b = run_cli("sweep " + shell_quote(pendulum_sweep(other, edited)) + " --out " +
                           shell_quote(out_edited) + " --jobs 2 --quiet");
  ASSERT_EQ(b.status, 0) << b.all();
  // The summaries agree but for the wall times: compare the collected column.
  const auto final_values = [](const std::string& summary) {
    std::vector<std::string> out;
    std::istringstream in(read_text(summary));
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) out.push_back(line.substr(0, line.find(",", line.find("done,0,") + 7)));
    return out;
  };
  EXPECT_EQ(final_values(out_set + "/summary.csv"), final_values(out_edited + "/summary.csv"));
  EXPECT_EQ(final_values(out_set + "/summary.csv").size(), 2u);

  const CliRun bad = run_cli("sweep " + shell_quote(pendulum_sweep(dir, shipped)) + " --out " +
                             shell_quote((dir / "bad").string()) + " --quiet --set bodies.link2.mas=2.5");
  EXPECT_EQ(bad.status, 2) << bad.all();
  EXPECT_NE(bad.err.find(shipped + ":12:5: unknown key 'mas'"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("(the value came from --set bodies.link2.mas=2.5)"), std::string::npos) << bad.err;

  const std::string slurm_out = (dir / "slurm").string();
  const CliRun slurm = run_cli("sweep " + shell_quote(pendulum_sweep(dir, shipped)) + " --out " +
                               shell_quote(slurm_out) + " --slurm --dry-run --quiet --set bodies.link2.mass=2.5");
  ASSERT_EQ(slurm.status, 0) << slurm.all();
  for (const char* script : {"points.sbatch", "collect.sbatch"})
    EXPECT_NE(read_text(slurm_out + "/slurm/" + script).find(" --set 'bodies.link2.mass=2.5' "), std::string::npos)
        << script;
}

}  // namespace
}  // namespace mbfe::test
