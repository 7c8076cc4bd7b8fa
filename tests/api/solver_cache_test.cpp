// The run-time solver cache (api/solver_cache.cpp) under stress and under
// attack, through the real `mbfe` binary in separate processes (and once
// through the API in threads), each test with its own MBFE_CACHE_DIR:
// concurrent first runs, damaged and stale entries, entries of another model,
// folders writable or owned by others, a failing or interrupted compiler, and
// content-addressed keys. The trust model is in docs/robustness.md.
// One file of about 580 lines because every test uses the one fixture below
// (a private cache folder, its entries and leftovers, forged hashes, a planted
// library, the rebuild check): the cache's trust model is checked in one place.
#include <gtest/gtest.h>
#include <pwd.h>
#include <sys/stat.h>

#include <fstream>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "api/mbfe.h"
#include "tests/support/process.h"

namespace mbfe::test {
namespace {

// A chain of `links` revolute links; `mass` varies the model (and so its
// generated sources).
std::string chain_model(const std::string& name, double mass, int links = 3) {
  std::ostringstream y;
  y << "model: " << name << "\n"
    << "gravity: [0, -9.81]\n"
    << "bodies:\n";
  const char* names[] = {"a", "b", "c"};
  for (int i = 0; i < links; ++i) {
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
constexpr double kProcessSeconds = 300;  // a generous bound for one `mbfe eval`, compile included

// The SHA-256 of a file as the sha256sum tool computes it (an oracle
// independent of mbfe's own hashing).
std::string sha256sum(const fs::path& file) {
  const fs::path out = file.string() + ".sum";
  if (std::system(("sha256sum " + quote(file.string()) + " | cut -c1-64 | tr -d '\\n' > " + quote(out.string()))
                      .c_str()) != 0)
    return "";
  const std::string sum = slurp(out);
  fs::remove(out);
  return sum;
}

// Whether process `pid` has ended (gone, or a zombie nobody reaped yet).
bool process_ended(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text;
  if (!std::getline(stat, text)) return true;
  const auto paren = text.rfind(')');
  return paren != std::string::npos && paren + 2 < text.size() && text[paren + 2] == 'Z';
}

class SolverCache : public ::testing::Test {
 protected:
  fs::path cache() const { return tmp_ / "cache"; }
  std::string env() const { return "MBFE_CACHE_DIR=" + quote(cache().string()); }
  fs::path write_model(const std::string& file, const std::string& name, double mass, int links = 3) const {
    const fs::path path = tmp_ / file;
    spit(path, chain_model(name, mass, links));
    return path;
  }
  RunResult eval(const fs::path& model, const std::string& extra_env = "", const char* args = kEvalArgs) {
    return run_mbfe(tmp_, "eval " + quote(model.string()) + args, env() + " " + extra_env);
  }
  // Entries of the cache (neither hidden, nor a lock file, nor a discarded
  // entry), and leftovers (build folders, discarded entries).
  std::vector<fs::path> entries() const {
    std::vector<fs::path> out;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(cache(), ec)) {
      const std::string name = e.path().filename().string();
      if (name[0] != '.' && name.find(".discard.") == std::string::npos && e.path().extension() != ".lock")
        out.push_back(e.path());
    }
    return out;
  }
  std::vector<std::string> leftovers() const {
    std::vector<std::string> out;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(cache(), ec)) {
      const std::string name = e.path().filename().string();
      if (name.rfind(".build-", 0) == 0 || name.find(".discard.") != std::string::npos) out.push_back(name);
    }
    return out;
  }

  // What someone who can write an entry does to make a swapped solver.so
  // pass a checksum: every hash record of the entry rewritten to the
  // library's bytes (solver.so.sha256 holds the bare digest; a manifest a
  // line `library-sha256 <digest>`).
  static void forge_hashes(const fs::path& entry) {
    const std::string sum = sha256sum(entry / "solver.so");
    ASSERT_EQ(sum.size(), 64u);
    if (fs::exists(entry / "solver.so.sha256")) spit(entry / "solver.so.sha256", sum);
    if (fs::exists(entry / "manifest")) {
      std::string text = slurp(entry / "manifest");
      const auto at = text.find("library-sha256 ");
      ASSERT_NE(at, std::string::npos) << text;
      text.replace(at + 15, 64, sum);
      spit(entry / "manifest", text);
    }
  }

  // A shared library whose constructor writes `marker` when it is loaded,
  // built with this build's compiler.
  fs::path planted_library(const fs::path& marker) const {
    const fs::path source = tmp_ / "planted.cpp";
    const fs::path library = tmp_ / "planted.so";
    spit(source,
         "#include <cstdio>\n"
         "__attribute__((constructor)) static void planted() {\n"
         "  if (std::FILE* f = std::fopen(\"" + marker.string() + "\", \"w\")) { std::fputs(\"ran\\n\", f); std::fclose(f); }\n"
         "}\n");
    const std::string command = quote(MBFE_TEST_CXX) + " -shared -fPIC " + quote(source.string()) + " -o " +
                                quote(library.string());
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    return library;
  }

  // After damaging the one entry: the next run says so, rebuilds it and gives
  // the same numbers; the run after that reuses the rebuilt entry.
  void expect_rebuilt(const fs::path& model, const RunResult& first, const std::string& reason = "rebuilding") {
    const RunResult rebuilt = eval(model);
    EXPECT_EQ(rebuilt.status, 0) << rebuilt.err;
    EXPECT_NE(rebuilt.err.find(reason), std::string::npos) << rebuilt.err;
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

// Four processes started together on a model new to the cache: one compiles,
// the others wait for it and load what it built. The compiler is the real
// one behind a wrapper that first sleeps a second, so that the four surely
// overlap (without the lock each of them compiles).
TEST_F(SolverCache, ConcurrentFirstRunsCompileOnceAndTheOthersWaitAndReuse) {
  const fs::path slow_cc = tmp_ / "slow-cc";
  spit(slow_cc, "#!/bin/sh\nsleep 1\nexec " + quote(MBFE_TEST_CXX) + " \"$@\"\n");
  fs::permissions(slow_cc, fs::perms::owner_all);
  const fs::path model = write_model("race.yaml", "race", 1.5);
  constexpr int kProcesses = 4;
  std::vector<std::unique_ptr<Spawned>> procs;
  for (int p = 0; p < kProcesses; ++p) {
    const std::string tag = "race" + std::to_string(p);
    procs.push_back(std::make_unique<Spawned>(
        std::vector<std::string>{MBFE_CLI, "eval", model.string(), "--q", "0.1,-0.2,0.3", "--qd", "1,0,-1"},
        std::vector<std::string>{"MBFE_CACHE_DIR=" + cache().string(), "MBFE_JIT_COMPILER_OVERRIDE=" + slow_cc.string()},
        tmp_ / (tag + ".stdout"), tmp_ / (tag + ".stderr")));
    ASSERT_GT(procs.back()->pid(), 0);
  }
  std::vector<std::string> outs;
  int compiled = 0, waited = 0, reused = 0;
  for (int p = 0; p < kProcesses; ++p) {
    const std::string tag = "race" + std::to_string(p);
    EXPECT_EQ(procs[p]->wait_for(kProcessSeconds), 0) << slurp(tmp_ / (tag + ".stderr"));
    const std::string log = slurp(tmp_ / (tag + ".stderr"));
    outs.push_back(slurp(tmp_ / (tag + ".stdout")));
    if (log.find("compiled the solver") != std::string::npos) ++compiled;
    if (log.find("waiting for another process") != std::string::npos) ++waited;
    if (log.find("using cached solver") != std::string::npos) ++reused;
  }
  EXPECT_EQ(compiled, 1);
  EXPECT_EQ(reused, kProcesses - 1);
  EXPECT_GE(waited, 1);  // they start within milliseconds; the compile takes over a second
  EXPECT_NE(outs[0].find("M = "), std::string::npos) << outs[0];
  for (int p = 1; p < kProcesses; ++p) EXPECT_EQ(outs[p], outs[0]);
  EXPECT_EQ(entries().size(), 1u);
  EXPECT_TRUE(leftovers().empty()) << leftovers().front();
}

// The same through the API, in threads of one process (as Python or a
// program loading models from several threads): one compile, one library.
TEST_F(SolverCache, ConcurrentLoadsInThreadsCompileOnce) {
  const char* previous = std::getenv("MBFE_CACHE_DIR");
  const std::string restore = previous ? previous : "";
  ASSERT_EQ(::setenv("MBFE_CACHE_DIR", cache().c_str(), 1), 0);
  const fs::path model = write_model("threads.yaml", "threads", 2.5);
  constexpr int kThreads = 4;
  std::vector<std::optional<Model>> loaded(kThreads);
  std::vector<std::string> errors(kThreads);
  std::vector<std::thread> threads;
  for (int i = 0; i < kThreads; ++i)
    threads.emplace_back([&, i] {
      try {
        LoadOptions quiet;
        quiet.quiet = true;
        loaded[i] = Model::load(model.string(), quiet);
      } catch (const std::exception& e) {
        errors[i] = e.what();
      }
    });
  for (auto& t : threads) t.join();
  int compiled = 0;
  for (int i = 0; i < kThreads; ++i) {
    ASSERT_TRUE(errors[i].empty()) << errors[i];
    compiled += loaded[i]->solver_compiled_now() ? 1 : 0;
    EXPECT_EQ(loaded[i]->solver(), loaded[0]->solver());  // one library, loaded once
  }
  EXPECT_EQ(compiled, 1);
  EXPECT_EQ(entries().size(), 1u);
  if (previous) ::setenv("MBFE_CACHE_DIR", restore.c_str(), 1);
  else ::unsetenv("MBFE_CACHE_DIR");
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

TEST_F(SolverCache, MissingManifestIsRebuilt) {
  const fs::path model = write_model("m.yaml", "unchecked", 1.0);
  const RunResult first = eval(model);
  ASSERT_EQ(first.status, 0) << first.err;
  ASSERT_EQ(entries().size(), 1u);
  ASSERT_TRUE(fs::exists(entries()[0] / "manifest"));
  fs::remove(entries()[0] / "manifest");
  expect_rebuilt(model, first, "no manifest");
}

// Bytes that match their recorded hash but are no shared library: the load
// fails, the entry is rebuilt.
TEST_F(SolverCache, UnloadableLibraryWithAMatchingHashIsRebuilt) {
  const fs::path model = write_model("m.yaml", "unloadable", 1.0);
  const RunResult first = eval(model);
  ASSERT_EQ(first.status, 0) << first.err;
  ASSERT_EQ(entries().size(), 1u);
  spit(entries()[0] / "solver.so", "not an ELF file\n");
  forge_hashes(entries()[0]);
  expect_rebuilt(model, first, "cannot load solver");
}

// Another model of the same name (masses 5x) copied into this model's entry,
// library and hash records alike: its numbers must never be printed.
TEST_F(SolverCache, AnotherModelsSolverInTheEntryIsRebuiltNotUsed) {
  const fs::path light = write_model("light.yaml", "twin", 1.0);
  const fs::path heavy = write_model("heavy.yaml", "twin", 5.0);
  const RunResult light_run = eval(light);
  ASSERT_EQ(light_run.status, 0) << light_run.err;
  const fs::path light_entry = entries().at(0);
  const RunResult heavy_run = eval(heavy);
  ASSERT_EQ(heavy_run.status, 0) << heavy_run.err;
  ASSERT_NE(heavy_run.out, light_run.out);
  ASSERT_EQ(entries().size(), 2u);
  const fs::path heavy_entry = entries()[0] == light_entry ? entries()[1] : entries()[0];
  for (const auto& file : fs::directory_iterator(light_entry))
    fs::copy_file(file.path(), heavy_entry / file.path().filename(), fs::copy_options::overwrite_existing);

  const RunResult again = eval(heavy);
  EXPECT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(again.out, heavy_run.out);  // the heavy model's matrices, not the light one's
  EXPECT_NE(again.err.find("another version of the model"), std::string::npos) << again.err;
  EXPECT_NE(again.err.find("compiled the solver"), std::string::npos) << again.err;
  const RunResult light_again = eval(light);
  EXPECT_EQ(light_again.out, light_run.out);
  EXPECT_NE(light_again.err.find("using cached solver"), std::string::npos) << light_again.err;
}

// An entry of a model with another number of coordinates under this model's
// key (a copy, or an entry left by a version of the model before an edit):
// rebuilt, not a refusal on every run.
TEST_F(SolverCache, EntryOfAnotherVersionOfTheModelIsRebuilt) {
  const fs::path two = write_model("two.yaml", "edited", 1.0, 2);
  const fs::path three = write_model("three.yaml", "edited", 1.0, 3);
  ASSERT_EQ(eval(two, "", " --q 0.1,-0.2 --qd 1,0").status, 0);
  const fs::path two_entry = entries().at(0);
  const RunResult first = eval(three);
  ASSERT_EQ(first.status, 0) << first.err;
  const fs::path three_entry = entries()[0] == two_entry ? entries()[1] : entries()[0];
  fs::remove_all(three_entry);
  fs::copy(two_entry, three_entry);
  for (int run = 0; run < 2; ++run) {
    const RunResult again = eval(three);
    EXPECT_EQ(again.status, 0) << again.err;
    EXPECT_EQ(again.out, first.out);
  }
}

TEST_F(SolverCache, DanglingSymlinkEntryIsRebuilt) {
  const fs::path model = write_model("m.yaml", "dangling", 1.0);
  const RunResult first = eval(model);
  ASSERT_EQ(first.status, 0) << first.err;
  const fs::path entry = entries().at(0);
  fs::remove_all(entry);
  fs::create_directory_symlink(tmp_ / "nowhere", entry);
  expect_rebuilt(model, first, "symbolic link");
  EXPECT_FALSE(fs::is_symlink(entry));
}

// A symlink to a sound entry of the same model elsewhere is not followed
// either: what is loaded lives in the cache itself.
TEST_F(SolverCache, SymlinkToAnotherFolderIsNeverFollowed) {
  const fs::path model = write_model("m.yaml", "linked", 1.0);
  const RunResult first = eval(model);
  ASSERT_EQ(first.status, 0) << first.err;
  const fs::path entry = entries().at(0);
  const fs::path elsewhere = tmp_ / "elsewhere";
  fs::rename(entry, elsewhere);
  fs::create_directory_symlink(elsewhere, entry);
  expect_rebuilt(model, first, "symbolic link");
  EXPECT_TRUE(fs::exists(elsewhere / "solver.so"));  // the link went, not its target
}

// A library swapped into an entry without its hash record is never loaded
// (its constructor would run at load time, before any check after loading).
TEST_F(SolverCache, SwappedLibraryIsNeverLoaded) {
  const fs::path model = write_model("m.yaml", "swapped", 1.0);
  const RunResult first = eval(model);
  ASSERT_EQ(first.status, 0) << first.err;
  const fs::path marker = tmp_ / "constructor-ran";
  fs::copy_file(planted_library(marker), entries().at(0) / "solver.so", fs::copy_options::overwrite_existing);
  expect_rebuilt(model, first, "do not match");
  EXPECT_FALSE(fs::exists(marker)) << "the swapped library was loaded";
}

TEST_F(SolverCache, WhatItCreatesIsPrivateWhateverTheUmask) {
  const fs::path model = write_model("m.yaml", "private_entry", 1.0);
  const RunResult first = run_mbfe(tmp_, "eval " + quote(model.string()) + kEvalArgs, "umask 000 && " + env());
  ASSERT_EQ(first.status, 0) << first.err;
  const auto mode = [](const fs::path& p) {
    struct stat st {};
    EXPECT_EQ(::lstat(p.c_str(), &st), 0) << p;
    return st.st_mode & 07777;
  };
  EXPECT_EQ(mode(cache()), 0700u);
  const fs::path entry = entries().at(0);
  EXPECT_EQ(mode(entry), 0700u);
  for (const auto& file : fs::directory_iterator(entry))
    EXPECT_EQ(mode(file.path()) & 0022u, 0u) << file.path() << " is writable by others";
  EXPECT_EQ(mode(entry / "solver.so"), 0600u);
  EXPECT_EQ(mode(entry / "manifest"), 0600u);
  const RunResult again = run_mbfe(tmp_, "eval " + quote(model.string()) + kEvalArgs, "umask 000 && " + env());
  EXPECT_EQ(again.status, 0) << again.err;
  EXPECT_NE(again.err.find("using cached solver"), std::string::npos) << again.err;
}

// A cache folder others may write into is refused (as OpenSSH refuses such a
// key), with the path, the owner and mode found and what to do; nothing is
// compiled or loaded.
TEST_F(SolverCache, CacheFolderWritableByOthersIsRefused) {
  const fs::path model = write_model("m.yaml", "refused", 1.0);
  for (const fs::perms mode : {fs::perms::all | fs::perms::sticky_bit, fs::perms::owner_all | fs::perms::group_all,
                               fs::perms::owner_all | fs::perms::others_write | fs::perms::others_exec}) {
    fs::remove_all(cache());
    fs::create_directory(cache());
    fs::permissions(cache(), mode);
    const RunResult r = eval(model);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(cache().string()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("writable by"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("mode"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("chmod"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("compiled the solver"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_TRUE(entries().empty());
  }
  fs::permissions(cache(), fs::perms::owner_all);
  EXPECT_EQ(eval(model).status, 0);
}

// The attack: user nobody plants an entry under the computable name
// of a model, with a library whose constructor runs at load time and hash
// records that match it. Needs root to give the files to nobody.
class SolverCachePlanted : public SolverCache {
 protected:
  void SetUp() override {
    if (::geteuid() != 0) GTEST_SKIP() << "needs root to create files owned by another user (CI runs as root)";
    const passwd* nobody = ::getpwnam("nobody");
    if (!nobody) GTEST_SKIP() << "no user 'nobody' on this machine";
    nobody_uid_ = nobody->pw_uid;
    nobody_gid_ = nobody->pw_gid;
    model_ = write_model("m.yaml", "planted", 1.0);
    const RunResult first = eval(model_);
    ASSERT_EQ(first.status, 0) << first.err;
    entry_ = entries().at(0);
    fs::copy_file(planted_library(marker()), entry_ / "solver.so", fs::copy_options::overwrite_existing);
    forge_hashes(entry_);
    give_to_nobody(entry_);
  }
  void give_to_nobody(const fs::path& path) const {
    ASSERT_EQ(::lchown(path.c_str(), nobody_uid_, nobody_gid_), 0);
    if (fs::is_directory(fs::symlink_status(path)))
      for (const auto& e : fs::recursive_directory_iterator(path))
        ASSERT_EQ(::lchown(e.path().c_str(), nobody_uid_, nobody_gid_), 0);
  }
  fs::path marker() const { return tmp_ / "constructor-ran"; }
  void expect_refused(const RunResult& r, const fs::path& path, const std::string& found) {
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(path.string()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(found), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("MBFE_CACHE_DIR"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(marker())) << "the planted library's constructor ran";
  }
  uid_t nobody_uid_ = 0;
  gid_t nobody_gid_ = 0;
  fs::path model_, entry_;
};

TEST_F(SolverCachePlanted, InAWorldWritableCacheIsNeverLoaded) {
  fs::permissions(cache(), fs::perms::all | fs::perms::sticky_bit);
  expect_refused(eval(model_), cache(), "mode 1777");
  EXPECT_TRUE(fs::exists(entry_ / "solver.so"));  // refused, not touched
}

TEST_F(SolverCachePlanted, InAPrivateCacheIsNeverLoaded) {
  expect_refused(eval(model_), entry_, "nobody");
}

TEST_F(SolverCache, NoHomeAndNoCacheSettingIsRefusedNotAPredictableTmpFolder) {
  const fs::path model = write_model("m.yaml", "homeless", 1.0);
  const fs::path predictable = "/tmp/mbfe-cache-" + std::to_string(::getuid());
  const bool existed = fs::exists(predictable);
  const RunResult r =
      run_mbfe(tmp_, "eval " + quote(model.string()) + kEvalArgs, "env -u HOME -u XDG_CACHE_HOME -u MBFE_CACHE_DIR");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("set MBFE_CACHE_DIR"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  if (!existed) EXPECT_FALSE(fs::exists(predictable));
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

// SIGTERM, SIGINT or SIGHUP to mbfe while its compiler runs: the compiler's
// whole process group ends with it, the build folder goes, and the signal
// then has its usual effect (mbfe dies of it: status 128 + signal).
class SolverCacheSignal : public SolverCache, public ::testing::WithParamInterface<int> {};

TEST_P(SolverCacheSignal, DuringACompileEndsTheCompilerAndLeavesNothing) {
  const int signal = GetParam();
  const fs::path pid_file = tmp_ / "compiler.pid";
  const fs::path fake = tmp_ / "sleepy-cc";
  // A compiler that records its pid, then takes a minute.
  spit(fake, "#!/bin/sh\necho $$ > " + quote(pid_file.string()) + "\nexec sleep 60\n");
  fs::permissions(fake, fs::perms::owner_all);
  const fs::path model = write_model("m.yaml", "interrupted", 1.0);
  Spawned mbfe({MBFE_CLI, "eval", model.string(), "--q", "0.1,-0.2,0.3", "--qd", "1,0,-1"},
               {"MBFE_CACHE_DIR=" + cache().string(), "MBFE_JIT_COMPILER_OVERRIDE=" + fake.string()},
               tmp_ / "sig.stdout", tmp_ / "sig.stderr");
  ASSERT_GT(mbfe.pid(), 0);
  pid_t compiler = 0;
  for (int i = 0; i < 1000 && compiler <= 0; ++i) {  // up to 20 s for mbfe to start its compiler
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const std::string text = slurp(pid_file);
    if (!text.empty() && text.back() == '\n') compiler = std::stoi(text);
  }
  ASSERT_GT(compiler, 0) << slurp(tmp_ / "sig.stderr");
  std::this_thread::sleep_for(std::chrono::milliseconds(100));  // let the script exec sleep
  ASSERT_EQ(::kill(mbfe.pid(), signal), 0);
  EXPECT_EQ(mbfe.wait_for(20), 128 + signal) << slurp(tmp_ / "sig.stderr");
  bool ended = false;
  for (int i = 0; i < 250 && !ended; ++i) {  // up to 5 s
    ended = process_ended(compiler);
    if (!ended) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_TRUE(ended) << "the compiler (pid " << compiler << ") outlived mbfe";
  if (!ended) ::kill(compiler, SIGKILL);
  EXPECT_TRUE(leftovers().empty()) << leftovers().front();
  EXPECT_TRUE(entries().empty());
}

INSTANTIATE_TEST_SUITE_P(Signals, SolverCacheSignal, ::testing::Values(SIGTERM, SIGINT, SIGHUP),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return std::string(info.param == SIGTERM ? "SIGTERM"
                                              : info.param == SIGINT ? "SIGINT"
                                                                     : "SIGHUP");
                         });

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
  fs::permissions(cache(), fs::perms::owner_all);
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
