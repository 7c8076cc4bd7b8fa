// Solvers for models not known at build time: generated, compiled with this
// build's compiler and flags into a shared library, cached, and loaded.
//
// Cache layout: <cache>/<key>/solver.so and <key>/solver.so.sha256, where key
// is the SHA-256 of the generated sources, the generator version, the
// compiler and its flags (content-addressed: a changed model or toolchain
// gets a new entry). An entry is built in a private temporary folder and
// renamed into place in one step, so concurrent processes never see half of
// one; a corrupted entry (checksum mismatch, or bytes that do not load) is
// discarded and rebuilt. Build folders left by a killed process are removed
// once they are an hour old.
//
// Test hook: $MBFE_JIT_COMPILER_OVERRIDE, when set, replaces the compiler
// command (it is then part of the cache key). tests/api/solver_cache_test.cpp points it at a
// script that fails, to check that a failed compile leaves nothing behind and
// shows the compiler's message. Not meant for users.
#pragma once

#include <string>

#include "ir/model.h"
#include "runtime/abi/mbfe_model_abi.h"

namespace mbfe {

struct LoadedSolver {
  const mbfe_model_v1* model = nullptr;  // owned by the loaded library (never unloaded)
  std::string library_path;
  bool compiled_now = false;  // false: reused from the cache
  double compile_seconds = 0.0;
};

/// The cache folder: $MBFE_CACHE_DIR, else $XDG_CACHE_HOME/mbfe, else
/// $HOME/.cache/mbfe, else /tmp/mbfe-cache-<uid>.
std::string solver_cache_dir();

/// Generates, compiles (when not cached) and loads the solver of `model`.
/// Prints one line on stderr about the cache unless `quiet`. The cache key is
/// the model file's SHA-256 with the generator's fingerprint, or the generated
/// sources when `by_sources` (or when the model has no file behind it).
/// @throws std::runtime_error with the compiler's message when compiling fails
/// (nothing is left behind in the cache).
LoadedSolver load_solver(const ir::Model& model, bool quiet, bool by_sources = false);

}  // namespace mbfe
