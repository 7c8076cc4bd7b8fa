// The one way tests run the built `mbfe` (MBFE_CLI): from the source folder
// (so that models/... paths work), with stdout and stderr captured apart, an
// optional environment prefix, and the exit status decoded; plus a reader for
// the CSVs it writes.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace mbfe::test {

/// 'text' quoted for the shell.
inline std::string shell_quote(const std::string& text) {
  std::string q = "'";
  for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

struct CliRun {
  int status = -1;  // exit status; 128 + signal number if killed by a signal
  std::string out;  // stdout
  std::string err;  // stderr
  /// stdout then stderr, for checks that do not care which stream says it.
  std::string all() const { return out + err; }
};

/// Runs `env_prefix mbfe args` through the shell from the source folder.
inline CliRun run_cli(const std::string& args, const std::string& env_prefix = "") {
  char out_path[] = "/tmp/mbfe-cli-out-XXXXXX";
  char err_path[] = "/tmp/mbfe-cli-err-XXXXXX";
  const int out_fd = ::mkstemp(out_path), err_fd = ::mkstemp(err_path);
  if (out_fd < 0 || err_fd < 0) throw std::runtime_error("run_cli: mkstemp failed");
  ::close(out_fd);
  ::close(err_fd);
  const std::string command = "cd " + shell_quote(MBFE_SOURCE_DIR) + " && " + env_prefix + " " +
                              shell_quote(MBFE_CLI) + " " + args + " >" + shell_quote(out_path) + " 2>" +
                              shell_quote(err_path);
  const int raw = std::system(command.c_str());
  CliRun run;
  run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : WIFSIGNALED(raw) ? 128 + WTERMSIG(raw) : -1;
  run.out = read_text(out_path);
  run.err = read_text(err_path);
  std::remove(out_path);
  std::remove(err_path);
  return run;
}

/// A shell prefix for a run that, broken, would read without end (a device
/// such as /dev/zero): at most 60 s and, outside AddressSanitizer builds (which
/// reserve terabytes of address space), 4 GB of it, so that a regression fails
/// its test instead of exhausting the machine.
inline std::string bounded_run_prefix() {
#if defined(__SANITIZE_ADDRESS__) || defined(MBFE_SANITIZED_BUILD)
  return "timeout 60";
#else
  return "ulimit -v 4000000 && timeout 60";
#endif
}

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  /// Index of a column, -1 if absent.
  int column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return static_cast<int>(i);
    return -1;
  }
};

/// A CSV of mbfe: one header line, then numbers (strtod reads back the
/// shortest round-trip text exactly).
inline Csv read_csv(const std::string& path) {
  Csv csv;
  std::ifstream in(path);
  std::string line, cell;
  if (!std::getline(in, line)) return csv;
  std::stringstream head(line);
  while (std::getline(head, cell, ',')) csv.header.push_back(cell);
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream cells(line);
    while (std::getline(cells, cell, ',')) row.push_back(std::strtod(cell.c_str(), nullptr));
    csv.rows.push_back(std::move(row));
  }
  return csv;
}

}  // namespace mbfe::test
