// `--set PATH=VALUE` on the command line: simulate and eval with an override
// give what the edited file gives; a bad PATH, a bad VALUE or a flag without
// '=' exit 2 with a message in the model file that names the --set.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "tests/support/cli.h"
#include "tests/support/process.h"

namespace mbfe {
namespace {

using test::CliRun;
using test::run_cli;
using test::shell_quote;

const std::string kModel = "models/double_pendulum.yaml";

/// The shipped double pendulum with link2's mass written as `mass`.
std::string edited_pendulum(const test::TempDir& dir, const std::string& mass) {
  std::string text = test::read_text(std::string(MBFE_SOURCE_DIR) + "/" + kModel);
  const std::string link2 = "  - name: link2";
  const std::string old_mass = "    mass: 1.0\n";
  const auto at = text.find(old_mass, text.find(link2));
  text.replace(at, old_mass.size(), "    mass: " + mass + "\n");
  const std::string path = (dir / "double_pendulum.yaml").string();
  std::ofstream(path) << text;
  return path;
}

TEST(CmdSimulateSet, AnOverrideRunsAsTheEditedFile) {
  test::TempDir dir;
  const std::string edited = edited_pendulum(dir, "2.5");
  const std::string set_csv = (dir / "set.csv").string(), edited_csv = (dir / "edited.csv").string();
  const CliRun a = run_cli("simulate " + kModel + " --set bodies.link2.mass=2.5 --t-end 0.5 --quiet --out " +
                           shell_quote(set_csv));
  ASSERT_EQ(a.status, 0) << a.all();
  const CliRun b = run_cli("simulate " + shell_quote(edited) + " --t-end 0.5 --quiet --out " + shell_quote(edited_csv));
  ASSERT_EQ(b.status, 0) << b.all();
  EXPECT_EQ(test::read_text(set_csv), test::read_text(edited_csv));
  // And not the file as it is.
  const CliRun plain = run_cli("simulate " + kModel + " --t-end 0.5 --quiet");
  EXPECT_NE(plain.out, test::read_text(set_csv));

  const CliRun ea = run_cli("eval " + kModel + " --set bodies.link2.mass=2.5 --q 0.3,-0.2 --qd 1,0.5 --json");
  const CliRun eb = run_cli("eval " + shell_quote(edited) + " --q 0.3,-0.2 --qd 1,0.5 --json");
  ASSERT_EQ(ea.status, 0) << ea.all();
  EXPECT_EQ(ea.out, eb.out);
}

TEST(CmdSimulateSet, ABadPathOrValueIsAnErrorInTheFileNamingTheSet) {
  const CliRun path = run_cli("simulate " + kModel + " --set bodies.link3.mass=2 --quiet");
  EXPECT_EQ(path.status, 2) << path.all();
  EXPECT_NE(path.err.find(kModel + ":5:3: --set bodies.link3.mass=2: 'bodies' has no item named 'link3'"),
            std::string::npos)
      << path.err;
  const CliRun value = run_cli("eval " + kModel + " --set bodies.link2.mass=-1 --json");
  EXPECT_EQ(value.status, 2) << value.all();
  EXPECT_NE(value.err.find(kModel + ":15:11: "), std::string::npos) << value.err;
  EXPECT_NE(value.err.find("(the value came from --set bodies.link2.mass=-1)"), std::string::npos) << value.err;
  const CliRun bare = run_cli("simulate " + kModel + " --set bodies.link2.mass --quiet");
  EXPECT_EQ(bare.status, 2) << bare.all();
  EXPECT_NE(bare.err.find("--set: expected PATH=VALUE"), std::string::npos) << bare.err;
}

TEST(CmdSimulateSet, TheSidecarListsTheOverrides) {
  test::TempDir dir;
  const std::string csv = (dir / "s.csv").string();
  const CliRun r = run_cli("simulate " + kModel +
                           " --set bodies.link2.mass=2.5 --set 'bodies.link2.com=[0.4, 0]' "
                           "--t-end 0.05 --quiet --out " +
                           shell_quote(csv));
  ASSERT_EQ(r.status, 0) << r.all();
  const std::string sidecar = test::read_text(csv + ".json");
  EXPECT_NE(sidecar.find("\"set\": [\n    \"bodies.link2.mass=2.5\",\n    \"bodies.link2.com=[0.4, 0]\"\n  ]"),
            std::string::npos)
      << sidecar;
  const CliRun plain = run_cli("simulate " + kModel + " --t-end 0.05 --quiet --out " + shell_quote(csv));
  ASSERT_EQ(plain.status, 0) << plain.all();
  EXPECT_NE(test::read_text(csv + ".json").find("\"set\": []"), std::string::npos);
}

TEST(CmdSimulateSet, ModalAndGenerateTakeSetToo) {
  // modal: the beam's frequencies scale with sqrt(I): I x 4 doubles them.
  const CliRun plain = run_cli("modal models/paper_beam.yaml --json");
  ASSERT_EQ(plain.status, 0) << plain.all();
  const CliRun quoted = run_cli(
      "modal models/paper_beam.yaml --json --set 'beams.beam1.section={area: 2.5e-5, "
      "inertia: 2.0833333333333333e-10}'");
  ASSERT_EQ(quoted.status, 0) << quoted.all();
  const auto first = [](const std::string& json) {
    const auto at = json.find("\"natural_frequencies_rad_s\"");
    return std::stod(json.substr(json.find('[', at) + 1));
  };
  // The square of side 0.005 has A = 2.5e-5 and I = 5.2083e-11: four times I.
  constexpr double kFrequencyRoundOff = 1e-9;  // relative: the same eigenproblem, K scaled
  EXPECT_NEAR(first(quoted.out) / first(plain.out), 2.0, kFrequencyRoundOff);
  // generate: the banner's SHA-256 covers the overrides.
  test::TempDir dir;
  const CliRun a = run_cli("generate " + kModel + " -o " + shell_quote((dir / "a").string()) + " --quiet");
  const CliRun b = run_cli("generate " + kModel + " -o " + shell_quote((dir / "b").string()) +
                           " --quiet --set bodies.link2.mass=2.5");
  ASSERT_EQ(a.status, 0) << a.all();
  ASSERT_EQ(b.status, 0) << b.all();
  const std::string ha = test::read_text((dir / "a" / "double_pendulum.cpp").string());
  const std::string hb = test::read_text((dir / "b" / "double_pendulum.cpp").string());
  EXPECT_NE(ha, hb);
}

TEST(CmdGenerateExpanded, PrintsTheModelAsTheSolverIsMadeFromIt) {
  test::TempDir dir;
  const CliRun r = run_cli("generate models/bridge_hslm_20m.yaml --expanded --set train.hslm=A3");
  ASSERT_EQ(r.status, 0) << r.all();
  EXPECT_EQ(r.out.find("train:"), std::string::npos) << r.out;  // expanded: the key is gone
  EXPECT_NE(r.out.find("train_a46"), std::string::npos);        // HSLM-A3: 2 x 16 + 14 axles
  EXPECT_EQ(r.out.find("train_a47"), std::string::npos);
  // The printed model is a model: the same one.
  const std::string path = (dir / "expanded.yaml").string();
  std::ofstream(path) << r.out;
  const CliRun a = run_cli("modal " + shell_quote(path) + " --json");
  const CliRun b = run_cli("modal models/bridge_hslm_20m.yaml --json --set train.hslm=A3");
  ASSERT_EQ(a.status, 0) << a.all();
  EXPECT_EQ(a.out, b.out);
  const CliRun both = run_cli("generate models/bridge_hslm_20m.yaml --expanded -o " + shell_quote(path));
  EXPECT_EQ(both.status, 2) << both.all();
}

}  // namespace
}  // namespace mbfe
