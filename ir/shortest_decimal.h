// How many significant decimal digits a double needs to read back exactly: the
// one rule behind every number mbfe prints (generated constants, their exact
// rationals, expression texts).
#pragma once

namespace mbfe::ir {

/// The fewest significant digits p (1..17) such that printing `value` with p
/// significant digits and reading it back gives `value`. For a finite value.
int shortest_significant_digits(double value);

}  // namespace mbfe::ir
