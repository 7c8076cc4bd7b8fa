// The model's warnings (tool/model_warnings_notice.h) in every command that
// reads a model, through the real binary: the moving-mass bridge with its
// deck's E = 210 (GPa typed as Pa). Each command prints the warning once on
// stderr and lists it under "warnings" of its JSON output; its exit status is
// that of the same command on the shipped model (E = 2.1e11), which warns of
// nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/support/cli.h"
#include "tests/support/process.h"

namespace mbfe::test {
namespace {

std::string source(const std::string& relative) { return std::string(MBFE_SOURCE_DIR) + "/" + relative; }

/// What api/model_warnings.cpp says of E = 210 Pa, after the model's file:line:col.
constexpr const char* kWarning = "warning: beam 'deck': E = 210 Pa is 1e9 times below steel's 2.1e11 Pa: GPa entered as Pa?";

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

/// Replaces `from` (which must be there) by `to` in `text`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

/// The shipped moving-mass bridge started as written (its static start
/// fails with E in GPa, for the reason the warning gives: the deck sags 7.6e7 m)
/// on a coarse mesh, and the same file with E in GPa typed as Pa. The warning points at the
/// deck's entry, line 27.
struct Models {
  TempDir dir;
  std::string plausible = (dir / "bridge.yaml").string();
  std::string gpa = (dir / "bridge_gpa.yaml").string();
  Models() {
    // Four elements instead of 40: stability and advise linearize the model.
    const std::string text = replaced(
        replaced(slurp(source("models/bridge_moving_mass.yaml")), "initial: {static: true}", "initial: {}"),
        "elements: 40", "elements: 4");
    spit(plausible, text);
    spit(gpa, replaced(text, "youngs_modulus: 2.1e11", "youngs_modulus: 210"));
  }
};

/// Runs `command MODEL rest` on both models; expects the same exit status, no
/// warning from the shipped model and the warning once, at the material's
/// line, from the other. Returns the run of the mistyped model.
CliRun expect_warned_once(const Models& m, const std::string& command, const std::string& rest) {
  const CliRun shipped = run_cli(command + " " + shell_quote(m.plausible) + " " + rest);
  const CliRun mistyped = run_cli(command + " " + shell_quote(m.gpa) + " " + rest);
  EXPECT_EQ(mistyped.status, shipped.status) << command << "\n" << shipped.all() << "\n" << mistyped.all();
  EXPECT_EQ(count_of(shipped.err, "warning"), 0u) << command << "\n" << shipped.err;
  EXPECT_EQ(count_of(mistyped.err, kWarning), 1u) << command << "\n" << mistyped.err;
  EXPECT_EQ(count_of(mistyped.err, m.gpa + ":27:5:"), 1u) << command << "\n" << mistyped.err;
  return mistyped;
}

/// The "warnings" of a JSON output: the one line about E.
void expect_json_warning(const std::string& out, const std::string& command) {
  const nlohmann::json j = nlohmann::json::parse(out);
  ASSERT_TRUE(j.contains("warnings")) << command << "\n" << out;
  ASSERT_EQ(j["warnings"].size(), 1u) << command << "\n" << out;
  EXPECT_NE(j["warnings"][0].get<std::string>().find(kWarning), std::string::npos) << command;
}

TEST(ModelWarningsNotice, EvalWarnsOnceAndListsItInItsJson) {
  const Models m;
  const CliRun r = expect_warned_once(m, "eval", "--q 0,-0.001 --json");
  EXPECT_EQ(r.status, 0) << r.all();
  expect_json_warning(r.out, "eval");
  // Without --json the output is unchanged; the warning is on stderr only.
  const CliRun text = expect_warned_once(m, "eval", "--q 0,-0.001");
  EXPECT_EQ(text.out.find("warning"), std::string::npos) << text.out;
}

TEST(ModelWarningsNotice, StabilityWarnsOnceAndListsItInItsJson) {
  const Models m;
  const CliRun r = expect_warned_once(m, "stability", "--json");
  expect_json_warning(r.out, "stability");
}

TEST(ModelWarningsNotice, ModalWarnsOnceAndListsItInItsJson) {
  const Models m;
  const CliRun r = expect_warned_once(m, "modal", "--beam deck --json");
  EXPECT_EQ(r.status, 0) << r.all();
  expect_json_warning(r.out, "modal");
}

TEST(ModelWarningsNotice, AdviseWarnsOnce) {
  const Models m;
  expect_warned_once(m, "advise", "--tolerance 0.01 --steps 2");
}

TEST(ModelWarningsNotice, SweepWarnsOnceNotPerPointAndListsItInItsSummary) {
  const Models m;
  // Three speeds, each its own point, of the mistyped model.
  const fs::path sweep = m.dir / "speeds.yaml";
  spit(sweep, "sweep: speeds\nmodel: bridge_gpa.yaml\nvary:\n"
              "  - {path: bodies.carriage.joint.motion, values: [\"10*t\", \"20*t\", \"30*t\"]}\n"
              "simulate: {integrator: rk4, step: 1.0e-3, t_end: 0.01}\n"
              "collect:\n  - {name: tyre_force_max, column: force_tyre, stat: max}\n");
  const std::string out = (m.dir / "out").string();
  const CliRun r = run_cli("sweep " + shell_quote(sweep.string()) + " --out " + shell_quote(out) + " --jobs 2");
  EXPECT_EQ(count_of(r.err, kWarning), 1u) << r.err;
  const nlohmann::json summary = nlohmann::json::parse(slurp(out + "/summary.json"));
  ASSERT_EQ(summary["warnings"].size(), 1u) << summary.dump(2);
  EXPECT_NE(summary["warnings"][0].get<std::string>().find(m.gpa + ":27:5:"), std::string::npos) << summary.dump(2);
  EXPECT_NE(summary["warnings"][0].get<std::string>().find(kWarning), std::string::npos) << summary.dump(2);
  // The points' runs say nothing of it, and they are done: exit 0.
  EXPECT_EQ(r.status, 0) << r.all();
  EXPECT_EQ(summary["done"], 3) << summary.dump(2);
  for (int i = 0; i < 3; ++i)
    EXPECT_EQ(slurp(out + "/points/" + std::to_string(i) + "/result.json").find("warning"), std::string::npos);
  // A point's value that brings a warning of its own is named once, at the
  // first point's model file; the sweep's own stays as it was.
  const fs::path lengths = m.dir / "lengths.yaml";
  spit(lengths, "sweep: lengths\nmodel: bridge_gpa.yaml\nvary:\n"
                "  - {path: beams.deck.material.density, values: [7.85, 7.85, 7850]}\n"
                "simulate: {integrator: rk4, step: 1.0e-3, t_end: 0.001}\n"
                "collect:\n  - {name: tyre_force_max, column: force_tyre, stat: max}\n");
  const std::string out2 = (m.dir / "out2").string();
  const CliRun d = run_cli("sweep " + shell_quote(lengths.string()) + " --out " + shell_quote(out2) + " --collect");
  EXPECT_EQ(count_of(d.err, kWarning), 1u) << d.err;
  EXPECT_EQ(count_of(d.err, "density = 7.85 kg/m^3"), 1u) << d.err;
  EXPECT_EQ(count_of(d.err, "points/0/model.yaml:"), 1u) << d.err;
  // --collect with no point run: every point missing, exit 3 as before.
  EXPECT_EQ(d.status, 3) << d.all();
  const nlohmann::json collected = nlohmann::json::parse(slurp(out2 + "/summary.json"));
  EXPECT_EQ(collected["warnings"].size(), 2u) << collected.dump(2);
}

}  // namespace
}  // namespace mbfe::test
