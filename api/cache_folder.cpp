#include "api/cache_folder.h"

#include <fcntl.h>
#include <pwd.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace mbfe {

namespace {

// "root (uid 0)", or "uid 1234" for a uid without a name.
std::string user_name(uid_t uid) {
  std::vector<char> buffer(16384);
  passwd entry{};
  passwd* found = nullptr;
  if (::getpwuid_r(uid, &entry, buffer.data(), buffer.size(), &found) == 0 && found)
    return std::string(found->pw_name) + " (uid " + std::to_string(uid) + ")";
  return "uid " + std::to_string(uid);
}

std::string octal_mode(mode_t mode) {
  char text[8];
  std::snprintf(text, sizeof text, "%04o", static_cast<unsigned>(mode & 07777));
  return text;
}

// mkdir -p with mode 0700 for every folder it creates.
void create_private_folders(const std::filesystem::path& path) {
  std::filesystem::path partial;
  for (const auto& part : path) {
    partial /= part;
    if (::mkdir(partial.c_str(), 0700) != 0 && errno != EEXIST)
      throw std::runtime_error(path.string() + ": cannot create the solver cache: " + std::strerror(errno));
  }
}

}  // namespace

UniqueFd& UniqueFd::operator=(UniqueFd&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.release();
  }
  return *this;
}

UniqueFd::~UniqueFd() {
  if (fd_ >= 0) ::close(fd_);
}

std::string solver_cache_dir() {
  if (const char* dir = std::getenv("MBFE_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg == '/') return std::string(xdg) + "/mbfe";
  if (const char* home = std::getenv("HOME"); home && *home == '/') return std::string(home) + "/.cache/mbfe";
  throw CacheRefused(
      "no folder for the solver cache: MBFE_CACHE_DIR is not set, and neither XDG_CACHE_HOME nor HOME is an "
      "absolute path; set MBFE_CACHE_DIR to a folder of your own (e.g. export MBFE_CACHE_DIR=\"$PWD/mbfe-cache\")");
}

void require_private(const struct stat& st, const std::string& path, const std::string& what) {
  const uid_t me = ::geteuid();
  if (st.st_uid != me)
    throw CacheRefused(path + ": refusing the " + what + ": it belongs to " + user_name(st.st_uid) +
                       ", not to you, " + user_name(me) + " (mode " + octal_mode(st.st_mode) +
                       "), so code in it could be anyone's. Remove it (as its owner or root), or set MBFE_CACHE_DIR " +
                       "to a folder of your own");
  const std::string found = "owner " + user_name(st.st_uid) + ", mode " + octal_mode(st.st_mode);
  if (!S_ISLNK(st.st_mode) && (st.st_mode & (S_IWGRP | S_IWOTH))) {
    const char* who = (st.st_mode & S_IWGRP) && (st.st_mode & S_IWOTH) ? "its group and others"
                      : (st.st_mode & S_IWGRP)                          ? "its group"
                                                                        : "others";
    throw CacheRefused(path + ": refusing the " + what + ": it is writable by " + who + " (" + found +
                       "), who could put code in it that mbfe would run. Make it private (chmod -R go-w '" + path +
                       "'), or set MBFE_CACHE_DIR to a folder of your own");
  }
}

UniqueFd open_cache_folder(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    if (errno != ENOENT)
      throw std::runtime_error(path + ": cannot use the solver cache: " + std::strerror(errno));
    create_private_folders(path);
  }
  UniqueFd folder(::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (!folder) throw std::runtime_error(path + ": cannot open the solver cache: " + std::strerror(errno));
  if (::fstat(folder.get(), &st) != 0)
    throw std::runtime_error(path + ": cannot use the solver cache: " + std::strerror(errno));
  require_private(st, path, "solver cache folder");
  return folder;
}

int open_beneath(int dir, const std::string& name, int flags, mode_t mode) {
  int fd;
  do fd = ::openat(dir, name.c_str(), flags | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK, mode);
  while (fd < 0 && errno == EINTR);
  return fd;
}

std::string read_fd(int fd, const std::string& path, std::size_t max_bytes) {
  std::string bytes;
  char buffer[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw std::runtime_error(path + ": cannot read: " + std::strerror(errno));
    if (n == 0) return bytes;
    if (bytes.size() + static_cast<std::size_t>(n) > max_bytes)
      throw std::runtime_error(path + ": larger than " + std::to_string(max_bytes) + " bytes");
    bytes.append(buffer, static_cast<std::size_t>(n));
  }
}

}  // namespace mbfe
