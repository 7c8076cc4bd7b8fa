// Running the compiler (api/compiler_process.cpp): output and status, a
// process group of its own, and a signal that ends the whole group and then
// reaches the program's own handler.
#include "api/compiler_process.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <string>
#include <thread>

#include "tests/support/process.h"

namespace mbfe::test {
namespace {

constexpr std::size_t kOutputCap = 4096;

TEST(CompilerProcess, CapturesOutputAndStatus) {
  DeferredSignals signals;
  const CompilerRun run = run_compiler("echo to-stdout; echo to-stderr >&2; exit 3", kOutputCap, signals);
  EXPECT_EQ(run.status, 3);
  EXPECT_FALSE(run.interrupted);
  EXPECT_NE(run.output.find("to-stdout"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("to-stderr"), std::string::npos) << run.output;
  signals.finish();
}

TEST(CompilerProcess, KeepsTheFirstBytesOfLongOutput) {
  DeferredSignals signals;
  const CompilerRun run = run_compiler("yes compiler-noise | head -c 1000000", kOutputCap, signals);
  EXPECT_EQ(run.status, 0);
  EXPECT_EQ(run.output.size(), kOutputCap);
  EXPECT_EQ(run.output.rfind("compiler-noise\n", 0), 0u);
  signals.finish();
}

TEST(CompilerProcess, RunsInAProcessGroupOfItsOwnWithStdinClosed) {
  DeferredSignals signals;
  // The shell's pid, its process group (field 5 of /proc/<pid>/stat) and
  // its stdin.
  const CompilerRun run =
      run_compiler("echo $$ $(cut -d' ' -f5 /proc/$$/stat) $(readlink /proc/$$/fd/0)", kOutputCap, signals);
  signals.finish();
  ASSERT_EQ(run.status, 0) << run.output;
  std::istringstream fields(run.output);
  long pid = 0, group = 0;
  std::string input;
  fields >> pid >> group >> input;
  EXPECT_EQ(group, pid);  // the leader of a new group
  EXPECT_NE(group, static_cast<long>(::getpgrp()));
  EXPECT_EQ(input, "/dev/null") << run.output;  // not the terminal
}

std::atomic<int> g_program_saw{0};
extern "C" void program_handler(int signal) { g_program_saw = signal; }

// SIGTERM while the compiler runs a background child: the whole group ends
// within the grace period, the run returns interrupted, and finish() hands
// the signal to the handler the program had (which returns, as Python's
// does), then throws.
TEST(CompilerProcess, ASignalEndsTheWholeGroupThenReachesTheProgramsHandler) {
  struct sigaction program {}, previous {};
  program.sa_handler = program_handler;
  sigemptyset(&program.sa_mask);
  ASSERT_EQ(::sigaction(SIGTERM, &program, &previous), 0);
  g_program_saw = 0;
  TempDir tmp;
  const fs::path pid_file = tmp / "child.pid";
  {
    DeferredSignals signals;
    std::thread sender([] {
      std::this_thread::sleep_for(std::chrono::milliseconds(300));
      ::kill(::getpid(), SIGTERM);
    });
    const auto start = std::chrono::steady_clock::now();
    const CompilerRun run =
        run_compiler("sleep 60 & echo $! > " + quote(pid_file.string()) + "; wait", kOutputCap, signals);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    sender.join();
    EXPECT_TRUE(run.interrupted);
    EXPECT_LT(seconds, 10.0);  // not the minute the child would take
    EXPECT_EQ(g_program_saw, 0);  // held off so far
    try {
      signals.finish();
      ADD_FAILURE() << "finish() returned after a signal";
    } catch (const CompileInterrupted& e) {
      EXPECT_STREQ(e.what(), "interrupted by SIGTERM while compiling a solver");
    }
    EXPECT_EQ(g_program_saw, SIGTERM);
  }
  const pid_t child = std::stoi(slurp(pid_file));
  bool ended = false;
  for (int i = 0; i < 100 && !ended; ++i) {
    std::ifstream stat("/proc/" + std::to_string(child) + "/stat");
    std::string text;
    ended = !std::getline(stat, text) || text[text.rfind(')') + 2] == 'Z';
    if (!ended) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_TRUE(ended) << "the compiler's child " << child << " outlived the interrupted run";
  if (!ended) ::kill(child, SIGKILL);
  struct sigaction now {};
  ::sigaction(SIGTERM, nullptr, &now);
  EXPECT_EQ(now.sa_handler, program_handler);  // restored
  ::sigaction(SIGTERM, &previous, nullptr);
}

TEST(CompilerProcess, AnIgnoredSignalStaysIgnored) {
  struct sigaction ignore {}, previous {}, during {};
  ignore.sa_handler = SIG_IGN;
  ASSERT_EQ(::sigaction(SIGHUP, &ignore, &previous), 0);
  {
    DeferredSignals signals;
    ::sigaction(SIGHUP, nullptr, &during);
    EXPECT_EQ(during.sa_handler, SIG_IGN);
    ::raise(SIGHUP);
    EXPECT_EQ(signals.caught(), 0);
    signals.finish();
  }
  ::sigaction(SIGHUP, &previous, nullptr);
}

}  // namespace
}  // namespace mbfe::test
