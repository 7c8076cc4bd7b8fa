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

}  // namespace
}  // namespace mbfe
