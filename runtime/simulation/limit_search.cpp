#include "runtime/simulation/limit_search.h"

#include <algorithm>
#include <cmath>

namespace mbfe::runtime {

double readable_limit(double x) {
  if (!(x > 0.0) || !std::isfinite(x)) return x;
  const double unit = std::pow(10.0, std::floor(std::log10(x)) - 3.0);
  return std::ceil(x / unit) * unit;
}

double lowest_limit_within(const std::function<double(double)>& change, double tolerance, double top, double bottom,
                           const LimitSearchResolution& resolution) {
  const int count = std::max(2, static_cast<int>(std::ceil(resolution.per_decade * std::log10(top / bottom))));
  const double ratio = std::pow(top / bottom, 1.0 / count);
  double pass = top, fail = 0.0;
  for (int k = 1; k <= count; ++k) {
    const double omega = top / std::pow(ratio, k);
    if (change(omega) > tolerance) {
      fail = omega;
      break;
    }
    pass = omega;
  }
  if (fail == 0.0) return readable_limit(pass);  // every limit down to the grid's bottom meets it
  for (int k = 0; k < resolution.bisections; ++k) {
    const double mid = std::sqrt(pass * fail);
    (change(mid) > tolerance ? fail : pass) = mid;
  }
  // The bisection ends just above a mode's fastest root, where the change
  // jumps: the limit a user reads and copies must be on the passing side.
  const double shown = readable_limit(pass);
  return change(shown) <= tolerance ? shown : pass;
}

}  // namespace mbfe::runtime
