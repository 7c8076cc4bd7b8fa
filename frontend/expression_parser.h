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

/// Nesting deeper than this is refused: the parser recurses once per
/// parenthesis, function call, unary sign and `^`, and a hostile file must not
/// exhaust its stack.
constexpr int kMaxExpressionDepth = 200;

/// The tree the parser builds may be at most this deep. A chain of binary
/// operators nests without parentheses (`t+t+t` is ((t+t)+t), 3 deep), so
/// this bounds sums and products of many terms. Nothing of ours recurses over
/// the tree (ir/expression.h), but GiNaC and the C++ compiler meet it.
constexpr int kMaxExpressionTreeDepth = 1000;

/// Numbers, names and operators in one expression: bounds the memory, the
/// generator's time and the code it emits.
constexpr int kMaxExpressionNodes = 10000;

/// Parses `text`, whose first character sits at `loc` in `file`; `what` names
/// the value in messages ("load #1: value"); `variable` is the name the text
/// uses for its variable: "t" (time) or "s" (position along a beam, for a
/// profile), held as Kind::kTime in the tree. Parts that do not depend on it
/// are evaluated: one that is not finite or undefined (1/0, 0/0, log(0),
/// sqrt(-1), 0^0, exp(1000)) is an error at its operator.
/// @throws ir::ModelError.
ir::Expression parse_expression(const std::string& text, const std::string& file, ir::SourceLoc loc,
                                const std::string& what, const std::string& variable = "t");

}  // namespace mbfe::frontend
