// `mbfe sweep` collect entries with a low-pass filter and a time window (and
// the EN 50318 statistics) against `mbfe stats` on each point's run.csv, and
// a sweep of a model whose beam reads its running surface from a CSV next to
// it: each point's model, written in another folder, still finds the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/cli.h"
#include "tests/support/process.h"

namespace mbfe::test {
namespace {

std::string source(const std::string& relative) { return std::string(MBFE_SOURCE_DIR) + "/" + relative; }

TEST(SweepCollect, FilteredAndWindowedStatisticsAreThoseOfMbfeStats) {
  TempDir dir;
  const std::string file = (dir / "filtered.yaml").string();
  spit(file, "sweep: filtered\nmodel: " + source("models/bridge_moving_mass.yaml") +
                 "\nvary:\n  - {path: contacts.tyre.damping, values: [1000, 3000]}\n"
                 "simulate: {integrator: rk4, step: 1.0e-3, t_end: 0.6, probes: [\"deck@10\"]}\n"
                 "collect:\n"
                 "  - {name: fm, column: force_tyre, stat: mean, lowpass: 20, from: 0.2, to: 0.5}\n"
                 "  - {name: fs, column: force_tyre, stat: std, lowpass: 20, from: 0.2, to: 0.5}\n"
                 "  - {name: fmax, column: force_tyre, stat: max, lowpass: 20, order: 2, from: 0.2, to: 0.5}\n"
                 "  - {name: fsmax, column: force_tyre, stat: statistical_max, lowpass: 20, from: 0.2, to: 0.5}\n"
                 "  - {name: floss, column: force_tyre, stat: loss_percent, from: 0.2}\n"
                 "  - {name: wpeak, column: \"deck@10\", stat: absmax, lowpass: 20}\n"
                 "  - {name: wraw, column: \"deck@10\", stat: absmax}\n");
  const std::string out = (dir / "out").string();
  const CliRun r = run_cli("sweep " + shell_quote(file) + " --out " + shell_quote(out) + " --jobs 2");
  ASSERT_EQ(r.status, 0) << r.all();
  const nlohmann::json summary = nlohmann::json::parse(slurp(out + "/summary.json"));
  for (int i = 0; i < 2; ++i) {
    SCOPED_TRACE("point " + std::to_string(i));
    const std::string run = out + "/points/" + std::to_string(i) + "/run.csv";
    const nlohmann::json& stats = summary["points"][i]["stats"];
    const auto stats_of = [&](const std::string& flags) {
      const CliRun s = run_cli("stats " + shell_quote(run) + " " + flags + " --json");
      EXPECT_EQ(s.status, 0) << s.all();
      return nlohmann::json::parse(s.out);
    };
    // The same code on the same doubles (run.csv holds 17 digits): the same numbers.
    const nlohmann::json force = stats_of("--column force_tyre --lowpass 20 --from 0.2 --to 0.5");
    EXPECT_EQ(stats["fm"], force["mean"]);
    EXPECT_EQ(stats["fs"], force["std"]);
    EXPECT_EQ(stats["fsmax"], force["statistical_max"]);
    EXPECT_EQ(stats["fmax"], stats_of("--column force_tyre --lowpass 20 --order 2 --from 0.2 --to 0.5")["max"]);
    EXPECT_EQ(stats["floss"], stats_of("--column force_tyre --from 0.2")["loss_percent"]);
    const nlohmann::json w = stats_of("--column deck@10 --lowpass 20");
    EXPECT_EQ(stats["wpeak"].get<double>(),
              std::max(std::abs(w["max"].get<double>()), std::abs(w["min"].get<double>())));
    // Filtered is not unfiltered: the filter did something.
    EXPECT_NE(stats["wpeak"], stats["wraw"]);
  }
  EXPECT_NE(summary["points"][0]["stats"]["fs"], summary["points"][1]["stats"]["fs"]);
}

TEST(SweepCollect, WhatMbfeStatsRefusesFailsThePointWithTheReason) {
  TempDir dir;
  const std::string file = (dir / "window.yaml").string();
  // A window after the run's end holds no sample.
  spit(file, "sweep: window\nmodel: " + source("models/double_pendulum.yaml") +
                 "\nvary:\n  - {path: bodies.link2.mass, values: [1.0]}\n"
                 "simulate: {t_end: 0.1}\ncollect:\n  - {name: late, column: link1, stat: mean, from: 5}\n");
  const CliRun r = run_cli("sweep " + shell_quote(file) + " --out " + shell_quote((dir / "out").string()));
  EXPECT_EQ(r.status, 3) << r.all();
  const nlohmann::json result = nlohmann::json::parse(slurp(dir / "out" / "points" / "0" / "result.json"));
  EXPECT_EQ(result["status"], "failed");
  EXPECT_EQ(result["exit_status"], 2);
  EXPECT_NE(result["message"].get<std::string>().find("collect 'late': "), std::string::npos) << result["message"];
  // Refused in the sweep file: initial and final take no window.
  spit(file, "sweep: window\nmodel: " + source("models/double_pendulum.yaml") +
                 "\nvary:\n  - {path: bodies.link2.mass, values: [1.0]}\n"
                 "collect:\n  - {name: last, column: link1, stat: final, lowpass: 5}\n");
  const CliRun bad = run_cli("sweep " + shell_quote(file) + " --out " + shell_quote((dir / "out2").string()));
  EXPECT_EQ(bad.status, 2) << bad.all();
  EXPECT_NE(bad.err.find("stat initial and final take the rows as written"), std::string::npos) << bad.err;
}

TEST(SweepProfileFile, EveryPointFindsTheTableBesideTheModel) {
  TempDir dir;
  std::filesystem::create_directories(dir / "models");
  std::filesystem::create_directories(dir / "sweeps");
  std::string model = slurp(source("models/bridge_moving_mass.yaml"));
  const std::string deck = "  - name: deck\n";
  const auto at = model.find(deck);
  ASSERT_NE(at, std::string::npos);
  model.insert(at + deck.size(), "    profile: {file: rail.csv}\n");
  spit(dir / "models" / "bridge.yaml", model);
  spit(dir / "models" / "rail.csv", "s,offset\n0,0\n10,-0.002\n20,0\n");
  spit(dir / "sweeps" / "rail.yaml",
       "sweep: rail\nmodel: ../models/bridge.yaml\n"
       "vary:\n  - {path: contacts.tyre.damping, values: [1000, 2000]}\n"
       "simulate: {t_end: 0.2}\ncollect:\n  - {name: f, column: force_tyre, stat: max}\n");
  const std::string out = (dir / "out").string();
  const CliRun r = run_cli("sweep " + shell_quote((dir / "sweeps" / "rail.yaml").string()) + " --out " +
                           shell_quote(out) + " --jobs 2");
  ASSERT_EQ(r.status, 0) << r.all();
  EXPECT_NE(r.err.find("2 done, 0 failed"), std::string::npos) << r.err;
  // Read by hand from its own folder, the point's model finds the table too
  // (generate --expanded reads the table and compiles nothing).
  const CliRun hand = run_cli("generate " + shell_quote(out + "/points/1/model.yaml") + " --expanded");
  EXPECT_EQ(hand.status, 0) << hand.all();
  EXPECT_NE(hand.out.find((dir / "models" / "rail.csv").string()), std::string::npos) << hand.out;
}

}  // namespace
}  // namespace mbfe::test
