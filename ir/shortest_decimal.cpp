#include "ir/shortest_decimal.h"

#include <cstdio>
#include <cstdlib>

namespace mbfe::ir {

int shortest_significant_digits(double value) {
  char text[40];
  for (int digits = 1; digits < 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*e", digits - 1, value);
    if (std::strtod(text, nullptr) == value) return digits;
  }
  return 17;  // always enough for a double
}

}  // namespace mbfe::ir
