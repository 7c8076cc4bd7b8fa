// mbfe sweep SWEEP.yaml --out DIR [--jobs N] [--point I | --collect | --slurm ...]
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "api/mbfe.h"
#include "frontend/parse_model.h"
#include "frontend/parse_sweep.h"
#include "frontend/sha256.h"
#include "generator/emit/generate_solver.h"
#include "runtime/platform/thread_budget.h"
#include "tool/cli_args.h"
#include "tool/commands.h"
#include "tool/file_checks.h"
#include "tool/sweep_point.h"
#include "tool/sweep_slurm.h"

extern char** environ;

namespace mbfe::tool {

namespace {

namespace fs = std::filesystem;

constexpr const char* kHelp = R"(Usage: mbfe sweep SWEEP.yaml --out DIR [--jobs N] [--quiet]
       mbfe sweep SWEEP.yaml --out DIR --slurm [--partition P] [--time T] [--array-limit K] [--dry-run]
       mbfe sweep SWEEP.yaml --out DIR --point I
       mbfe sweep SWEEP.yaml --out DIR --collect

Runs a parameter study: one model file with some of its values varied
(docs/sweeps.md). Every point gets DIR/points/<i>/ with its model.yaml (run it
again by hand with mbfe simulate), run.csv and result.json; DIR/summary.csv and
DIR/summary.json list each point's values, status and collected statistics.
Warnings about likely unit mistakes in the model file or a point's values
(docs/robustness.md, "Warnings") are printed once for the sweep, not per
point, and listed under "warnings" in summary.json.

  --jobs N         points run at once on this machine (default: every core this
                   process may use); each point may use cores / N threads (MBFE_THREADS)
  --point I        run point I only (what each Slurm task does)
  --collect        write the summary from the results present
  --slurm          submit a Slurm job array (one task per point) and a collect
                   job that waits for it; prints the job ids. DIR must be on a
                   filesystem the nodes share; solvers are compiled here first,
                   into DIR/cache
  --partition P, --time T, --array-limit K
                   sbatch's --partition, --time and the %K of --array
  --dry-run        with --slurm: write DIR/slurm/*.sbatch, do not submit
  --set PATH=VALUE replace a value of the model file before the sweep varies
                   it (repeatable; PATH as the vary paths); every point, and
                   each --point and --collect run, needs the same --set flags

A re-run skips points already done for the same request (the point's model
file, the simulate: block and the collect: entries); failed points, and points
whose result is of another request, run again. A failed point (bad
combination, divergence) is recorded with its message and exit status; the
others go on.

Exit status: 0 every point done; 2 bad sweep file or flags; 3 some point failed
(the summary says which).

Example:
  mbfe sweep models/sweeps/bridge_speeds.yaml --out speeds --jobs 2
  mbfe sweep models/sweeps/bridge_speeds.yaml --out stiff --set beams.deck.section.inertia=0.3
)";

std::string self_exe() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("cannot find the mbfe executable (/proc/self/exe)");
  return p.string();
}

/// Each distinct solver of the sweep compiled once, before the points run
/// side by side (they would otherwise all compile the same one at once).
void precompile(const ir::Sweep& sweep, const std::string& model_text, const std::string& out_dir, bool quiet) {
  for (long i = 0; i < sweep.points(); ++i) {
    const std::string text = frontend::point_model_text(sweep, model_text, i);
    LoadOptions options;
    options.quiet = quiet;
    options.cache_by_sources = true;
    try {
      Model::parse(text, point_dir(out_dir, i) + "/model.yaml", options);
    } catch (const std::exception&) {
      // This point's own run reports it.
    }
  }
}

/// The generated sources of point i, hashed: points with the same key share
/// one compiled solver. Empty for a model without bodies (no solver) or one
/// that does not parse (its own run reports why).
std::string solver_key(const ir::Sweep& sweep, const std::string& model_text, long i) {
  try {
    const ir::Model model = frontend::parse_model_text(frontend::point_model_text(sweep, model_text, i), "point");
    if (model.bodies.empty()) return "";
    std::string text;
    for (const auto& file : gen::generate_solver(model).files) text += file.name + "\n" + file.text;
    return frontend::sha256_hex(text);
  } catch (const std::exception&) {
    return "";
  }
}

int run_local(const ir::Sweep& sweep, const std::string& sweep_file, const std::string& model_text,
              const std::string& out_dir, long jobs, bool quiet, const std::vector<std::string>& model_sets,
              const std::vector<std::string>& warnings) {
  const long n = sweep.points();
  std::vector<long> todo;
  long stale = 0;
  for (long i = 0; i < n; ++i) {
    bool other_request = false;
    const auto r = read_point_result(sweep, model_text, out_dir, i, &other_request);
    if (!r || !r->done) todo.push_back(i);
    stale += other_request ? 1 : 0;
  }
  if (stale > 0 && !quiet)
    std::cerr << "mbfe sweep: " << stale << " point" << (stale == 1 ? " holds a result" : "s hold results")
              << " of another request (the model, the point's values, simulate: or collect: changed); "
              << (stale == 1 ? "it runs" : "they run") << " again\n";
  if (!quiet)
    std::cerr << "mbfe sweep: " << sweep.name << ": " << n << " points, " << (n - static_cast<long>(todo.size()))
              << " already done, " << todo.size() << " to run on " << jobs << " job" << (jobs == 1 ? "" : "s") << "\n";
  // Each distinct solver is compiled once: the first point of a key runs
  // alone for that key; the others wait until it has finished (and cached it).
  std::vector<std::string> key(todo.size());
  for (std::size_t k = 0; k < todo.size(); ++k) key[k] = solver_key(sweep, model_text, todo[k]);
  enum class KeyState { kIdle, kCompiling, kReady };
  std::map<std::string, KeyState> keys;
  for (const std::string& k : key) keys[k] = k.empty() ? KeyState::kReady : KeyState::kIdle;

  const std::string exe = self_exe();
  // The points share the cores: each may use its share of threads (a
  // catenary's two wires step on two threads when a point has two cores).
  const unsigned per_point = std::max(1u, runtime::thread_budget() / static_cast<unsigned>(jobs));
  std::vector<std::string> environment = {"MBFE_THREADS=" + std::to_string(per_point)};
  for (char** e = environ; *e != nullptr; ++e)
    if (std::strncmp(*e, "MBFE_THREADS=", 13) != 0) environment.emplace_back(*e);
  std::vector<char*> envp;
  for (std::string& e : environment) envp.push_back(e.data());
  envp.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  std::map<pid_t, std::size_t> running;  // pid -> index into todo
  std::vector<bool> started(todo.size(), false);
  std::size_t finished = 0;
  while (finished < todo.size()) {
    for (std::size_t k = 0; k < todo.size() && static_cast<long>(running.size()) < jobs; ++k) {
      if (started[k]) continue;
      KeyState& state = keys[key[k]];
      if (state == KeyState::kCompiling) continue;
      if (state == KeyState::kIdle) state = KeyState::kCompiling;
      started[k] = true;
      std::vector<std::string> args = {exe, "sweep", sweep_file, "--out", out_dir, "--point",
                                       std::to_string(todo[k]), "--quiet"};
      for (const std::string& set : model_sets) args.insert(args.end(), {"--set", set});
      std::vector<char*> argv;
      for (std::string& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      pid_t pid = 0;
      if (::posix_spawn(&pid, exe.c_str(), nullptr, nullptr, argv.data(), envp.data()) != 0)
        throw std::runtime_error("cannot start " + exe);
      running[pid] = k;
    }
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) break;
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    keys[key[it->second]] = KeyState::kReady;
    running.erase(it);
    ++finished;
    if (!quiet && ::isatty(2)) {
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const double left = elapsed / static_cast<double>(finished) * static_cast<double>(todo.size() - finished);
      std::fprintf(stderr, "\r  %zu/%zu run, %.0f s left   ", finished, todo.size(), left);
    }
  }
  if (!quiet && ::isatty(2)) std::fprintf(stderr, "\n");
  const SweepCounts c = write_summary(sweep, model_text, out_dir, warnings);
  if (!quiet)
    std::cerr << "mbfe sweep: " << c.done << " done, " << c.failed << " failed" << (c.missing ? ", " : "")
              << (c.missing ? std::to_string(c.missing) + " missing" : "") << "; summary in " << out_dir
              << "/summary.csv and summary.json\n";
  return c.failed + c.missing == 0 ? 0 : 3;
}

}  // namespace

int cmd_sweep(const Args& args) {
  const ParsedArgs parsed(args, {"out", "jobs", "point", "partition", "time", "array-limit", "set"},
                          {"help", "quiet", "collect", "slurm", "dry-run"});
  if (parsed.has("help")) {
    std::cout << kHelp;
    return 0;
  }
  if (parsed.positional().size() != 1) throw UsageError("expected one sweep file (see --help)");
  const auto out = parsed.value("out");
  if (!out || out->empty()) throw UsageError("--out DIR is required: the folder of the points and the summary");
  const bool quiet = parsed.has("quiet");
  const std::string sweep_file = parsed.positional()[0];
  ir::Sweep sweep = frontend::load_sweep_file(sweep_file);
  // A --set of a path the sweep file's `set:` names wins: it is the later word.
  for (const ir::ModelOverride& o : model_overrides(parsed))
    sweep.set.erase(std::remove_if(sweep.set.begin(), sweep.set.end(),
                                   [&](const ir::SweepVariable& v) { return v.path == o.path; }),
                    sweep.set.end());
  const std::string model_path = frontend::sweep_model_path(sweep);
  if (!fs::exists(model_path))
    throw ir::ModelError(sweep.source_path, sweep.model_loc, "model file '" + model_path + "' does not exist");
  const std::string model_text =
      frontend::overridden_sweep_model(sweep, frontend::read_sweep_model(sweep), model_overrides(parsed));
  frontend::check_sweep_paths(sweep, model_text);
  const long n = sweep.points();
  // The summary and the points go into DIR: it must be a folder, its summary
  // must not be one of the sweep's own files (the sweep file, the model, the
  // files the model reads), and none of them may lie in the folders mbfe fills.
  std::vector<std::string> inputs{sweep_file, model_path};
  // The files the models read, as the points have them (the model file alone
  // may hold values only the points make valid): the first point's, and every
  // point's when the sweep varies a running-surface profile (which may name a
  // table file per point).
  const bool varies_files = std::any_of(sweep.vary.begin(), sweep.vary.end(), [](const ir::SweepVariable& v) {
    return v.path.find("profile") != std::string::npos;
  });
  for (long i = 0; i < (varies_files ? n : std::min(n, 1L)); ++i) {
    try {
      const ir::Model point = frontend::parse_model_text(frontend::point_model_text(sweep, model_text, i), model_path);
      for (std::string& file : ir::data_files(point))
        if (std::find(inputs.begin(), inputs.end(), file) == inputs.end()) inputs.push_back(std::move(file));
    } catch (const ir::ModelError&) {
      // A point's own run reports what is wrong with its model.
    }
  }
  check_output_folder(*out, "--out", inputs);
  for (const char* name : {"summary.csv", "summary.json"})
    check_output_file((fs::path(*out) / name).string(), "--out", inputs, true);
  for (const char* folder : {"points", "slurm"})
    check_folder_holds_no_input((fs::path(*out) / folder).string(), "--out", inputs);
  SlurmOptions slurm;
  if (parsed.has("slurm")) {
    slurm.partition = parsed.value("partition").value_or("");
    slurm.time = parsed.value("time").value_or("");
    if (const auto k = parsed.number("array-limit")) {
      if (*k < 1 || *k != std::floor(*k)) throw UsageError("--array-limit must be a positive whole number");
      slurm.array_limit = static_cast<long>(*k);
    }
    slurm.dry_run = parsed.has("dry-run");
    slurm.model_sets = parsed.values("set");
    // Before anything is created: a newline in --out would write DIR too.
    check_slurm_arguments(self_exe(), fs::absolute(sweep_file).string(), fs::absolute(*out).string(), slurm);
  }
  fs::create_directories(*out);

  if (const auto point = parsed.number("point")) {
    if (*point < 0 || *point >= static_cast<double>(n) || *point != std::floor(*point))
      throw UsageError("--point must be a whole number in 0.." + std::to_string(n - 1));
    const PointResult r = run_sweep_point(sweep, model_text, *out, static_cast<long>(*point));
    if (!quiet) std::cerr << "mbfe sweep: point " << r.point << (r.done ? " done" : " failed: " + r.message) << "\n";
    return r.exit_status;
  }
  // Likely unit mistakes, once for the whole sweep (a point's run says nothing of them).
  const std::vector<std::string> warnings = sweep_warnings(sweep, model_text, model_overrides(parsed), *out);
  for (const std::string& w : warnings) std::cerr << w << "\n";
  if (parsed.has("collect")) {
    const SweepCounts c = write_summary(sweep, model_text, *out, warnings);
    if (!quiet)
      std::cerr << "mbfe sweep: " << c.done << " done, " << c.failed << " failed, " << c.missing << " missing"
                << (c.stale ? " (" + std::to_string(c.stale) + " with a result of another request)" : "") << "\n";
    return c.failed + c.missing == 0 ? 0 : 3;
  }
  if (parsed.has("slurm")) {
    const SlurmOptions& options = slurm;
    // The tasks find their solvers in DIR/cache, compiled here where the compiler is.
    ::setenv("MBFE_CACHE_DIR", (fs::absolute(*out) / "cache").c_str(), 1);
    precompile(sweep, model_text, *out, quiet);
    const SlurmSubmission s = submit_slurm_sweep(self_exe(), sweep_file, *out, sweep.name, n, options);
    if (options.dry_run) {
      std::cout << "mbfe sweep: wrote " << s.points_script << " and " << s.collect_script << " (" << n
                << " points); submit with\n  sbatch " << shell_word(s.points_script)
                << "\n  sbatch --dependency=afterany:<array job> " << shell_word(s.collect_script) << "\n";
    } else {
      std::cout << "mbfe sweep: submitted job array " << s.array_job << " (" << n << " points) and collect job "
                << s.collect_job << "; the summary will be " << *out << "/summary.csv\n";
    }
    return 0;
  }
  if (parsed.has("dry-run") || parsed.has("partition") || parsed.has("time") || parsed.has("array-limit"))
    throw UsageError("--dry-run, --partition, --time and --array-limit go with --slurm");
  long jobs = static_cast<long>(runtime::thread_budget());
  if (const auto j = parsed.number("jobs")) {
    if (*j < 1 || *j != std::floor(*j)) throw UsageError("--jobs must be a positive whole number");
    jobs = static_cast<long>(*j);
  }
  return run_local(sweep, sweep_file, model_text, *out, jobs, quiet, parsed.values("set"), warnings);
}

}  // namespace mbfe::tool
