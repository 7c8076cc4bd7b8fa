#include "tool/results_columns.h"

#include <charconv>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "frontend/text_guard.h"
#include "tool/cli_args.h"
#include "tool/file_checks.h"

namespace mbfe::tool {

namespace {

// The sidecar of a .npy names its columns: a few tens of bytes each.
constexpr std::size_t kMaxSidecarBytes = std::size_t{512} << 20;
// A .npy header is a short Python dict (mbfe writes 118 bytes).
constexpr std::size_t kMaxNpyHeaderBytes = 65536;

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

/// One line of `in` into `line` (without the '\n'); false at the end of the
/// input. @throws UsageError when the line is longer than kMaxResultLineBytes.
bool read_line(std::istream& in, std::string& line, const std::string& path, long number) {
  line.clear();
  std::streambuf* buffer = in.rdbuf();
  for (;;) {
    const int c = buffer->sbumpc();
    if (c == std::char_traits<char>::eof()) return !line.empty();
    if (c == '\n') return true;
    if (line.size() >= kMaxResultLineBytes)
      throw UsageError(path + ":" + std::to_string(number) + ": the line is longer than " +
                       std::to_string(kMaxResultLineBytes >> 20) + " MiB; not a results CSV");
    line.push_back(static_cast<char>(c));
  }
}

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

/// The index of each name in `header`. @throws UsageError naming a missing one.
std::vector<std::size_t> indices_of(const std::vector<std::string>& header, const std::vector<std::string>& names,
                                    const std::string& where) {
  std::vector<std::size_t> index;
  for (const std::string& name : names) {
    std::size_t i = 0;
    while (i < header.size() && header[i] != name) ++i;
    if (i == header.size()) {
      std::string some;
      for (std::size_t k = 0; k < header.size() && k < 8; ++k) some += (k ? ", " : "") + header[k];
      throw UsageError(where + ": no column '" + name + "' (it has " + std::to_string(header.size()) +
                       " columns: " + some + (header.size() > 8 ? ", ..." : "") + ")");
    }
    index.push_back(i);
  }
  return index;
}

void read_csv(std::istream& in, const std::vector<std::string>& names, ResultColumns& out) {
  const std::string& path = out.path;
  std::string line;
  if (!read_line(in, line, path, 1)) throw UsageError(path + ": empty file (expected a CSV with a header line)");
  const std::vector<std::size_t> index = indices_of(split_fields(line), names, path + ":1");
  long line_number = 1;
  while (read_line(in, line, path, line_number + 1)) {
    ++line_number;
    if (line.empty()) continue;
    if (out.lines.size() >= kMaxResultRows)
      throw UsageError(path + ":" + std::to_string(line_number) + ": more than " + std::to_string(kMaxResultRows) +
                       " rows");
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
      out.values[c].push_back(v);
    }
    out.lines.push_back(line_number);
  }
  if (in.bad()) throw UsageError(path + ": read error");
}

/// A .npy by its name or, whatever the name, by NumPy's magic bytes at the
/// start of a file that can be read again from there (`in` is left at the
/// start; a pipe is read as named).
bool is_npy(const std::string& path, std::istream& in) {
  if (ends_with(path, ".npy")) return true;
  if (in.tellg() < 0) return false;
  char magic[6] = {};
  in.read(magic, sizeof magic);
  const bool numpy = in.gcount() == 6 && std::string(magic, 6) == "\x93NUMPY";
  in.clear();
  in.seekg(0);
  return numpy;
}

/// The column names of a .npy from its sidecar FILE.npy.json (mbfe simulate
/// writes them there: a .npy holds numbers only).
std::vector<std::string> sidecar_columns(const std::string& path) {
  const std::string sidecar = path + ".json";
  std::ifstream in(sidecar, std::ios::binary);
  if (!in)
    throw UsageError(path + ": its column names are in " + sidecar + ", which cannot be read: " +
                     std::strerror(errno));
  std::string text(kMaxSidecarBytes + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > kMaxSidecarBytes)
    throw UsageError(sidecar + ": more than " + std::to_string(kMaxSidecarBytes >> 20) + " MiB; not a sidecar of mbfe");
  std::vector<std::string> names;
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    for (const nlohmann::json& c : j.at("columns")) names.push_back(c.at("name").get<std::string>());
  } catch (const nlohmann::json::exception&) {
    throw UsageError(sidecar + ": expected the sidecar mbfe simulate writes, with \"columns\": [{\"name\": ...}]");
  }
  return names;
}

/// Rows and columns from a .npy header, "{'descr': '<f8', 'fortran_order':
/// False, 'shape': (R, C), }"; only what mbfe writes is taken.
void npy_shape(const std::string& header, const std::string& path, std::size_t& rows, std::size_t& columns) {
  auto has = [&](const char* text) { return header.find(text) != std::string::npos; };
  const std::size_t shape = header.find("'shape': (");
  if (!has("'descr': '<f8'") || !has("'fortran_order': False") || shape == std::string::npos)
    throw UsageError(path + ": expected a 2-D array of little-endian doubles in C order (what mbfe simulate writes), "
                            "got the header " + frontend::utf8_prefix(header, 200));
  const char* p = header.data() + shape + 10;
  const char* end = header.data() + header.size();
  unsigned long long r = 0, c = 0;
  auto [after_rows, e1] = std::from_chars(p, end, r);
  if (e1 != std::errc() || end - after_rows < 2 || after_rows[0] != ',' || after_rows[1] != ' ')
    throw UsageError(path + ": expected a 2-D shape (rows, columns) in the header " + frontend::utf8_prefix(header, 200));
  auto [after_columns, e2] = std::from_chars(after_rows + 2, end, c);
  if (e2 != std::errc() || after_columns == end || *after_columns != ')')
    throw UsageError(path + ": expected a 2-D shape (rows, columns) in the header " + frontend::utf8_prefix(header, 200));
  rows = r;
  columns = c;
}

void read_npy(std::istream& in, const std::vector<std::string>& names, ResultColumns& out) {
  const std::string& path = out.path;
  char magic[8];
  if (!in.read(magic, 8) || std::memcmp(magic, "\x93NUMPY", 6) != 0)
    throw UsageError(path + ": not a NumPy .npy file (no \\x93NUMPY at its start)");
  std::size_t header_length = 0;
  unsigned char length[4] = {0, 0, 0, 0};
  const int length_bytes = magic[6] == 1 ? 2 : 4;  // format 1.0: 2 bytes; 2.0 and 3.0: 4
  if (magic[6] < 1 || magic[6] > 3 || !in.read(reinterpret_cast<char*>(length), length_bytes))
    throw UsageError(path + ": a .npy of an unknown format version " + std::to_string(magic[6]));
  for (int i = length_bytes - 1; i >= 0; --i) header_length = header_length << 8 | length[i];
  if (header_length > kMaxNpyHeaderBytes) throw UsageError(path + ": the .npy header is too long to be mbfe's");
  std::string header(header_length, '\0');
  if (!in.read(header.data(), static_cast<std::streamsize>(header_length)))
    throw UsageError(path + ": the .npy header is cut short");
  std::size_t rows = 0, columns = 0;
  npy_shape(header, path, rows, columns);
  const std::vector<std::string> header_names = sidecar_columns(path);
  if (header_names.size() != columns)
    throw UsageError(path + ": the array has " + std::to_string(columns) + " columns, its sidecar " + path +
                     ".json names " + std::to_string(header_names.size()));
  const std::vector<std::size_t> index = indices_of(header_names, names, path);
  if (rows > kMaxResultRows)
    throw UsageError(path + ": " + std::to_string(rows) + " rows, more than " + std::to_string(kMaxResultRows));
  static_assert(sizeof(double) == 8, "IEEE doubles, as '<f8' says (x86-64 and aarch64 are little-endian)");
  std::vector<double> row(columns);
  for (std::size_t r = 0; r < rows; ++r) {
    if (!in.read(reinterpret_cast<char*>(row.data()), static_cast<std::streamsize>(columns * sizeof(double))))
      throw UsageError(path + ": the header says " + std::to_string(rows) + " rows, the file holds " +
                       std::to_string(r));
    for (std::size_t c = 0; c < index.size(); ++c) out.values[c].push_back(row[index[c]]);
  }
}

}  // namespace

std::string ResultColumns::where(std::size_t row) const {
  if (npy) return path + ": row " + std::to_string(row + 1);
  return path + ":" + std::to_string(row < lines.size() ? lines[row] : 0);
}

ResultColumns read_columns(const std::string& path, const std::vector<std::string>& names) {
  check_input_file(path, "the results file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UsageError(path + ": cannot read the results file: " + std::strerror(errno));
  ResultColumns out;
  out.path = path;
  out.npy = is_npy(path, in);
  out.values.assign(names.size(), {});
  if (out.npy)
    read_npy(in, names, out);
  else
    read_csv(in, names, out);
  return out;
}

std::vector<std::string> result_column_names(const std::string& path) {
  check_input_file(path, "the results file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UsageError(path + ": cannot read the results file: " + std::strerror(errno));
  if (is_npy(path, in)) return sidecar_columns(path);
  bool has_rows = false;
  return read_csv_header(path, has_rows);
}

std::vector<std::string> read_csv_header(const std::string& path, bool& has_rows) {
  check_input_file(path, "the results file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UsageError(path + ": cannot read the results file: " + std::strerror(errno));
  std::string line;
  if (!read_line(in, line, path, 1)) {
    has_rows = false;
    return {};
  }
  const std::vector<std::string> header = split_fields(line);
  has_rows = read_line(in, line, path, 2) && !line.empty();
  return header;
}

}  // namespace mbfe::tool
