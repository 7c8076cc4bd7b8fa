#include "api/csv_format.h"

#include <charconv>

namespace mbfe {

namespace {
// The longest shortest-round-trip text of a double ("-2.2250738585072014e-308": 24) and a comma.
constexpr std::size_t kMaxNumberChars = 26;
}  // namespace

void format_csv_row(const double* values, std::size_t count, std::string& line) {
  line.resize(count * kMaxNumberChars + 1);
  char* p = line.data();
  char* const end = p + line.size();
  for (std::size_t i = 0; i < count; ++i) {
    if (i) *p++ = ',';
    p = std::to_chars(p, end, values[i]).ptr;
  }
  *p++ = '\n';
  line.resize(static_cast<std::size_t>(p - line.data()));
}

}  // namespace mbfe
