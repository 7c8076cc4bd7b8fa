// The text of an expression in t (a load value, a joint motion) into an
// ir::Expression, with a `file:line:col` error at the first character that
// does not fit the grammar (docs/model-format.md, "Expressions"):
//
//   sum     := product (('+' | '-') product)*
//   product := unary (('*' | '/') unary)*
//   unary   := ('-' | '+') unary | power
//   power   := primary ('^' unary)?          right-associative
//   primary := number | 't' | 'pi' | name '(' sum (',' sum)* ')' | '(' sum ')'
#pragma once

#include <string>

#include "ir/expression.h"
#include "ir/source_loc.h"

namespace mbfe::frontend {

/// Nesting deeper than this is refused (a hostile file cannot exhaust the stack).
constexpr int kMaxExpressionDepth = 200;

/// Parses `text`, whose first character sits at `loc` in `file`; `what` names
/// the value in messages ("loads[0].value"). @throws ir::ModelError.
ir::Expression parse_expression(const std::string& text, const std::string& file, ir::SourceLoc loc,
                                const std::string& what);

}  // namespace mbfe::frontend
