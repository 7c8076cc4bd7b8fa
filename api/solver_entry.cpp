// A solver cache entry checked and its very bytes loaded (api/solver_entry.h).
#include "api/solver_entry.h"

#include <dlfcn.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include "api/cache_folder.h"
#include "api/file_util.h"
#include "frontend/sha256.h"

namespace mbfe::internal {

namespace {

constexpr const char* kManifestHeader = "mbfe solver cache entry 2";
constexpr std::size_t kMaxManifestBytes = 64 * 1024;      // a manifest is a few hundred bytes

// Why a manifest does not describe the expected solver, or "" when it does;
// `library_sha256` gets the recorded hash.
std::string manifest_mismatch(const std::string& text, const Identity& want, std::string& library_sha256) {
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line) || line != kManifestHeader) return "its manifest is not one this mbfe writes";
  std::map<std::string, std::string> fields;
  while (std::getline(in, line)) {
    const auto space = line.find(' ');
    if (space == std::string::npos) return "its manifest is malformed";
    fields[line.substr(0, space)] = line.substr(space + 1);
  }
  library_sha256 = fields["library-sha256"];
  if (fields["model"] != want.model)
    return "built for another model: '" + fields["model"] + "', not '" + want.model + "'";
  if (fields["model-sha256"] != want.model_sha256)
    return "built from another version of the model: model sha256 " + fields["model-sha256"] + ", this file's is " +
           want.model_sha256;
  if (fields["coordinates"] != std::to_string(want.coordinates))
    return "built for another version of the model: " + fields["coordinates"] + " coordinates, this one has " +
           std::to_string(want.coordinates);
  if (fields["generator"] != want.generator || fields["key"] != want.key)
    return "built by another generator, compiler or flags (generator " + fields["generator"] + ")";
  if (library_sha256.size() != 64) return "its manifest records no library hash";
  return "";
}

// dlopen of the very file `fd` is open on: the bytes just hashed, whatever
// the path names by now. The loader remembers a library by the name it was
// opened under, /proc/self/fd/N, and adds every further name of the same file
// to it; so each file is opened once per process (found again by its device
// and inode, which cannot be reused while it is mapped), and its descriptor
// stays open for ever, so that N never names another file.
void* open_library_fd(UniqueFd fd, const struct stat& st, std::string& problem) {
  static std::mutex mutex;
  static std::map<std::pair<dev_t, ino_t>, void*> loaded;
  std::lock_guard<std::mutex> lock(mutex);
  if (const auto it = loaded.find({st.st_dev, st.st_ino}); it != loaded.end()) return it->second;
  const std::string name = "/proc/self/fd/" + std::to_string(fd.get());
  void* handle = ::dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    problem = std::string("cannot load solver: ") + ::dlerror();
    return nullptr;
  }
  fd.release();
  loaded[{st.st_dev, st.st_ino}] = handle;
  return handle;
}

// Whether the loaded solver says it is the one the manifest promised.
std::string solver_mismatch(const mbfe_model_v1* solver, const Identity& want) {
  if (!solver) return "its mbfe_model_entry returned null";
  if (solver->abi_version != MBFE_MODEL_ABI_VERSION)
    return "solver ABI version " + std::to_string(solver->abi_version) + ", expected " +
           std::to_string(MBFE_MODEL_ABI_VERSION);
  const auto text = [](const char* s) { return std::string(s ? s : ""); };
  if (want.model != text(solver->model_name) || want.model_sha256 != text(solver->model_sha256) ||
      want.coordinates != solver->num_coordinates || want.generator != text(solver->generator_version))
    return "the library holds the solver of '" + text(solver->model_name) + "' (sha256 " +
           text(solver->model_sha256) + ", " + std::to_string(solver->num_coordinates) + " coordinates, generator " +
           text(solver->generator_version) + "), not of this version of the model";
  return "";
}

}  // namespace

std::string manifest_text(const Identity& id, const std::string& library_sha256) {
  std::ostringstream m;
  m << kManifestHeader << "\n"
    << "key " << id.key << "\n"
    << "model " << id.model << "\n"
    << "model-sha256 " << id.model_sha256 << "\n"
    << "coordinates " << id.coordinates << "\n"
    << "generator " << id.generator << "\n"
    << "library-sha256 " << library_sha256 << "\n";
  return m.str();
}

Look look_at_entry(int cache, const std::string& entry_name, const std::filesystem::path& entry, const Identity& want) {
  Look look;
  struct stat st {};
  if (::fstatat(cache, entry_name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0) {
    if (errno != ENOENT) {
      look.present = true;
      look.problem = std::string("cannot examine it: ") + std::strerror(errno);
    }
    return look;
  }
  look.present = true;
  require_private(st, entry.string(), "solver cache entry");
  if (S_ISLNK(st.st_mode)) {
    look.problem = "it is a symbolic link, never followed in the cache";
    return look;
  }
  if (!S_ISDIR(st.st_mode)) {
    look.problem = "it is not a folder";
    return look;
  }
  const UniqueFd folder(open_beneath(cache, entry_name, O_RDONLY | O_DIRECTORY));
  if (!folder || ::fstat(folder.get(), &st) != 0) {
    look.problem = std::string("cannot open it: ") + std::strerror(errno);
    return look;
  }
  require_private(st, entry.string(), "solver cache entry");

  // Opens a file of the entry: regular, the user's, written by nobody else.
  const auto open_file = [&](const char* name, UniqueFd& fd) -> bool {
    fd = UniqueFd(open_beneath(folder.get(), name, O_RDONLY));
    const std::string path = (entry / name).string();
    if (!fd) {
      look.problem = errno == ENOENT ? std::string("no ") + name
                     : errno == ELOOP ? std::string(name) + " is a symbolic link"
                                      : "cannot open " + std::string(name) + ": " + std::strerror(errno);
      return false;
    }
    if (::fstat(fd.get(), &st) != 0 || !S_ISREG(st.st_mode)) {
      look.problem = std::string(name) + " is not a regular file";
      return false;
    }
    require_private(st, path, "solver cache file");
    return true;
  };

  UniqueFd manifest_fd, library_fd;
  if (!open_file(kManifestName, manifest_fd)) {
    if (look.problem == std::string("no ") + kManifestName) look.problem += " (an older mbfe's entry, or a copy)";
    return look;
  }
  std::string recorded_sha256;
  try {
    look.problem =
        manifest_mismatch(read_fd(manifest_fd.get(), (entry / kManifestName).string(), kMaxManifestBytes), want,
                          recorded_sha256);
  } catch (const std::runtime_error& e) {
    look.problem = e.what();
  }
  if (!look.problem.empty() || !open_file(kLibraryName, library_fd)) return look;
  try {
    const std::string bytes = read_fd(library_fd.get(), (entry / kLibraryName).string(), kMaxLibraryBytes);
    if (frontend::sha256_hex(bytes) != recorded_sha256) {
      look.problem = "the library's bytes do not match the hash its manifest records (damaged, or changed after "
                     "it was compiled)";
      return look;
    }
  } catch (const std::runtime_error& e) {
    look.problem = e.what();
    return look;
  }

  // Loaded even when it proves not to fit: a rebuilt library is another
  // file, loaded afresh.
  void* handle = open_library_fd(std::move(library_fd), st, look.problem);
  if (!handle) return look;
  const auto entry_fn = reinterpret_cast<mbfe_model_entry_fn>(::dlsym(handle, "mbfe_model_entry"));
  const mbfe_model_v1* solver = entry_fn ? entry_fn() : nullptr;
  look.problem = entry_fn ? solver_mismatch(solver, want) : "no mbfe_model_entry symbol";
  if (look.problem.empty()) look.model = solver;
  return look;
}

}  // namespace mbfe::internal
