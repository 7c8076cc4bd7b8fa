// `mbfe modal` end to end: runs the built binary (MBFE_CLI) on the shipped
// models and checks the text and the JSON of `mbfe modal --json`.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <unistd.h>
#include <vector>
#include <nlohmann/json.hpp>
#include <string>
#include <sys/wait.h>

#include "tests/support/cli.h"

namespace mbfe {
namespace {

using test::CliRun;

// `mbfe ARGS`, stderr after stdout.
CliRun run_cli(const std::string& args) {
  CliRun r = test::run_cli(args);
  r.out += r.err;
  return r;
}

// JSON doubles round-trip exactly; the reference is docs/reference-values.md's h_max
// (6 digits: half a unit is 5e-14).
constexpr double kHmaxPrintedTol = 5e-14;
// s: the paper's 1.45969e-5 is given to six digits; half a unit of its last.
constexpr double kPaperSixDigitsTol = 5e-11;
// omega^2 / 1e10 written to JSON and computed here: round-off, relative.
constexpr double kModalMassRoundOff = 1e-12;

TEST(CmdModal, JsonHoldsTheContract) {
  const CliRun r = run_cli("modal models/paper_beam.yaml --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j.at("beams").size(), 1u);
  const nlohmann::json& b = j["beams"][0];
  EXPECT_EQ(b.at("name"), "beam1");
  EXPECT_EQ(b.at("dof"), 100);
  const auto omega = b.at("natural_frequencies_rad_s").get<std::vector<double>>();
  ASSERT_EQ(omega.size(), 100u);
  for (size_t i = 1; i < omega.size(); ++i) EXPECT_LT(omega[i - 1], omega[i]);
  const nlohmann::json& o = b.at("original");
  const auto& ev = o.at("eigenvalues");
  ASSERT_EQ(ev.size(), 200u);
  for (size_t i = 1; i < ev.size(); ++i) {
    EXPECT_LE(std::hypot(ev[i - 1][0].get<double>(), ev[i - 1][1].get<double>()),
              std::hypot(ev[i][0].get<double>(), ev[i][1].get<double>()));
  }
  EXPECT_EQ(o.at("oscillatory_pairs"), 13);
  EXPECT_NEAR(o.at("h_max").at("forward_euler").get<double>(), 1.52098e-8, kHmaxPrintedTol);
}

TEST(CmdModal, TextIsTable1WithASummary) {
  const CliRun r = run_cli("modal models/paper_beam.yaml");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("f damped [Hz]"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("..."), std::string::npos);
  EXPECT_NE(r.out.find("-1.314938e+08"), std::string::npos);
  EXPECT_NE(r.out.find("13 oscillatory pairs"), std::string::npos);
  EXPECT_NE(r.out.find("h_max = 1.52098e-08 s"), std::string::npos);
  const CliRun all = run_cli("modal models/paper_beam.yaml --all");
  ASSERT_EQ(all.status, 0);
  EXPECT_EQ(all.out.find("..."), std::string::npos);
  EXPECT_NE(all.out.find("\n   150 "), std::string::npos);  // a middle row, hidden without --all
  EXPECT_EQ(r.out.find("\n   150 "), std::string::npos);
}

TEST(CmdModal, BadInputExitsWithStatus2) {
  EXPECT_EQ(run_cli("modal models/double_pendulum.yaml").status, 2);  // no beams
  const CliRun unknown = run_cli("modal models/paper_beam.yaml --beam nope");
  EXPECT_EQ(unknown.status, 2);
  EXPECT_NE(unknown.out.find("beam1"), std::string::npos) << unknown.out;
  EXPECT_EQ(run_cli("modal models/paper_beam.yaml --frobnicate").status, 2);
  EXPECT_EQ(run_cli("modal --help").status, 0);
}

TEST(CmdModal, EveryShippedBeamModelRuns) {
  for (const char* m : {"models/paper_beam_a4.5.yaml", "models/paper_beam_a5.5.yaml",
                        "models/cantilever.yaml"}) {
    const CliRun r = run_cli(std::string("modal ") + m + " --json");
    ASSERT_EQ(r.status, 0) << m << ": " << r.out;
    EXPECT_GT(nlohmann::json::parse(r.out)["beams"][0]["dof"].get<int>(), 0) << m;
  }
}

TEST(CmdModal, PolicyMassShowsTheCapsSpectrumAndTheModalMasses) {
  char dir[] = "/tmp/mbfe-modal-mass-XXXXXX";
  ASSERT_NE(::mkdtemp(dir), nullptr);
  const std::string model = std::string(dir) + "/beam.yaml";
  std::string yaml = test::read_text(std::string(MBFE_SOURCE_DIR) + "/models/paper_beam.yaml");
  const std::string from = "policy: cap";
  ASSERT_NE(yaml.find(from), std::string::npos);
  yaml.replace(yaml.find(from), from.size(), "policy: mass");
  { std::ofstream(model) << yaml; }
  const CliRun r = run_cli("modal " + test::shell_quote(model) + " --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const nlohmann::json a = nlohmann::json::parse(r.out)["beams"][0].at("adjusted");
  EXPECT_EQ(a.at("policy"), "mass");
  EXPECT_EQ(a.at("adjusted_modes"), 81);  // as the cap: 19 modes kept
  // The paper's adjusted forward-Euler limit, as with the cap (to round-off of
  // the roots, 1e-14 relative).
  EXPECT_NEAR(a.at("h_max").at("forward_euler").get<double>(), 1.45969e-5, kPaperSixDigitsTol);
  const auto masses = a.at("modal_masses").get<std::vector<double>>();
  const auto omega = nlohmann::json::parse(r.out)["beams"][0].at("natural_frequencies_rad_s").get<std::vector<double>>();
  ASSERT_EQ(masses.size(), 100u);
  for (std::size_t j = 0; j < masses.size(); ++j) {
    if (j < 19) EXPECT_EQ(masses[j], 1.0) << j;
    else EXPECT_NEAR(masses[j], omega[j] * omega[j] / 1e10, kModalMassRoundOff * masses[j]) << j;
  }
  const CliRun text = run_cli("modal " + test::shell_quote(model));
  ASSERT_EQ(text.status, 0) << text.out;
  EXPECT_NE(text.out.find("adjusted (policy mass, omega_limit 100000 rad/s"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("the adjusted modes keep their stiffness"), std::string::npos) << text.out;
  std::remove(model.c_str());
  ::rmdir(dir);
}

}  // namespace
}  // namespace mbfe
