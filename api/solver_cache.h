// Solvers for models not known at build time: generated, compiled with this
// build's compiler and flags into a shared library, cached, and loaded.
//
// Cache layout, in the cache folder (solver_cache_dir(), mode 0700):
//   <name>-<key>/          an entry, mode 0700: the generated sources,
//     solver.so            the library (0600),
//     manifest             what it was built for and the SHA-256 of its bytes
//                          (0600), written by the process that compiled it;
//   <name>-<key>.lock      taken (flock) by whoever builds the entry;
//   .build-XXXXXX/         a build in progress.
// The key is the SHA-256 of what decides the library: the model file's
// SHA-256 with the generator's fingerprint (or the generated sources), the
// generator version, the compiler and its flags. An entry is built in a
// private folder and renamed into place in one step, under the entry's lock,
// so concurrent first runs compile once and the others wait and reuse it.
//
// Nothing is loaded unless the cache folder, the entry and its files belong
// to the user and no one else may write them (else CacheRefused), the
// manifest names this model (name, file SHA-256, coordinates, generator,
// key) and the library's bytes hash to what the manifest records; the
// library is opened without following links and those very bytes are loaded
// (dlopen of /proc/self/fd/N). After loading, the solver's own record (name,
// SHA-256, coordinates, generator) is checked again. An entry that fails a
// check other than ownership (a link, a truncated or changed library,
// another model's or version's, a library that does not load) is discarded
// and rebuilt. SIGINT, SIGTERM or SIGHUP during a build end the compiler's
// process group and remove the build folder before taking effect. The trust
// model is in docs/robustness.md.
//
// Test hook: $MBFE_JIT_COMPILER_OVERRIDE, when set, replaces the compiler
// command (it is then part of the cache key). tests/api/solver_cache_test.cpp
// points it at scripts that fail, sleep or wrap the compiler. Not meant for
// users.
#pragma once

#include <string>

#include "api/cache_folder.h"
#include "ir/model.h"
#include "runtime/abi/mbfe_model_abi.h"

namespace mbfe {

struct LoadedSolver {
  const mbfe_model_v1* model = nullptr;  // owned by the loaded library (never unloaded)
  std::string library_path;
  bool compiled_now = false;  // false: reused from the cache
  double compile_seconds = 0.0;
};

/// Generates, compiles (when not cached) and loads the solver of `model`.
/// Prints one line on stderr about the cache unless `quiet` (two when it
/// waits for another process's compile or rebuilds an entry). The cache key
/// is the model file's SHA-256 with the generator's fingerprint, or the
/// generated sources when `by_sources` (or when the model has no file behind
/// it).
/// @throws CacheRefused (a runtime::InvalidInput) when there is no cache
///         folder or something in it could have been written by someone else;
///         CompileInterrupted when a signal ended the compile and the program
///         lives on; std::runtime_error with the compiler's message when
///         compiling fails (nothing is left behind in the cache).
LoadedSolver load_solver(const ir::Model& model, bool quiet, bool by_sources = false);

}  // namespace mbfe
