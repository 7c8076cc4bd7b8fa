#include "frontend/capped_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <vector>

namespace mbfe::frontend {

namespace {

CappedRead refused(ReadFault fault, std::string why) {
  CappedRead out;
  out.fault = fault;
  out.why = std::move(why);
  return out;
}

}  // namespace

CappedRead read_capped_file(const std::string& path, std::size_t max_bytes, FileKinds kinds) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0)
    return refused(ReadFault::kCannotRead, std::string("cannot read: ") + std::strerror(errno));
  if (!S_ISREG(info.st_mode) && kinds == FileKinds::kRegularOnly)
    return refused(S_ISDIR(info.st_mode) ? ReadFault::kFolder : ReadFault::kNotRegular,
                   "cannot read: not a regular file (a folder, a device or a pipe)");
  if (S_ISDIR(info.st_mode)) return refused(ReadFault::kFolder, "cannot read: is a directory");
  if (S_ISREG(info.st_mode) && static_cast<std::size_t>(info.st_size) > max_bytes)
    return refused(ReadFault::kTooLarge, "the file is " + std::to_string(info.st_size) +
                                             " bytes, more than the limit of " + std::to_string(max_bytes));
  std::ifstream in(path, std::ios::binary);
  if (!in) return refused(ReadFault::kCannotRead, std::string("cannot read: ") + std::strerror(errno));
  CappedRead out;
  if (S_ISREG(info.st_mode)) out.text.reserve(static_cast<std::size_t>(info.st_size));
  std::vector<char> block(std::size_t{1} << 16);
  while (in && out.text.size() <= max_bytes) {
    in.read(block.data(), static_cast<std::streamsize>(block.size()));
    out.text.append(block.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) return refused(ReadFault::kCannotRead, "cannot read: I/O error");
  if (out.text.size() > max_bytes)
    return refused(ReadFault::kTooLarge, "the file is more than the limit of " + std::to_string(max_bytes) + " bytes");
  return out;
}

}  // namespace mbfe::frontend
