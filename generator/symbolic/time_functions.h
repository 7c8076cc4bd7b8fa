// Expressions in time (ir::Expression) as GiNaC expressions: load values and
// the motions of driven joints.
//
// step, abs, min and max have no GiNaC counterpart that differentiates and
// prints the way generated code needs, so they are GiNaC functions of our own
// (mbfe_step, mbfe_fabs, mbfe_fmin, mbfe_fmax, and mbfe_sign for the
// derivative of abs), each with its derivative, printed by CppPrinter.
// Derivatives at the kinks take one side (step' = 0, abs'(0) = 0): a driven
// joint's motion is differentiated twice and is expected to be smooth where
// it is used.
#pragma once

#include <ginac/ginac.h>

#include "ir/expression.h"

namespace mbfe::gen {

/// `e` as a GiNaC expression in the symbol `t`; numbers as exact decimal
/// rationals. Converted node by node without recursion. @throws ir::ModelError
/// at the node where GiNaC finds the expression undefined or not real for
/// every t (1/(t - t), log(t - t), sqrt(t - t - 1)); the parser has refused
/// such parts that are written as constants already.
GiNaC::ex to_ginac(const ir::Expression& e, const GiNaC::symbol& t);

/// 1 on [start, stop), 0 outside, as a product of steps (1 for an unbounded window).
GiNaC::ex window_factor(const ir::TimeWindow& window, const GiNaC::symbol& t);

/// The C++ text of a call of one of our functions on printed arguments, or
/// empty when `name` is not one of them.
std::string print_time_function(const std::string& name, const std::vector<std::string>& args);

}  // namespace mbfe::gen
