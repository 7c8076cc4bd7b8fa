#include "frontend/expression_parser.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <iterator>
#include <string_view>
#include <vector>

#include "ir/model_error.h"
#include "frontend/yaml_reader.h"

namespace mbfe::frontend {
namespace {

using ir::Expression;

constexpr double kPi = 3.14159265358979323846;

std::string allowed_names(const std::string& variable) {
  std::string names = variable + ", pi";
  for (const auto& f : ir::kExpressionFunctions) names += std::string(", ") + f.name;
  return names;
}

class ExpressionParser {
 public:
  ExpressionParser(const std::string& text, const std::string& file, ir::SourceLoc loc,
                   const std::string& what, const std::string& variable)
      : text_(text), file_(file), loc_(loc), what_(what), variable_(variable) {}

  Expression parse() {
    skip_space();
    if (pos_ == text_.size()) fail(pos_, "is empty; expected an expression in " + variable_);
    sum(0);
    skip_space();
    if (pos_ != text_.size()) fail(pos_, "unexpected '" + shown(std::string(1, text_[pos_])) + "'");
    Expression e(std::move(nodes_), ir::ExpressionSource{file_, what_, shown(text_), loc_, variable_});
    // A part that does not depend on the variable is a number: one that is not finite
    // (1/0, log(0), exp(1000)) or undefined (0^0) is an error here, where it
    // is written, not a GiNaC exception in the generator or a NaN in a run.
    if (const auto fault = e.constant_fault()) {
      const ir::SourceLoc where = e.nodes()[fault->node].loc;
      throw ir::ModelError(file_, where,
                           what_ + ": " + fault->reason + "; expected a finite value in expression \"" +
                               shown(text_) + "\"");
    }
    return e;
  }

 private:
  [[noreturn]] void fail(std::size_t at, const std::string& message) const {
    throw ir::ModelError(file_, here(at), what_ + ": " + message + " in expression \"" + shown(text_) + "\"");
  }

  ir::SourceLoc here(std::size_t at) const {
    ir::SourceLoc where = loc_;
    if (where.line > 0) where.column += static_cast<int>(at);
    return where;
  }

  void skip_space() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t')) ++pos_;
  }

  bool accept(char c) {
    skip_space();
    if (pos_ < text_.size() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }

  void enter(int depth) const {
    if (depth > kMaxExpressionDepth)
      fail(pos_, "nested more than " + std::to_string(kMaxExpressionDepth) + " deep");
  }

  /// Appends a node written at `at` whose arguments, the last subtrees
  /// appended, are at most `deepest` deep; returns the depth of its tree.
  int push(Expression::Kind kind, std::size_t at, int deepest, double value = 0.0,
           ir::Function function = ir::Function::kSin) {
    if (nodes_.size() >= static_cast<std::size_t>(kMaxExpressionNodes))
      fail(at, "more than " + std::to_string(kMaxExpressionNodes) +
                   " numbers, names and operators (the limit, kMaxExpressionNodes)");
    if (deepest + 1 > kMaxExpressionTreeDepth)
      fail(at, "a tree deeper than " + std::to_string(kMaxExpressionTreeDepth) +
                   " (the limit, kMaxExpressionTreeDepth; a sum or product of n terms is n deep)");
    ir::ExpressionNode n;
    n.kind = kind;
    n.value = value;
    n.function = function;
    n.loc = here(at);
    nodes_.push_back(n);
    return deepest + 1;
  }

  int sum(int depth) {
    enter(depth);
    int tree = product(depth + 1);
    for (;;) {
      skip_space();
      const std::size_t at = pos_;
      Expression::Kind kind;
      if (accept('+')) kind = Expression::Kind::kAdd;
      else if (accept('-')) kind = Expression::Kind::kSubtract;
      else return tree;
      const int right = product(depth + 1);
      tree = push(kind, at, std::max(tree, right));
    }
  }

  int product(int depth) {
    enter(depth);
    int tree = unary(depth + 1);
    for (;;) {
      skip_space();
      const std::size_t at = pos_;
      Expression::Kind kind;
      if (accept('*')) kind = Expression::Kind::kMultiply;
      else if (accept('/')) kind = Expression::Kind::kDivide;
      else return tree;
      const int right = unary(depth + 1);
      tree = push(kind, at, std::max(tree, right));
    }
  }

  int unary(int depth) {
    enter(depth);
    skip_space();
    const std::size_t at = pos_;
    if (accept('-')) return push(Expression::Kind::kNegate, at, unary(depth + 1));
    if (accept('+')) return unary(depth + 1);
    const int base = primary(depth + 1);
    skip_space();
    const std::size_t op = pos_;
    if (accept('^')) {
      const int exponent = unary(depth + 1);
      return push(Expression::Kind::kPower, op, std::max(base, exponent));
    }
    return base;
  }

  int primary(int depth) {
    enter(depth);
    skip_space();
    if (pos_ == text_.size()) fail(pos_, "ends where a number, " + variable_ + ", a function or '(' was expected");
    const std::size_t at = pos_;
    const char c = text_[pos_];
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number();
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      while (pos_ < text_.size() &&
             (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_'))
        ++pos_;
      const std::string name = text_.substr(at, pos_ - at);
      if (name == variable_) return push(Expression::Kind::kTime, at, 0);
      if (name == "pi") return push(Expression::Kind::kNumber, at, 0, kPi);
      for (std::size_t f = 0; f < std::size(ir::kExpressionFunctions); ++f) {
        const ir::ExpressionFunction& function = ir::kExpressionFunctions[f];
        if (name != function.name) continue;
        if (!accept('(')) fail(pos_, "expected '(' after " + name);
        int deepest = sum(depth + 1);
        int count = 1;
        while (accept(',')) {
          deepest = std::max(deepest, sum(depth + 1));
          ++count;
        }
        if (!accept(')')) fail(pos_, "expected ')' or ',' in the arguments of " + name);
        if (count != function.arity)
          fail(at, name + " takes " + std::to_string(function.arity) + " argument" +
                       (function.arity == 1 ? "" : "s") + ", got " + std::to_string(count));
        return push(Expression::Kind::kCall, at, deepest, 0.0, static_cast<ir::Function>(f));
      }
      fail(at, "unknown name '" + shown(name) + "' (allowed: " + allowed_names(variable_) + ")");
    }
    if (accept('(')) {
      const int tree = sum(depth + 1);
      if (!accept(')')) fail(pos_, "expected ')'");
      return tree;
    }
    fail(at, "unexpected '" + shown(std::string(1, c)) + "'");
  }

  int number() {
    const std::size_t at = pos_;
    while (pos_ < text_.size() && (std::isdigit(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '.')) ++pos_;
    if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
      std::size_t p = pos_ + 1;
      if (p < text_.size() && (text_[p] == '+' || text_[p] == '-')) ++p;
      if (p < text_.size() && std::isdigit(static_cast<unsigned char>(text_[p]))) {
        pos_ = p;
        while (pos_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_]))) ++pos_;
      }
    }
    const std::string digits = text_.substr(at, pos_ - at);
    // from_chars: the same in every locale, unlike strtod.
    double v = 0.0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
    if (error != std::errc() || end != digits.data() + digits.size() || !std::isfinite(v))
      fail(at, "bad number '" + shown(digits) + "'");
    return push(Expression::Kind::kNumber, at, 0, v);
  }

  const std::string& text_;
  const std::string& file_;
  ir::SourceLoc loc_;
  const std::string& what_;
  const std::string& variable_;
  std::size_t pos_ = 0;
  std::vector<ir::ExpressionNode> nodes_;  // postfix, as built
};

}  // namespace

ir::Expression parse_expression(const std::string& text, const std::string& file, ir::SourceLoc loc,
                                const std::string& what, const std::string& variable) {
  return ExpressionParser(text, file, loc, what, variable).parse();
}

}  // namespace mbfe::frontend
