// Replays every input the model fuzzer ever crashed on (tests/fuzz/regressions/)
// and the seed corpus (tests/fuzz/corpus/) through the fuzzer's own entry point
// (fuzz_entry.h): none may throw anything but the expected errors, and each
// stays fast. scripts/fuzz.sh runs the fuzzer itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/fuzz/fuzz_entry.h"

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> files_in(const std::string& folder) {
  std::vector<fs::path> files;
  const fs::path dir = fs::path(MBFE_SOURCE_DIR) / folder;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

const char* outcome_name(mbfe::fuzz::FuzzOutcome o) {
  switch (o) {
    case mbfe::fuzz::FuzzOutcome::kRejected: return "rejected";
    case mbfe::fuzz::FuzzOutcome::kParsed: return "parsed";
    case mbfe::fuzz::FuzzOutcome::kGenerated: return "generated";
    case mbfe::fuzz::FuzzOutcome::kGeneratorRefused: return "refused by the generator";
  }
  return "?";
}

// Each input runs in well under a second in a normal build (the fuzzer's own
// limit is 10 s per input); a generous bound that survives the sanitizer build.
constexpr double kSecondsPerInput = 30.0;

void replay(const fs::path& file) {
  const std::string bytes = read_bytes(file);
  const auto start = std::chrono::steady_clock::now();
  try {
    const auto outcome =
        mbfe::fuzz::fuzz_one_input(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    ::testing::Test::RecordProperty(file.filename().string(), outcome_name(outcome));
  } catch (const std::exception& e) {
    ADD_FAILURE() << file << ": unexpected exception: " << e.what();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, kSecondsPerInput) << file;
}

// The regression inputs committed so far; fewer means files were lost, and an
// empty folder would make the replay below pass without replaying anything.
constexpr std::size_t kMinRegressionInputs = 8;

TEST(FuzzRegressions, EveryCrashInputIsHandled) {
  const auto files = files_in("tests/fuzz/regressions");
  const auto inputs = std::count_if(files.begin(), files.end(), [](const fs::path& f) { return f.extension() == ".yaml"; });
  ASSERT_GE(static_cast<std::size_t>(inputs), kMinRegressionInputs);
  for (const auto& f : files) {
    SCOPED_TRACE(f.string());
    replay(f);
  }
}

TEST(FuzzRegressions, SeedCorpusParsesAndGenerates) {
  const auto files = files_in("tests/fuzz/corpus");
  ASSERT_GE(files.size(), 10u);
  int generated = 0;
  for (const auto& f : files) {
    SCOPED_TRACE(f.string());
    const std::string bytes = read_bytes(f);
    const auto outcome =
        mbfe::fuzz::fuzz_one_input(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    // Seeds are valid models: a seed the parser rejects seeds nothing deep.
    EXPECT_NE(outcome, mbfe::fuzz::FuzzOutcome::kRejected) << f;
    if (outcome == mbfe::fuzz::FuzzOutcome::kGenerated) ++generated;
  }
  EXPECT_GE(generated, 5);
}

}  // namespace
