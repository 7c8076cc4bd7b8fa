// Runs the built `mbfe` (MBFE_CLI) from the source folder for the coupled tests.
#pragma once

#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace mbfe::coupled_test {

struct CliRun {
  int status = -1;
  std::string out;  // stdout (and stderr when merged)
};

/// `mbfe ARGS`; stderr merged into out unless `stderr_to_null`.
inline CliRun run_cli(const std::string& args, bool stderr_to_null = false) {
  const std::string cmd = std::string("cd '") + MBFE_SOURCE_DIR + "' && '" + MBFE_CLI + "' " + args +
                          (stderr_to_null ? " 2>/dev/null" : " 2>&1");
  CliRun r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int st = pclose(pipe);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  int col(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return static_cast<int>(i);
    return -1;
  }
};

inline Csv read_csv(const std::string& path) {
  Csv csv;
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) return csv;
  std::stringstream hs(line);
  std::string cell;
  while (std::getline(hs, cell, ',')) csv.header.push_back(cell);
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream ls(line);
    while (std::getline(ls, cell, ',')) row.push_back(std::stod(cell));
    csv.rows.push_back(row);
  }
  return csv;
}

}  // namespace mbfe::coupled_test
