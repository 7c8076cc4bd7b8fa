#include "tool/results_output.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "api/csv_format.h"
#include "tool/cli_args.h"

namespace mbfe::tool {

namespace {
constexpr std::size_t kFlushEveryRows = 256;  // bounded loss window even if the process is killed

}

ResultsOutput::ResultsOutput(const std::string& path) : path_(path) {
  if (path.empty()) {
    file_ = stdout;
  } else {
    file_ = std::fopen(path.c_str(), "w");
    // A path that cannot be written (no such folder, no permission) is bad
    // input: UsageError, exit status 2, before anything is computed.
    if (!file_) throw UsageError(path + ": cannot write the output: " + std::strerror(errno));
    owned_ = true;
  }
}

ResultsOutput::~ResultsOutput() {
  if (!file_) return;
  std::fflush(file_);
  if (owned_) std::fclose(file_);
}

void ResultsOutput::discard_if_empty() {
  if (!owned_ || !file_ || rows_ > 0) return;
  std::fclose(file_);
  file_ = nullptr;
  std::remove(path_.c_str());
}

void ResultsOutput::header(const std::vector<std::string>& columns) {
  for (std::size_t i = 0; i < columns.size(); ++i) std::fprintf(file_, "%s%s", i ? "," : "", columns[i].c_str());
  std::fputc('\n', file_);
}

void ResultsOutput::row(const double* values, std::size_t count) {
  // One buffer per row, written at once: printf per value cost more than the
  // simulation on wide rows (docs/performance.md).
  format_csv_row(values, count, line_);
  std::fwrite(line_.data(), 1, line_.size(), file_);
  if (++rows_ % kFlushEveryRows == 0) flush();
}

void ResultsOutput::flush() {
  if (std::fflush(file_) != 0) throw std::runtime_error(path_ + ": write failed: " + std::strerror(errno));
}

}  // namespace mbfe::tool
