// How mbfe writes numbers into CSV rows: each in the shortest text that reads
// back as the same double (std::to_chars: "0.1", "1e-05", "-2.5"), comma
// separated, a row formatted in one buffer. `mbfe simulate`, `mbfe sweep` and
// programs that want the same files use it.
#pragma once

#include <cstddef>
#include <string>

namespace mbfe {

/// Replaces `line` with the values, comma separated, and a newline.
void format_csv_row(const double* values, std::size_t count, std::string& line);

}  // namespace mbfe
