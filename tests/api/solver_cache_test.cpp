// The run-time solver cache (api/solver_cache.cpp) under stress, through the
// real `mbfe` binary in separate processes, each test with its own
// MBFE_CACHE_DIR: concurrent compiles of the same new model, damaged entries,
// a failing compiler, and content-addressed keys.
#include <gtest/gtest.h>

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "tests/support/process.h"

namespace mbfe::test {
namespace {

// A three-link chain; `mass` varies the model (and so its generated sources).
std::string chain_model(const std::string& name, double mass) {
  std::ostringstream y;
  y << "model: " << name << "\n"
    << "gravity: [0, -9.81]\n"
    << "bodies:\n";
  const char* names[] = {"a", "b", "c"};
  for (int i = 0; i < 3; ++i) {
    y << "  - name: " << names[i] << "\n"
      << "    parent: " << (i == 0 ? "ground" : names[i - 1]) << "\n"
      << "    joint: {type: revolute, at: [" << (i == 0 ? 0 : 1) << ", 0]}\n"
      << "    mass: " << mass << "\n"
      << "    inertia: 0.1\n"
      << "    com: [0.5, 0]\n";
  }
  return y.str();
}

constexpr const char* kEvalArgs = " --q 0.1,-0.2,0.3 --qd 1,0,-1";

class SolverCache : public ::testing::Test {
 protected:
  fs::path cache() const { return tmp_ / "cache"; }
  std::string env() const { return "MBFE_CACHE_DIR=" + quote(cache().string()); }
  fs::path write_model(const std::string& file, const std::string& name, double mass) const {
    const fs::path path = tmp_ / file;
    spit(path, chain_model(name, mass));
    return path;
  }
  RunResult eval(const fs::path& model, const std::string& extra_env = "") {
    return run_mbfe(tmp_, "eval " + quote(model.string()) + kEvalArgs, env() + " " + extra_env);
  }
  // Entries of the cache (folders not starting with '.'), and leftovers
  // (build folders, discarded entries).
  std::vector<fs::path> entries() const {
    std::vector<fs::path> out;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(cache(), ec))
      if (e.path().filename().string()[0] != '.' && e.path().filename().string().find(".discard.") == std::string::npos)
        out.push_back(e.path());
    return out;
  }
  std::vector<std::string> leftovers() const {
    std::vector<std::string> out;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(cache(), ec)) {
      const std::string name = e.path().filename().string();
      if (name[0] == '.' || name.find(".discard.") != std::string::npos) out.push_back(name);
    }
    return out;
  }

  // After damaging the one entry: the next run says so, rebuilds it and gives
  // the same numbers; the run after that reuses the rebuilt entry.
  void expect_rebuilt(const fs::path& model, const RunResult& first) {
    const RunResult rebuilt = eval(model);
    EXPECT_EQ(rebuilt.status, 0) << rebuilt.err;
    EXPECT_NE(rebuilt.err.find("is damaged"), std::string::npos) << rebuilt.err;
    EXPECT_NE(rebuilt.err.find("compiled the solver"), std::string::npos) << rebuilt.err;
    EXPECT_EQ(rebuilt.out, first.out);
    const RunResult reused = eval(model);
    EXPECT_EQ(reused.status, 0) << reused.err;
    EXPECT_NE(reused.err.find("using cached solver"), std::string::npos) << reused.err;
    EXPECT_EQ(reused.out, first.out);
    EXPECT_EQ(entries().size(), 1u);
    EXPECT_TRUE(leftovers().empty());
  }

  TempDir tmp_;
};

TEST_F(SolverCache, TwoProcessesCompilingTheSameNewModelBothSucceedAndAgree) {
  // Several rounds, each with a model new to the cache, started together so
  // that both processes compile (a compile takes about a second or more).
  int both_compiled = 0;
  for (int round = 0; round < 3; ++round) {
    const fs::path model = write_model("race" + std::to_string(round) + ".yaml",
                                       "race" + std::to_string(round), 1.0 + round);
    std::vector<std::unique_ptr<Spawned>> procs;
    for (int p = 0; p < 2; ++p) {
      const std::string tag = "race" + std::to_string(round) + "_" + std::to_string(p);
      procs.push_back(std::make_unique<Spawned>(
          std::vector<std::string>{MBFE_CLI, "eval", model.string(), "--q", "0.1,-0.2,0.3", "--qd", "1,0,-1"},
          std::vector<std::string>{"MBFE_CACHE_DIR=" + cache().string()}, tmp_ / (tag + ".stdout"),
          tmp_ / (tag + ".stderr")));
      ASSERT_GT(procs.back()->pid(), 0);
    }
    std::vector<std::string> outs;
    int compiled = 0;
    for (int p = 0; p < 2; ++p) {
      const std::string tag = "race" + std::to_string(round) + "_" + std::to_string(p);
      EXPECT_EQ(procs[p]->wait_for(300), 0) << slurp(tmp_ / (tag + ".stderr"));
      outs.push_back(slurp(tmp_ / (tag + ".stdout")));
      if (slurp(tmp_ / (tag + ".stderr")).find("compiled the solver") != std::string::npos) ++compiled;
    }
    EXPECT_FALSE(outs[0].empty());
    EXPECT_NE(outs[0].find("M = "), std::string::npos) << outs[0];
    EXPECT_EQ(outs[0], outs[1]);
    if (compiled == 2) ++both_compiled;
    EXPECT_EQ(entries().size(), static_cast<std::size_t>(round + 1));
    EXPECT_TRUE(leftovers().empty()) << leftovers().front();
  }
  // The race itself: both processes compiled in at least one round (they
  // start within milliseconds; a compile takes a second or more).
  EXPECT_GE(both_compiled, 1);
  // And the entry they left is sound: a third process reuses it.
  const RunResult again = eval(tmp_ / "race0.yaml");
  EXPECT_EQ(again.status, 0) << again.err;
  EXPECT_NE(again.err.find("using cached solver"), std::string::npos) << again.err;
}

TEST_F(SolverCache, TruncatedLibraryIsDetectedAndRebuilt) {
  const fs::path model = write_model("m.yaml", "truncated", 1.0);
  const RunResult first = eval(model);
  ASSERT_EQ(first.status, 0) << first.err;
  ASSERT_EQ(entries().size(), 1u);
  const fs::path library = entries()[0] / "solver.so";
  const auto size = fs::file_size(library);
  fs::resize_file(library, size / 2);
  expect_rebuilt(model, first);
  EXPECT_EQ(fs::file_size(library), size);
  EXPECT_EQ(entries().size(), 1u);
  EXPECT_TRUE(leftovers().empty());
}

TEST_F(SolverCache, FlippedBytesAreDetectedAndRebuilt) {
  const fs::path model = write_model("m.yaml", "flipped", 1.0);
  const RunResult first = eval(model);
  ASSERT_EQ(first.status, 0) << first.err;
  ASSERT_EQ(entries().size(), 1u);
  const fs::path library = entries()[0] / "solver.so";
  std::string bytes = slurp(library);
  for (std::size_t i = bytes.size() / 3; i < bytes.size() / 3 + 16; ++i) bytes[i] = static_cast<char>(~bytes[i]);
  spit(library, bytes);
  expect_rebuilt(model, first);
  EXPECT_TRUE(leftovers().empty());
}

TEST_F(SolverCache, MissingChecksumIsRebuilt) {
  const fs::path model = write_model("m.yaml", "unchecked", 1.0);
  const RunResult first = eval(model);
  ASSERT_EQ(first.status, 0) << first.err;
  ASSERT_EQ(entries().size(), 1u);
  fs::remove(entries()[0] / "solver.so.sha256");
  expect_rebuilt(model, first);
}

// Bytes that match their checksum but are no shared library (say, a file
// replaced together with its checksum): the load fails, the entry is rebuilt.
TEST_F(SolverCache, UnloadableLibraryWithAMatchingChecksumIsRebuilt) {
  const fs::path model = write_model("m.yaml", "unloadable", 1.0);
  const RunResult first = eval(model);
  ASSERT_EQ(first.status, 0) << first.err;
  ASSERT_EQ(entries().size(), 1u);
  const fs::path library = entries()[0] / "solver.so";
  spit(library, "not an ELF file\n");
  // The checksum of the fake bytes, computed by the sha256sum tool.
  ASSERT_EQ(std::system(("sha256sum " + quote(library.string()) + " | cut -c1-64 | tr -d '\\n' > " +
                         quote((entries()[0] / "solver.so.sha256").string()))
                            .c_str()),
            0);
  expect_rebuilt(model, first);
}

TEST_F(SolverCache, FailedCompileLeavesNothingBehindAndShowsTheCompilersMessage) {
  const fs::path model = write_model("m.yaml", "doomed", 1.0);
  const fs::path fake = tmp_ / "fake-cc";
  spit(fake,
       "#!/bin/sh\n"
       "echo \"fake-cc: error: simulated compiler failure in $#-argument command\" >&2\n"
       "exit 1\n");
  fs::permissions(fake, fs::perms::owner_all);
  const RunResult failed = eval(model, "MBFE_JIT_COMPILER_OVERRIDE=" + quote(fake.string()));
  // A compiler that fails on generated code is not the user's input: status 1.
  EXPECT_EQ(failed.status, 1) << failed.err;
  EXPECT_NE(failed.err.find("compiling the solver of 'doomed' failed"), std::string::npos) << failed.err;
  EXPECT_NE(failed.err.find("fake-cc: error: simulated compiler failure"), std::string::npos) << failed.err;
  EXPECT_TRUE(failed.out.empty()) << failed.out;
  EXPECT_TRUE(entries().empty());
  EXPECT_TRUE(leftovers().empty()) << leftovers().front();

  // Nothing poisoned: the real compiler then builds the same model.
  const RunResult ok = eval(model);
  EXPECT_EQ(ok.status, 0) << ok.err;
  EXPECT_NE(ok.err.find("compiled the solver"), std::string::npos) << ok.err;
  EXPECT_EQ(entries().size(), 1u);
}

TEST_F(SolverCache, KeyChangesWhenTheModelChangesAndIsStableOtherwise) {
  const fs::path a = write_model("a.yaml", "keyed", 1.0);
  const RunResult first = eval(a);
  ASSERT_EQ(first.status, 0) << first.err;
  ASSERT_EQ(entries().size(), 1u);
  const fs::path entry_a = entries()[0];
  EXPECT_EQ(entry_a.filename().string().rfind("keyed-", 0), 0u) << entry_a;

  // Same model, same file: the same entry.
  const RunResult same = eval(a);
  EXPECT_NE(same.err.find("using cached solver " + (entry_a / "solver.so").string()), std::string::npos)
      << same.err;

  // A different mass: new sources, a new key, a second entry; the first stays.
  const fs::path b = write_model("b.yaml", "keyed", 2.5);
  const RunResult changed = eval(b);
  ASSERT_EQ(changed.status, 0) << changed.err;
  EXPECT_NE(changed.err.find("compiled the solver"), std::string::npos) << changed.err;
  EXPECT_NE(changed.out, first.out);
  ASSERT_EQ(entries().size(), 2u);
  std::set<std::string> names;
  for (const auto& e : entries()) names.insert(e.filename().string());
  EXPECT_EQ(names.count(entry_a.filename().string()), 1u);

  // Back to the first model: reused, not rebuilt.
  const RunResult back = eval(a);
  EXPECT_NE(back.err.find("using cached solver"), std::string::npos) << back.err;
  EXPECT_EQ(back.out, first.out);
}

TEST_F(SolverCache, StaleBuildFoldersOfKilledProcessesAreRemoved) {
  fs::create_directories(cache() / ".build-old123");
  spit(cache() / ".build-old123" / "x.cpp", "half");
  fs::create_directories(cache() / ".build-new456");
  const auto two_hours_ago = fs::file_time_type::clock::now() - std::chrono::hours(2);
  fs::last_write_time(cache() / ".build-old123", two_hours_ago);
  const RunResult r = eval(write_model("m.yaml", "sweeper", 1.0));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(fs::exists(cache() / ".build-old123"));
  EXPECT_TRUE(fs::exists(cache() / ".build-new456"));  // may belong to a running compile
}

}  // namespace
}  // namespace mbfe::test
