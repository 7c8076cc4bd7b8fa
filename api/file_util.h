// Writing files so that a reader never sees half of one.
#pragma once

#include <string>

namespace mbfe {

/// Writes `text` to `path` through a temporary file in the same folder and a
/// rename, so the file is either the old one or the whole new one.
/// @throws std::runtime_error naming the path on failure.
void write_file_atomically(const std::string& path, const std::string& text);

/// Reads a whole file. @throws std::runtime_error naming the path on failure.
std::string read_file(const std::string& path);

}  // namespace mbfe
