// Reading a whole file with a bound on its size, so that no input is read
// without end: a device such as /dev/zero, a sparse file of gigabytes that
// takes no disk space, a file that grows while it is read.
#pragma once

#include <cstddef>
#include <string>

namespace mbfe::frontend {

/// Which files read_capped_file takes besides regular ones.
enum class FileKinds {
  kRegularOnly,  // a folder, device, pipe or socket is refused before reading
  kAlsoStreams,  // pipes and devices are read up to the cap (a model from /dev/stdin); folders refused
};

/// Why read_capped_file refused a file.
enum class ReadFault {
  kNone,
  kCannotRead,  // stat or open failed, or an I/O error
  kFolder,
  kNotRegular,  // a device, pipe or socket under FileKinds::kRegularOnly
  kTooLarge,    // more than max_bytes: by its size before reading, or as read
};

struct CappedRead {
  std::string text;            // the bytes (ReadFault::kNone)
  ReadFault fault = ReadFault::kNone;
  std::string why;             // "cannot read: No such file or directory", "the file is 1073741824 bytes, more
                               // than the limit of 67108864", ...; empty when read
  explicit operator bool() const { return fault == ReadFault::kNone; }
};

/// Reads `path` whole. A regular file larger than `max_bytes` is refused by
/// its size before a byte is read; any file is read in blocks and refused as
/// soon as it gives more than `max_bytes` (at most one block past the cap is
/// held), so memory follows the file's size, not the cap.
CappedRead read_capped_file(const std::string& path, std::size_t max_bytes, FileKinds kinds);

}  // namespace mbfe::frontend
