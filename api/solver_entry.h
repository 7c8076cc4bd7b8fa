// One entry of the solver cache (api/solver_cache.h): its manifest, and the
// checks that pass before its library is loaded (ownership, manifest,
// library hash, the solver's own record). Internal to api/.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include "runtime/abi/mbfe_model_abi.h"

namespace mbfe::internal {

inline constexpr const char* kLibraryName = "solver.so";
inline constexpr const char* kManifestName = "manifest";
inline constexpr std::size_t kMaxLibraryBytes = std::size_t(1) << 32;  // 4 GiB: far above any solver

// What an entry must have been built for: the manifest's fields.
struct Identity {
  std::string key;  // full SHA-256 of the key material
  std::string model;
  std::string model_sha256;
  int coordinates = 0;
  std::string generator;
};

/// The manifest written beside a library whose SHA-256 is `library_sha256`.
std::string manifest_text(const Identity& id, const std::string& library_sha256);

// The outcome of looking at an entry: loaded, absent, or unusable (why).
struct Look {
  const mbfe_model_v1* model = nullptr;
  bool present = false;
  std::string problem;
};

/// Checks the entry `entry_name` of the cache folder open as `cache` (`entry`
/// its path, for messages) and loads its library when every check passes.
/// @throws CacheRefused when something in it belongs to someone else or
///         others may write it; any other fault is a problem (the entry is
///         rebuilt).
Look look_at_entry(int cache, const std::string& entry_name, const std::filesystem::path& entry, const Identity& want);

}  // namespace mbfe::internal
