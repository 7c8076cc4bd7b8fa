#include "tool/results_columns.h"

#include <charconv>
#include <fstream>
#include <sstream>

#include "tool/cli_args.h"

namespace mbfe::tool {

namespace {

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    out.push_back(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (!out.empty() && !out.back().empty() && out.back().back() == '\r') out.back().pop_back();
  return out;
}

}  // namespace

std::vector<std::vector<double>> read_columns(const std::string& path, const std::vector<std::string>& names) {
  std::ifstream in(path);
  if (!in) throw UsageError("cannot open '" + path + "'");
  std::string line;
  if (!std::getline(in, line)) throw UsageError(path + ": empty file (expected a CSV with a header line)");
  const std::vector<std::string> header = split_fields(line);
  std::vector<std::size_t> index;
  for (const std::string& name : names) {
    std::size_t i = 0;
    while (i < header.size() && header[i] != name) ++i;
    if (i == header.size()) {
      std::string some;
      for (std::size_t k = 0; k < header.size() && k < 8; ++k) some += (k ? ", " : "") + header[k];
      throw UsageError(path + ":1: no column '" + name + "' (it has " + std::to_string(header.size()) +
                       " columns: " + some + (header.size() > 8 ? ", ..." : "") + ")");
    }
    index.push_back(i);
  }
  std::vector<std::vector<double>> out(names.size());
  int line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty()) continue;
    const std::vector<std::string> fields = split_fields(line);
    for (std::size_t c = 0; c < index.size(); ++c) {
      const std::size_t i = index[c];
      double v = 0.0;
      const std::string& f = i < fields.size() ? fields[i] : std::string();
      const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
      if (f.empty() || ec != std::errc() || end != f.data() + f.size()) {
        throw UsageError(path + ":" + std::to_string(line_number) + ": column '" + names[c] + "' (field " +
                         std::to_string(i + 1) + "): '" + f + "' is not a number");
      }
      out[c].push_back(v);
    }
  }
  return out;
}

}  // namespace mbfe::tool
