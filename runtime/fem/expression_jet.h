// The value of an expression and its first and second derivatives with
// respect to its variable, by forward-mode differentiation over the postfix
// array (no recursion, no symbolic algebra in the runtime): what a contact
// riding on a running surface given as an expression in s needs, r(s), r'(s)
// and r''(s) (docs/profiles.md).
#pragma once

#include "ir/expression.h"

namespace mbfe::runtime {

/// f, df/dx and d2f/dx2 at one point.
struct Jet {
  double value = 0.0;
  double d1 = 0.0;
  double d2 = 0.0;
};

/// The jet of `e` at x (its variable, Kind::kTime, set to x). IEEE arithmetic:
/// may be inf or NaN where `e` or a derivative is (sqrt at 0, log at 0).
/// min, max and abs take the derivatives of the branch they pick, step has
/// none: where they switch the derivatives jump.
Jet evaluate_jet(const ir::Expression& e, double x);

}  // namespace mbfe::runtime
