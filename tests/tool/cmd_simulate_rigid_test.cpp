// The command-line contracts of the rigid pipeline: generate, eval, simulate.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "runtime/abi/mbfe_model_abi.h"
#include "tests/support/cli.h"

extern "C" const mbfe_model_v1* mbfe_model_double_pendulum(void);

namespace {

namespace fs = std::filesystem;

// Runs the mbfe binary with `args`: stdout, and stderr after it when `merge`.
using mbfe::test::CliRun;

CliRun mbfe(const std::string& args, bool merge = false) {
  CliRun r = mbfe::test::run_cli(args);
  if (merge) r.out += r.err;
  return r;
}

std::string model(const char* name) { return std::string(MBFE_SOURCE_DIR) + "/models/" + name; }

fs::path temp_dir(const std::string& tag) {
  const fs::path dir = fs::temp_directory_path() / ("mbfe-cli-" + tag + "-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

TEST(CliRigid, EvalJsonMatchesTheLinkedSolver) {
  const CliRun r = mbfe("eval " + model("double_pendulum.yaml") + " --q 0.3,-0.2 --qd 1,0.5 --t 0.1 --json");
  ASSERT_EQ(r.status, 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  // The run-time compiled solver and the one linked into this test come from
  // the same generator: the JSON must carry the same doubles (printed losslessly).
  const double q[2] = {0.3, -0.2}, qd[2] = {1, 0.5};
  double M[4], F[2], Q[2];
  const mbfe_model_v1& m = *mbfe_model_double_pendulum();
  m.mass_matrix(q, M);
  m.inertial_forces(q, qd, F);
  m.generalized_forces(q, qd, 0.1, Q);
  ASSERT_EQ(j["M"].size(), 2u);
  for (int r0 = 0; r0 < 2; ++r0)
    for (int c = 0; c < 2; ++c) EXPECT_EQ(j["M"][r0][c].get<double>(), M[2 * r0 + c]);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(j["F"][i].get<double>(), F[i]);
    EXPECT_EQ(j["Q"][i].get<double>(), Q[i]);
  }
}

TEST(CliRigid, EvalRejectsWrongStateLength) {
  const CliRun r = mbfe("eval " + model("double_pendulum.yaml") + " --q 0.3 --json", true);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("expected 2"), std::string::npos) << r.out;
}

TEST(CliRigid, SimulateWritesTheContractHeaderAndFlagsOverrideTheModel) {
  const fs::path dir = temp_dir("sim");
  const std::string csv = (dir / "out.csv").string();
  const CliRun r = mbfe("simulate " + model("cart_pendulum.yaml") + " --integrator forward_euler --step 0.01 --t-end 0.1 "
                     "--out " + csv + " --quiet");
  ASSERT_EQ(r.status, 0);
  std::ifstream in(csv);
  std::string header, line, last;
  std::getline(in, header);
  int rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    last = line;
  }
  EXPECT_EQ(header, "t,cart,pendulum,cart_dot,pendulum_dot");
  EXPECT_EQ(rows, 11);  // t = 0, 0.01, ..., 0.1 (flags override the model's 1e-3 and t_end)
  EXPECT_EQ(std::stod(last.substr(0, last.find(','))), 0.1);
  fs::remove_all(dir);
}

TEST(CliRigid, GenerateWritesBothFilesAndNothingOnError) {
  const fs::path dir = temp_dir("gen");
  EXPECT_EQ(mbfe("generate " + model("double_pendulum.yaml") + " -o " + (dir / "ok").string() + " --quiet").status, 0);
  EXPECT_TRUE(fs::exists(dir / "ok" / "double_pendulum.h"));
  EXPECT_TRUE(fs::exists(dir / "ok" / "double_pendulum.cpp"));
  std::ofstream(dir / "bad.yaml") << "model: bad\nbodies:\n  - name: a\n    parent: ground\n"
                                     "    joint: {type: revolute}\n    mass: -2\n    inertia: 0\n";
  const CliRun r = mbfe("generate " + (dir / "bad.yaml").string() + " -o " + (dir / "bad").string(), true);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("bad.yaml:6:"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir / "bad"));
  fs::remove_all(dir);
}

TEST(CliRigid, EveryCommandHasHelpWithAnExample) {
  for (const char* cmd : {"generate", "eval", "simulate", "modal", "stability", "plot"}) {
    const CliRun r = mbfe(std::string(cmd) + " --help");
    EXPECT_EQ(r.status, 0) << cmd;
    EXPECT_NE(r.out.find("Example"), std::string::npos) << cmd << ":\n" << r.out;
  }
}

}  // namespace
