// Columns of a results CSV (what `mbfe simulate --out FILE.csv` writes), read
// by name for `mbfe stats`.
#pragma once

#include <string>
#include <vector>

namespace mbfe::tool {

/// The columns `names` of the CSV at `path`, as numbers, one vector per name.
/// @throws UsageError (cli_args.h) naming the file, the line and the column
///         for a missing file or column, or a field that is not a number.
std::vector<std::vector<double>> read_columns(const std::string& path, const std::vector<std::string>& names);

}  // namespace mbfe::tool
