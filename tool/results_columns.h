// Columns of a results file (what `mbfe simulate --out FILE` writes), read by
// name for `mbfe stats`: a CSV with a header line, or a NumPy .npy array of
// doubles whose column names are in the sidecar FILE.npy.json.
//
// Bounded whatever the file: a line of a CSV is at most kMaxResultLineBytes,
// a file holds at most kMaxResultRows rows, and only regular files and pipes
// are read (a device such as /dev/zero or a folder is refused before reading).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace mbfe::tool {

/// A CSV line longer than this is refused: the widest row mbfe writes (a model
/// at the limit of 2 million beam coordinates, with rates, ~25 bytes a
/// number) is about 100 MB.
constexpr std::size_t kMaxResultLineBytes = std::size_t{256} << 20;
/// Rows read at most: 1e8 rows of two columns take 1.6 GB; a run writes at
/// most about 10,000 rows unless --every asks for more.
constexpr std::size_t kMaxResultRows = 100000000;

/// Some columns of a results file, and where each row came from.
struct ResultColumns {
  std::vector<std::vector<double>> values;  // one vector per name asked, in that order
  std::string path;
  bool npy = false;
  std::vector<long> lines;  // CSV: the line of each row (1 = the header)
  /// "FILE:LINE" for a CSV, "FILE: row N" (from 1) for a .npy.
  std::string where(std::size_t row) const;
};

/// The columns `names` of the results file at `path` (.npy by its name or
/// its magic bytes, else CSV), as numbers.
/// @throws UsageError (cli_args.h) naming the file, and the line or row and the
///         column: a missing or unreadable file, a device or folder, a missing
///         column, a field that is not a number, a line or row count over the
///         limits, a .npy that is not the 2-D array of little-endian doubles
///         mbfe writes or has no readable sidecar naming its columns.
ResultColumns read_columns(const std::string& path, const std::vector<std::string>& names);

/// Every column name of the results file at `path` (a CSV's header, a .npy's
/// sidecar). @throws UsageError as read_columns().
std::vector<std::string> result_column_names(const std::string& path);

/// The header of the CSV at `path` (its column names) and whether a data row
/// follows, read within the same bounds (for `mbfe plot`, whose rows gnuplot
/// reads). @throws UsageError as read_columns().
std::vector<std::string> read_csv_header(const std::string& path, bool& has_rows);

}  // namespace mbfe::tool
