#pragma once

#include <functional>

namespace mbfe::runtime {

/// How finely `lowest_limit_within` searches: grid points a decade, then
/// bisections between the last passing and the first failing one. Each
/// probe costs one estimate, so a costly estimate takes a coarser search.
struct LimitSearchResolution {
  int per_decade = 40;
  int bisections = 40;
};

/// `x` (> 0) rounded up to four significant digits (459.41... -> 459.5), as
/// chosen limits are printed and checked.
double readable_limit(double x);

/// The lowest omega_limit (rad/s) whose `change(omega_limit)` stays within
/// `tolerance`: a log grid down from `top` to `bottom`, stopping at the first
/// grid point that fails (the change need not fall monotonically with the
/// limit: every limit returned has every higher grid point passing too), then
/// bisection towards it. The result is rounded by readable_limit when the
/// rounded limit still passes (it is what a user reads and copies), else
/// left as found. Returns `top` when `change(top)` fails; the caller checks
/// that case first, as it has the better message.
double lowest_limit_within(const std::function<double(double)>& change, double tolerance, double top, double bottom,
                           const LimitSearchResolution& resolution);

}  // namespace mbfe::runtime
