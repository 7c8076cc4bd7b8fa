#include "api/modal_cache.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <Eigen/Core>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <iostream>
#include <random>
#include <sstream>
#include <stdexcept>

#include "api/cache_folder.h"
#include "jit_config.h"
#include "frontend/sha256.h"
#include "modal_fingerprint.h"

namespace mbfe {

namespace {

constexpr const char* kFolder = "modes";
constexpr const char* kMagic = "mbfe-modes";
constexpr int kFormat = 1;
// Longer than any header this code writes (about 220 bytes).
constexpr std::size_t kMaxHeaderBytes = 512;

std::string entry_key(const std::string& inputs) {
  const std::string build = std::string("modes cache ") + std::to_string(kFormat) + "\nsources " +
                            MBFE_MODAL_FINGERPRINT + "\ncompiler " + MBFE_JIT_COMPILER + "\nflags " + MBFE_JIT_FLAGS +
                            "\neigen " + std::to_string(EIGEN_WORLD_VERSION) + "." +
                            std::to_string(EIGEN_MAJOR_VERSION) + "." + std::to_string(EIGEN_MINOR_VERSION) + "\n";
  return frontend::sha256_hex_of_parts({build, inputs});
}

std::string_view bytes_of(const double* data, Eigen::Index count) {
  return {reinterpret_cast<const char*>(data), static_cast<std::size_t>(count) * sizeof(double)};
}

std::string data_sha256(const runtime::ModalBasis& basis) {
  return frontend::sha256_hex_of_parts(
      {bytes_of(basis.omega.data(), basis.omega.size()), bytes_of(basis.phi.data(), basis.phi.size())});
}

// Reads exactly `size` bytes at `offset`; false on an error or a short file.
bool read_exact(int fd, char* out, std::size_t size, off_t offset) {
  while (size > 0) {
    const ssize_t n = ::pread(fd, out, size, offset);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    out += n;
    size -= static_cast<std::size_t>(n);
    offset += n;
  }
  return true;
}

bool write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

// The private modes folder under the cache folder (created when absent), or
// an empty descriptor when there is none we may trust.
UniqueFd open_modes_folder(const std::string& cache_dir, bool create) {
  const UniqueFd cache = open_cache_folder(cache_dir);  // throws CacheRefused for a folder others could write
  if (create && ::mkdirat(cache.get(), kFolder, 0700) != 0 && errno != EEXIST) return {};
  UniqueFd folder(open_beneath(cache.get(), kFolder, O_RDONLY | O_DIRECTORY));
  if (!folder) return {};
  struct stat st {};
  if (::fstat(folder.get(), &st) != 0) return {};
  require_private(st, cache_dir + "/" + kFolder, "modes cache folder");
  return folder;
}

}  // namespace

std::string DiskModalStore::entry_path(const std::string& inputs) const {
  return cache_dir_ + "/" + kFolder + "/" + entry_key(inputs) + ".modes";
}

std::optional<runtime::ModalBasis> DiskModalStore::find(const std::string& inputs, int rows) const {
  const std::string key = entry_key(inputs);
  const std::string path = cache_dir_ + "/" + kFolder + "/" + key + ".modes";
  std::string problem;
  try {
    const UniqueFd folder = open_modes_folder(cache_dir_, false);
    if (!folder) return std::nullopt;
    const UniqueFd file(open_beneath(folder.get(), key + ".modes", O_RDONLY));
    if (!file) {
      if (errno == ENOENT) return std::nullopt;
      throw std::runtime_error(std::string("cannot open it: ") + std::strerror(errno));
    }
    struct stat st {};
    if (::fstat(file.get(), &st) != 0 || !S_ISREG(st.st_mode)) throw std::runtime_error("not a regular file");
    require_private(st, path, "modes cache entry");
    std::string head(std::min<std::size_t>(kMaxHeaderBytes, static_cast<std::size_t>(st.st_size)), '\0');
    if (!read_exact(file.get(), head.data(), head.size(), 0)) throw std::runtime_error("cannot read its header");
    const std::size_t end = head.find('\n');
    if (end == std::string::npos) throw std::runtime_error("no header line");
    std::istringstream header(head.substr(0, end));
    std::string magic, key_word, file_key, rows_word, cols_word, complete_word, sha_word, sha;
    int format = 0, complete = -1;
    long long file_rows = -1, cols = -1;
    header >> magic >> format >> key_word >> file_key >> rows_word >> file_rows >> cols_word >> cols >>
        complete_word >> complete >> sha_word >> sha;
    if (!header || magic != kMagic || format != kFormat || key_word != "key" || rows_word != "rows" ||
        cols_word != "cols" || complete_word != "complete" || sha_word != "sha256" || sha.size() != 64 ||
        (complete != 0 && complete != 1))
      throw std::runtime_error("its header is not one this version writes");
    if (file_key != key) throw std::runtime_error("its header names another key");
    if (file_rows != rows)
      throw std::runtime_error("it has " + std::to_string(file_rows) + " rows, expected " + std::to_string(rows));
    if (cols < 1 || cols > rows)
      throw std::runtime_error(std::to_string(cols) + " modes, expected 1 to " + std::to_string(rows));
    const long long data_bytes = 8LL * (cols + static_cast<long long>(rows) * cols);
    const long long expected = static_cast<long long>(end) + 1 + data_bytes;
    if (st.st_size != expected)
      throw std::runtime_error(std::to_string(st.st_size) + " bytes, expected " + std::to_string(expected) +
                               " (truncated or extended)");
    runtime::ModalBasis basis;
    basis.omega.resize(cols);
    basis.phi.resize(rows, cols);
    basis.complete = complete == 1;
    const off_t at = static_cast<off_t>(end) + 1;
    if (!read_exact(file.get(), reinterpret_cast<char*>(basis.omega.data()), 8 * cols, at) ||
        !read_exact(file.get(), reinterpret_cast<char*>(basis.phi.data()), 8 * rows * cols, at + 8 * cols))
      throw std::runtime_error("cannot read its data");
    if (data_sha256(basis) != sha) throw std::runtime_error("its data do not hash to its header's SHA-256");
    return basis;
  } catch (const std::exception& e) {
    problem = e.what();
  }
  if (!quiet_) std::cerr << "mbfe: cached modes " << path << " cannot be used (" << problem << "); computing them again\n";
  return std::nullopt;
}

void DiskModalStore::keep(const std::string& inputs, const runtime::ModalBasis& basis) const {
  if (basis.omega.size() < 1 || basis.phi.cols() != basis.omega.size()) return;
  try {
    const UniqueFd folder = open_modes_folder(cache_dir_, true);
    if (!folder) return;
    const std::string key = entry_key(inputs);
    const std::string header = std::string(kMagic) + " " + std::to_string(kFormat) + " key " + key + " rows " +
                               std::to_string(basis.phi.rows()) + " cols " + std::to_string(basis.phi.cols()) +
                               " complete " + (basis.complete ? "1" : "0") + " sha256 " + data_sha256(basis) + "\n";
    static std::atomic<unsigned> counter{0};
    const std::string temporary = ".tmp-" + key.substr(0, 16) + "-" + std::to_string(::getpid()) + "-" +
                                  std::to_string(counter++) + "-" + std::to_string(std::random_device{}());
    UniqueFd out(open_beneath(folder.get(), temporary, O_WRONLY | O_CREAT | O_EXCL, 0600));
    if (!out) return;
    const std::string_view omega = bytes_of(basis.omega.data(), basis.omega.size());
    const std::string_view phi = bytes_of(basis.phi.data(), basis.phi.size());
    const bool written = write_all(out.get(), header.data(), header.size()) &&
                         write_all(out.get(), omega.data(), omega.size()) &&
                         write_all(out.get(), phi.data(), phi.size()) && ::fsync(out.get()) == 0;
    out = UniqueFd();
    if (!written || ::renameat(folder.get(), temporary.c_str(), folder.get(), (key + ".modes").c_str()) != 0)
      ::unlinkat(folder.get(), temporary.c_str(), 0);
  } catch (const std::exception&) {
    // Not kept: the next run computes the modes again.
  }
}

std::shared_ptr<const runtime::ModalBasisStore> disk_modal_store(bool quiet) {
  try {
    return std::make_shared<DiskModalStore>(solver_cache_dir(), quiet);
  } catch (const CacheRefused&) {
    return nullptr;
  }
}

}  // namespace mbfe
