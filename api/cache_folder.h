// The solver cache's folder: where it is, and the checks that keep anyone but
// the user from putting code in it. Everything in the cache is opened without
// following symbolic links, relative to a descriptor of a folder already
// checked, and checked again through its own descriptor (what is checked is
// what is used), as OpenSSH checks a private key: owned by the user, writable
// by nobody else. The trust model is in docs/robustness.md.
#pragma once

#include <sys/stat.h>

#include <string>

#include "runtime/errors/invalid_input.h"

namespace mbfe {

/// A cache folder or file someone other than the user could have written,
/// or no cache folder at all: a setting the user must fix (the command-line
/// tool exits with status 2). The message names the path, the owner and mode
/// found, and what to do.
class CacheRefused : public runtime::InvalidInput {
 public:
  using runtime::InvalidInput::InvalidInput;
};

/// An open file descriptor, closed when destroyed (unless released).
class UniqueFd {
 public:
  UniqueFd() = default;
  explicit UniqueFd(int fd) : fd_(fd) {}
  UniqueFd(UniqueFd&& other) noexcept : fd_(other.release()) {}
  UniqueFd& operator=(UniqueFd&& other) noexcept;
  UniqueFd(const UniqueFd&) = delete;
  UniqueFd& operator=(const UniqueFd&) = delete;
  ~UniqueFd();
  int get() const { return fd_; }
  explicit operator bool() const { return fd_ >= 0; }
  int release() {
    const int fd = fd_;
    fd_ = -1;
    return fd;
  }

 private:
  int fd_ = -1;
};

/// The cache folder: $MBFE_CACHE_DIR, else $XDG_CACHE_HOME/mbfe, else
/// $HOME/.cache/mbfe (the last two only when absolute, as the XDG base
/// directory specification says). @throws CacheRefused when none is set:
/// there is no shared fallback (a predictable name under /tmp could be made
/// first by someone else).
std::string solver_cache_dir();

/// Throws CacheRefused unless `st` (of `path`, a "solver cache folder",
/// "solver cache entry", ...: `what`) belongs to the effective user and, unless
/// it is a symbolic link, is writable by neither its group nor others.
void require_private(const struct stat& st, const std::string& path, const std::string& what);

/// Opens the cache folder `path` (created with mode 0700, with any missing
/// parents, when absent; symbolic links on the way are followed: the path is
/// the user's setting) and checks it with require_private.
/// @throws CacheRefused for a folder others could write; std::runtime_error
///         naming the path when it cannot be created or opened.
UniqueFd open_cache_folder(const std::string& path);

/// openat(dir, name) with O_NOFOLLOW, O_CLOEXEC and O_NONBLOCK (a FIFO planted
/// under the name does not block) added to `flags`. -1 with errno on failure;
/// ELOOP when `name` is a symbolic link.
int open_beneath(int dir, const std::string& name, int flags, mode_t mode = 0);

/// The whole content of an open regular file, at most `max_bytes`.
/// @throws std::runtime_error naming `path` on a read error or a larger file.
std::string read_fd(int fd, const std::string& path, std::size_t max_bytes);

}  // namespace mbfe
