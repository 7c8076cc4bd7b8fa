#include "api/solver_cache.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>

#include "api/compiler_process.h"
#include "api/file_util.h"
#include "frontend/sha256.h"
#include "generator/emit/generate_solver.h"
#include "generator_fingerprint.h"
#include "ir/coordinate_layout.h"
#include "api/model_abi_header.h"
#include "api/solver_entry.h"
#include "jit_config.h"

namespace mbfe {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMaxCompilerMessage = 8000;  // characters of compiler output shown

using internal::Identity;
using internal::kLibraryName;
using internal::kManifestName;
using internal::kMaxLibraryBytes;
using internal::Look;
using internal::look_at_entry;
using internal::manifest_text;

// A name for something this process moves aside, unique across its threads.
std::string unique_suffix() {
  static std::atomic<unsigned> counter{0};
  return std::to_string(::getpid()) + "." + std::to_string(counter++);
}

// Moves an unusable entry out of the way atomically, then deletes it (a
// symbolic link itself, never what it points to). Called under the entry's
// lock; a failed rename means someone without it got there first.
void discard_entry(int cache, const fs::path& cache_path, const std::string& entry_name) {
  const std::string trash = entry_name + ".discard." + unique_suffix();
  if (::renameat(cache, entry_name.c_str(), cache, trash.c_str()) != 0) return;
  std::error_code ec;
  fs::remove_all(cache_path / trash, ec);
}

// Build folders and discarded entries that a killed process left behind (a
// SIGKILL or power loss during a compile): removed once they are an hour old,
// far longer than any compile takes.
void remove_stale_leftovers(const fs::path& cache) {
  std::error_code ec;
  const auto now = fs::file_time_type::clock::now();
  for (fs::directory_iterator it(cache, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(".build-", 0) != 0 && name.find(".discard.") == std::string::npos) continue;
    std::error_code time_ec;
    const auto modified = fs::last_write_time(it->path(), time_ec);
    if (!time_ec && now - modified > std::chrono::hours(1)) {
      std::error_code remove_ec;
      fs::remove_all(it->path(), remove_ec);
    }
  }
}

// Takes the entry's lock (an flock on <entry>.lock beside it), waiting for a
// process that holds it: the one compiling this very solver.
UniqueFd lock_entry(int cache, const fs::path& cache_path, const std::string& entry_name, const std::string& model,
                    bool quiet) {
  const std::string name = entry_name + ".lock";
  UniqueFd lock(open_beneath(cache, name, O_RDWR | O_CREAT, 0600));
  struct stat st {};
  if (!lock || ::fstat(lock.get(), &st) != 0)
    throw std::runtime_error((cache_path / name).string() + ": cannot open the lock of the solver cache entry: " +
                             std::strerror(errno));
  require_private(st, (cache_path / name).string(), "solver cache lock");
  if (::flock(lock.get(), LOCK_EX | LOCK_NB) == 0) return lock;
  if (errno != EWOULDBLOCK)
    throw std::runtime_error((cache_path / name).string() + ": cannot lock: " + std::strerror(errno));
  if (!quiet) std::cerr << "mbfe: waiting for another process compiling the solver of '" << model << "'\n";
  while (::flock(lock.get(), LOCK_EX) != 0)
    if (errno != EINTR)
      throw std::runtime_error((cache_path / name).string() + ": cannot lock: " + std::strerror(errno));
  return lock;
}

// The compiler command: this build's compiler, unless the test-only hook
// $MBFE_JIT_COMPILER_OVERRIDE names another command. It is part of the key.
std::string jit_compiler() {
  if (const char* cc = std::getenv("MBFE_JIT_COMPILER_OVERRIDE"); cc && *cc) return cc;
  return MBFE_JIT_COMPILER;
}

std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

// Compiles the solver into a private build folder, writes its manifest and
// renames the folder to the entry. Called under the entry's lock. Returns
// the compile's seconds.
double build_entry(int cache, const fs::path& cache_path, const std::string& entry_name, const Identity& want,
                   const gen::GeneratedSolver& sources, const std::string& compiler) {
  DeferredSignals signals;  // from here, SIGINT, SIGTERM and SIGHUP wait for the clean-up
  std::string staging_pattern = (cache_path / ".build-XXXXXX").string();
  if (!::mkdtemp(staging_pattern.data()))
    throw std::runtime_error(cache_path.string() + ": cannot create a build folder in the solver cache: " +
                             std::strerror(errno));
  const fs::path staging(staging_pattern);
  double seconds = 0.0;
  try {
    // The folder just made, opened through the checked cache folder.
    const UniqueFd folder(open_beneath(cache, staging.filename().string(), O_RDONLY | O_DIRECTORY));
    struct stat st {};
    if (!folder || ::fstat(folder.get(), &st) != 0)
      throw std::runtime_error(staging.string() + ": cannot open the build folder: " + std::strerror(errno));
    require_private(st, staging.string(), "solver build folder");
    for (const auto& file : sources.files) write_file_atomically((staging / file.name).string(), file.text);
    write_file_atomically((staging / "mbfe_model_abi.h").string(), internal::kModelAbiHeader);
    const std::string command = compiler + " " + MBFE_JIT_FLAGS +
                                " -std=c++17 -shared -fPIC -DMBFE_SHARED_ENTRY -I" + shell_quote(staging.string()) +
                                " " +
                                shell_quote((staging / (want.model + ".cpp")).string()) + " -o " +
                                shell_quote((staging / kLibraryName).string());
    const auto start = std::chrono::steady_clock::now();
    CompilerRun run = run_compiler(command, kMaxCompilerMessage + 1, signals);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (run.interrupted || signals.caught()) throw CompileInterrupted("interrupted");  // finish() below says by what
    if (run.status != 0) {
      if (run.output.size() > kMaxCompilerMessage) run.output = run.output.substr(0, kMaxCompilerMessage) + "\n[...]";
      throw std::runtime_error("compiling the solver of '" + want.model + "' failed (" + command + "):\n" +
                               run.output);
    }
    // The library as the compiler left it, made the user's alone whatever
    // the umask, hashed through the descriptor that checked it.
    const UniqueFd library(open_beneath(folder.get(), kLibraryName, O_RDONLY));
    if (!library || ::fstat(library.get(), &st) != 0 || !S_ISREG(st.st_mode) || st.st_uid != ::geteuid() ||
        ::fchmod(library.get(), 0600) != 0)
      throw std::runtime_error((staging / kLibraryName).string() + ": the compiler left no library of ours");
    const std::string library_sha256 =
        frontend::sha256_hex(read_fd(library.get(), (staging / kLibraryName).string(), kMaxLibraryBytes));
    const std::string manifest = manifest_text(want, library_sha256);
    const UniqueFd out(open_beneath(folder.get(), kManifestName, O_WRONLY | O_CREAT | O_EXCL, 0600));
    if (!out || ::write(out.get(), manifest.data(), manifest.size()) != static_cast<ssize_t>(manifest.size()) ||
        ::fsync(out.get()) != 0)
      throw std::runtime_error((staging / kManifestName).string() + ": cannot write: " + std::strerror(errno));
    // Atomic; fails only if a process without the lock (an older mbfe) put
    // an entry there meanwhile: then that one is examined like any other.
    if (::renameat(cache, staging.filename().c_str(), cache, entry_name.c_str()) != 0) {
      std::error_code ec;
      fs::remove_all(staging, ec);
    }
  } catch (...) {
    std::error_code ec;
    fs::remove_all(staging, ec);
    signals.finish();  // a signal that came takes its usual effect now
    throw;
  }
  signals.finish();
  return seconds;
}

}  // namespace

LoadedSolver load_solver(const ir::Model& model, bool quiet, bool by_sources) {
  // The key: what the sources would be, without generating them. A model read
  // from text is known by the SHA-256 of that text and the fingerprint of the
  // code that turns text into sources; a model built otherwise by the sources.
  std::optional<gen::GeneratedSolver> sources;
  const std::string compiler = jit_compiler();
  std::string key_material = std::string("mbfe ") + gen::generator_version() + "\ncache 2\n" + compiler + "\n" +
                             MBFE_JIT_FLAGS + "\n";
  if (!by_sources && !model.source_sha256.empty()) {
    key_material += std::string("fingerprint ") + MBFE_GENERATOR_FINGERPRINT + "\nmodel " + model.name + " " +
                    model.source_sha256 + "\n";
  } else {
    sources = gen::generate_solver(model);
    for (const auto& file : sources->files) key_material += file.name + "\n" + file.text;
    key_material += std::string("mbfe_model_abi.h\n") + internal::kModelAbiHeader;
  }
  Identity want;
  want.key = frontend::sha256_hex(key_material);
  want.model = model.name;
  want.model_sha256 = model.source_sha256;
  want.coordinates = ir::coordinate_layout(model).num_positions;
  want.generator = gen::generator_version();

  const fs::path cache_path(solver_cache_dir());
  if (::access("/proc/self/fd", X_OK) != 0)
    throw std::runtime_error("mbfe loads compiled solvers through /proc/self/fd, which this system does not have");
  const UniqueFd cache = open_cache_folder(cache_path.string());
  const std::string entry_name = model.name + "-" + want.key.substr(0, 32);
  const fs::path entry = cache_path / entry_name;
  LoadedSolver result;
  result.library_path = (entry / kLibraryName).string();

  // A sound entry is loaded without the lock: entries change only by rename.
  Look look = look_at_entry(cache.get(), entry_name, entry, want);
  if (!look.model) {
    const UniqueFd lock = lock_entry(cache.get(), cache_path, entry_name, model.name, quiet);
    look = look_at_entry(cache.get(), entry_name, entry, want);  // whoever held the lock may have built it
    if (!look.model) {
      if (look.present) {
        if (!quiet)
          std::cerr << "mbfe: cached solver " << entry.string() << " cannot be used (" << look.problem
                    << "); rebuilding it\n";
        discard_entry(cache.get(), cache_path, entry_name);
      }
      remove_stale_leftovers(cache_path);
      if (!sources) sources = gen::generate_solver(model);
      result.compile_seconds = build_entry(cache.get(), cache_path, entry_name, want, *sources, compiler);
      look = look_at_entry(cache.get(), entry_name, entry, want);
      if (!look.model)
        throw std::runtime_error(entry.string() + ": the solver just compiled cannot be used: " + look.problem);
      result.compiled_now = true;
    }
  }
  result.model = look.model;
  if (!quiet) {
    if (result.compiled_now)
      std::cerr << "mbfe: compiled the solver of '" << model.name << "' in " << result.compile_seconds
                << " s; cached as " << result.library_path << "\n";
    else
      std::cerr << "mbfe: using cached solver " << result.library_path << "\n";
  }
  return result;
}

}  // namespace mbfe
