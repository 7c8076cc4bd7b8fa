#include "api/solver_cache.h"

#include <dlfcn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>

#include "api/file_util.h"
#include "frontend/sha256.h"
#include "generator/emit/generate_solver.h"
#include "generator_fingerprint.h"
#include "jit_config.h"

namespace mbfe {

namespace fs = std::filesystem;

namespace {

constexpr const char* kLibraryName = "solver.so";
constexpr std::size_t kMaxCompilerMessage = 8000;  // characters of compiler output shown

std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

// Runs `command` with stdout and stderr captured; returns the exit status.
int run_captured(const std::string& command, std::string& output) {
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot start the compiler: " + command);
  char buffer[4096];
  std::size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) output.append(buffer, n);
  const int status = ::pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

bool entry_is_intact(const fs::path& entry) {
  std::error_code ec;
  if (!fs::is_regular_file(entry / kLibraryName, ec)) return false;
  try {
    const std::string expected = read_file((entry / (std::string(kLibraryName) + ".sha256")).string());
    return expected == frontend::sha256_hex(read_file((entry / kLibraryName).string()));
  } catch (const std::exception&) {
    return false;
  }
}

// Moves a bad entry out of the way atomically, then deletes it. If the rename
// fails, another process has moved it already (and may have put a fresh entry
// in its place by the time we would delete): leave the path alone.
void discard_entry(const fs::path& entry) {
  const fs::path trash = entry.string() + ".discard." + std::to_string(::getpid());
  std::error_code ec;
  fs::rename(entry, trash, ec);
  if (!ec) fs::remove_all(trash, ec);
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

// The compiler command: this build's compiler, unless the test-only hook
// $MBFE_JIT_COMPILER_OVERRIDE names another command (tests/robustness uses it
// to simulate a failing compiler). It is part of the cache key.
std::string jit_compiler() {
  if (const char* cc = std::getenv("MBFE_JIT_COMPILER_OVERRIDE"); cc && *cc) return cc;
  return MBFE_JIT_COMPILER;
}

const mbfe_model_v1* open_library(const fs::path& library) {
  void* handle = ::dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) throw std::runtime_error(std::string("cannot load solver: ") + ::dlerror());
  auto entry = reinterpret_cast<mbfe_model_entry_fn>(::dlsym(handle, "mbfe_model_entry"));
  if (!entry) {
    ::dlclose(handle);  // so that a rebuilt library at the same path is loaded afresh
    throw std::runtime_error(library.string() + ": no mbfe_model_entry symbol");
  }
  const mbfe_model_v1* model = entry();
  if (!model || model->abi_version != MBFE_MODEL_ABI_VERSION) {
    ::dlclose(handle);
    throw std::runtime_error(library.string() + ": solver ABI version mismatch");
  }
  return model;
}

}  // namespace

std::string solver_cache_dir() {
  if (const char* dir = std::getenv("MBFE_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::string(xdg) + "/mbfe";
  if (const char* home = std::getenv("HOME"); home && *home) return std::string(home) + "/.cache/mbfe";
  return "/tmp/mbfe-cache-" + std::to_string(::getuid());
}

LoadedSolver load_solver(const ir::Model& model, bool quiet, bool by_sources) {
  // The key: what the sources would be, without generating them. A model read
  // from text is known by the SHA-256 of that text and the fingerprint of the
  // code that turns text into sources; a model built otherwise by the sources.
  std::optional<gen::GeneratedSolver> sources;
  const std::string compiler = jit_compiler();
  std::string key_material = std::string("mbfe ") + gen::generator_version() + "\n" + compiler +
                             "\n" + MBFE_JIT_FLAGS + "\n";
  if (!by_sources && !model.source_sha256.empty()) {
    key_material += std::string("fingerprint ") + MBFE_GENERATOR_FINGERPRINT + "\nmodel " + model.name + " " +
                    model.source_sha256 + "\n";
  } else {
    sources = gen::generate_solver(model);
    for (const auto& file : sources->files) key_material += file.name + "\n" + file.text;
  }
  const std::string key = frontend::sha256_hex(key_material).substr(0, 32);

  const fs::path cache(solver_cache_dir());
  const fs::path entry = cache / (model.name + "-" + key);
  LoadedSolver result;
  result.library_path = (entry / kLibraryName).string();

  if (fs::exists(entry)) {
    std::string damage = "checksum mismatch";
    if (entry_is_intact(entry)) {
      try {
        result.model = open_library(entry / kLibraryName);
        if (!quiet) std::cerr << "mbfe: using cached solver " << result.library_path << "\n";
        return result;
      } catch (const std::runtime_error& e) {
        damage = e.what();  // intact bytes that do not load: rebuild them too
      }
    }
    if (!quiet)
      std::cerr << "mbfe: cached solver " << entry.string() << " is damaged (" << damage << "); rebuilding\n";
    discard_entry(entry);
  }

  std::error_code ec;
  fs::create_directories(cache, ec);
  if (ec) throw std::runtime_error(cache.string() + ": cannot create the solver cache: " + ec.message());
  remove_stale_leftovers(cache);
  std::string staging_pattern = (cache / ".build-XXXXXX").string();
  if (!::mkdtemp(staging_pattern.data()))
    throw std::runtime_error(cache.string() + ": cannot create a build folder in the solver cache");
  const fs::path staging(staging_pattern);
  try {
    if (!sources) sources = gen::generate_solver(model);
    for (const auto& file : sources->files) write_file_atomically((staging / file.name).string(), file.text);
    const fs::path library = staging / kLibraryName;
    const std::string command = compiler + " " + MBFE_JIT_FLAGS +
                                " -std=c++17 -shared -fPIC -DMBFE_SHARED_ENTRY -I" +
                                shell_quote(MBFE_JIT_ABI_INCLUDE) + " " +
                                shell_quote((staging / (model.name + ".cpp")).string()) + " -o " +
                                shell_quote(library.string());
    const auto start = std::chrono::steady_clock::now();
    std::string output;
    const int status = run_captured(command, output);
    result.compile_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (status != 0) {
      if (output.size() > kMaxCompilerMessage) output = output.substr(0, kMaxCompilerMessage) + "\n[...]";
      throw std::runtime_error("compiling the solver of '" + model.name + "' failed (" + command +
                               "):\n" + output);
    }
    write_file_atomically((staging / (std::string(kLibraryName) + ".sha256")).string(),
                          frontend::sha256_hex(read_file(library.string())));
    fs::rename(staging, entry, ec);  // atomic; fails if another process got there first
    if (ec) {
      fs::remove_all(staging, ec);
      if (!entry_is_intact(entry)) throw std::runtime_error(entry.string() + ": solver cache entry unusable");
    }
  } catch (...) {
    fs::remove_all(staging, ec);
    throw;
  }
  result.model = open_library(entry / kLibraryName);
  result.compiled_now = true;
  if (!quiet)
    std::cerr << "mbfe: compiled the solver of '" << model.name << "' in " << result.compile_seconds
              << " s; cached as " << result.library_path << "\n";
  return result;
}

}  // namespace mbfe
