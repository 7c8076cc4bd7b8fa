// Helpers for the tests that run the `mbfe` binary (MBFE_CLI) in separate
// processes beyond tests/support/cli.h: a private temporary folder per test
// (also used as MBFE_CACHE_DIR), and a process the test can signal.
#pragma once

#include "tests/support/cli.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace mbfe::test {

namespace fs = std::filesystem;

using test::shell_quote;
inline std::string quote(const std::string& text) { return shell_quote(text); }

inline std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void spit(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

/// A private folder under $TMPDIR (or /tmp), removed with everything in it.
class TempDir {
 public:
  TempDir() {
    const char* base = std::getenv("TMPDIR");
    std::string pattern = std::string(base && *base ? base : "/tmp") + "/mbfe-robustness-XXXXXX";
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    fs::permissions(path_, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }
  fs::path operator/(const std::string& name) const { return path_ / name; }

 private:
  fs::path path_;
};

using RunResult = CliRun;

inline int decode_status(int raw) {
  if (WIFEXITED(raw)) return WEXITSTATUS(raw);
  if (WIFSIGNALED(raw)) return 128 + WTERMSIG(raw);
  return -1;
}

/// `env_prefix mbfe args` from the source tree (run_cli); `dir` is the test's
/// folder, whose cache the caller names in env_prefix.
inline RunResult run_mbfe(const TempDir& /*dir*/, const std::string& args, const std::string& env_prefix = "") {
  return run_cli(args, env_prefix);
}

/// A process started with posix_spawn (SIGINT at its default disposition and
/// unblocked, whatever the test runner does), stdout and stderr to files.
class Spawned {
 public:
  Spawned(const std::vector<std::string>& argv, const std::vector<std::string>& extra_env,
          const fs::path& stdout_path, const fs::path& stderr_path) {
    std::vector<std::string> env_strings = extra_env;
    for (char** e = environ; *e; ++e) env_strings.emplace_back(*e);
    std::vector<char*> envp, args;
    for (auto& s : env_strings) envp.push_back(s.data());
    envp.push_back(nullptr);
    std::vector<std::string> argv_copy = argv;
    for (auto& s : argv_copy) args.push_back(s.data());
    args.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    sigset_t defaults, empty;
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGINT);
    sigemptyset(&empty);
    posix_spawnattr_setsigdefault(&attr, &defaults);
    posix_spawnattr_setsigmask(&attr, &empty);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
    const int rc = posix_spawn(&pid_, args[0], &actions, &attr, args.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attr);
    if (rc != 0) pid_ = -1;
  }
  ~Spawned() {
    if (pid_ > 0 && !reaped_) {
      ::kill(pid_, SIGKILL);
      int raw;
      ::waitpid(pid_, &raw, 0);
    }
  }
  Spawned(const Spawned&) = delete;
  Spawned& operator=(const Spawned&) = delete;

  pid_t pid() const { return pid_; }
  bool running() {
    if (pid_ <= 0 || reaped_) return false;
    int raw;
    const pid_t r = ::waitpid(pid_, &raw, WNOHANG);
    if (r == pid_) {
      reaped_ = true;
      status_ = decode_status(raw);
      return false;
    }
    return true;
  }
  /// Waits up to `seconds`; returns the exit status, or -1 if still running.
  int wait_for(double seconds) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (running()) {
      if (std::chrono::steady_clock::now() > deadline) return -1;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return status_;
  }

 private:
  pid_t pid_ = -1;
  bool reaped_ = false;
  int status_ = -1;
};

/// Lines of a text file's content (the last one may be partial: no newline).
inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// Checks that a CSV is whole: a header, then rows of the header's field
/// count, every line ending in a newline. Returns the number of data rows.
inline std::size_t check_complete_csv(const std::string& text) {
  if (text.empty()) {
    ADD_FAILURE() << "empty CSV";
    return 0;
  }
  EXPECT_EQ(text.back(), '\n') << "last line of the CSV is cut: ..." << text.substr(text.size() > 200 ? text.size() - 200 : 0);
  const auto lines = lines_of(text);
  const auto fields = [](const std::string& line) { return 1 + std::count(line.begin(), line.end(), ','); };
  const auto expected = fields(lines.at(0));
  for (std::size_t i = 1; i < lines.size(); ++i) {
    EXPECT_EQ(fields(lines[i]), expected) << "row " << i << ": " << lines[i];
    if (fields(lines[i]) != expected) break;
  }
  return lines.size() - 1;
}

}  // namespace mbfe::test
