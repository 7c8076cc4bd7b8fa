#include "api/results_output.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "api/csv_format.h"
#include "runtime/errors/invalid_input.h"

namespace mbfe {

namespace {
constexpr std::size_t kFlushEveryRows = 256;  // bounded loss window even if the process is killed
// The .npy header (magic, version, length, dict, padding) takes this many bytes,
// so that it can be rewritten in place with the final row count.
constexpr std::size_t kNpyHeaderBytes = 128;

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

/// NumPy's format 1.0: "\x93NUMPY", 1, 0, the header length (little endian),
/// a Python dict padded with spaces to a 64-byte boundary, ending in '\n'.
std::string npy_header(std::size_t rows, std::size_t columns) {
  std::string dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (" + std::to_string(rows) + ", " +
                     std::to_string(columns) + "), }";
  const std::size_t length = kNpyHeaderBytes - 10;
  dict.resize(length - 1, ' ');
  dict += '\n';
  std::string out = "\x93NUMPY";
  out += '\x01';
  out += '\x00';
  out += static_cast<char>(length & 0xff);
  out += static_cast<char>((length >> 8) & 0xff);
  return out + dict;
}
}  // namespace

ResultsOutput::ResultsOutput(const std::string& path) : path_(path), npy_(ends_with(path, ".npy")) {
  if (path.empty()) {
    file_ = stdout;
  } else {
    file_ = std::fopen(path.c_str(), "w");
    // A path that cannot be written (no such folder, no permission) is bad
    // input: InvalidInput, exit status 2, before anything is computed.
    if (!file_) throw runtime::InvalidInput(path + ": cannot write the output: " + std::strerror(errno));
    owned_ = true;
    struct stat info {};
    regular_ = ::fstat(fileno(file_), &info) == 0 && S_ISREG(info.st_mode);
  }
}

ResultsOutput::~ResultsOutput() {
  if (!file_) return;
  if (npy_) {
    try {
      flush();
    } catch (const std::exception&) {
      // Destructors do not throw; flush() reported a failure already if it could.
    }
  }
  std::fflush(file_);
  if (owned_) std::fclose(file_);
}

void ResultsOutput::discard_if_empty() {
  if (!owned_ || !file_ || rows_ > 0) return;
  std::fclose(file_);
  file_ = nullptr;
  // Only a file: --out /dev/null or a pipe is not ours to remove (as root,
  // removing /dev/null breaks every program on the machine).
  if (regular_) std::remove(path_.c_str());
}

void ResultsOutput::header(const std::vector<std::string>& columns) {
  columns_ = columns.size();
  if (npy_) {
    // The names go to the sidecar (FILE.npy.json); the array's shape is
    // rewritten at every flush, so a run cut short leaves a valid file.
    const std::string h = npy_header(0, columns_);
    std::fwrite(h.data(), 1, h.size(), file_);
    return;
  }
  for (std::size_t i = 0; i < columns.size(); ++i) std::fprintf(file_, "%s%s", i ? "," : "", columns[i].c_str());
  std::fputc('\n', file_);
}

void ResultsOutput::row(const double* values, std::size_t count) {
  if (npy_) {
    static_assert(sizeof(double) == 8, "IEEE doubles");
    std::fwrite(values, sizeof(double), count, file_);  // little-endian x86-64 / aarch64, as '<f8' says
    if (++rows_ % kFlushEveryRows == 0) flush();
    return;
  }
  // One buffer per row, written at once: printf per value cost more than the
  // simulation on wide rows (docs/performance.md).
  format_csv_row(values, count, line_);
  std::fwrite(line_.data(), 1, line_.size(), file_);
  if (++rows_ % kFlushEveryRows == 0) flush();
}

void ResultsOutput::flush() {
  if (npy_ && file_) {
    const long end = std::ftell(file_);
    std::fseek(file_, 0, SEEK_SET);
    const std::string h = npy_header(rows_, columns_);
    std::fwrite(h.data(), 1, h.size(), file_);
    std::fseek(file_, end, SEEK_SET);
  }
  if (std::fflush(file_) != 0) throw std::runtime_error(path_ + ": write failed: " + std::strerror(errno));
}

}  // namespace mbfe
