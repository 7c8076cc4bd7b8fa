// The committed sources under generated/ are exactly what the generator emits
// today, and the generator's output does not change from run to run.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "frontend/parse_model.h"
#include "generator/emit/generate_solver.h"
#include "tests/support/cli.h"

namespace mbfe {
namespace {

namespace fs = std::filesystem;
constexpr const char* kRegenerate = "run scripts/regenerate.sh and commit generated/";

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(GeneratedSources, CommittedSourcesAreUpToDate) {
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(MBFE_SOURCE_DIR) / "models")) {
    if (entry.path().extension() != ".yaml") continue;
    const ir::Model m = frontend::load_model_file(entry.path().string());
    if (m.bodies.empty()) continue;  // beam-only models have no generated part
    const fs::path folder = fs::path(MBFE_SOURCE_DIR) / "generated" / m.name;
    ASSERT_TRUE(fs::is_directory(folder)) << folder << " is missing: " << kRegenerate;
    for (const auto& file : gen::generate_solver(m).files) {
      EXPECT_EQ(slurp(folder / file.name), file.text) << (folder / file.name) << " is stale: " << kRegenerate;
      ++checked;
    }
  }
  EXPECT_GE(checked, 10) << "expected the shipped rigid models (double pendulum, cart-pendulum, chains)";
}

// Two separate processes (different address-space layouts, so different GiNaC
// hash seeds) must write byte-identical files.
TEST(GeneratedSources, ByteIdenticalAcrossProcesses) {
  const fs::path base = fs::temp_directory_path() / ("mbfe-determinism-" + std::to_string(::getpid()));
  const std::string model = std::string(MBFE_SOURCE_DIR) + "/models/chain_10.yaml";
  for (const char* run : {"a", "b"}) {
    const test::CliRun r = test::run_cli("generate " + model + " -o " + test::shell_quote((base / run).string()) + " --quiet");
    ASSERT_EQ(r.status, 0) << r.err;
  }
  for (const char* name : {"chain_10.h", "chain_10.cpp"})
    EXPECT_EQ(slurp(base / "a" / name), slurp(base / "b" / name)) << name;
  fs::remove_all(base);
}

}  // namespace
}  // namespace mbfe
