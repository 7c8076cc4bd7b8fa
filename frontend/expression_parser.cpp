#include "frontend/expression_parser.h"

#include <cctype>
#include <charconv>
#include <cmath>

#include <string_view>

#include "ir/model_error.h"
#include "frontend/yaml_reader.h"

namespace mbfe::frontend {
namespace {

using ir::Expression;

constexpr double kPi = 3.14159265358979323846;

std::string allowed_names() {
  std::string names = "t, pi";
  for (const auto& f : ir::kExpressionFunctions) names += std::string(", ") + f.name;
  return names;
}

class ExpressionParser {
 public:
  ExpressionParser(const std::string& text, const std::string& file, ir::SourceLoc loc,
                   const std::string& what)
      : text_(text), file_(file), loc_(loc), what_(what) {}

  Expression parse() {
    skip_space();
    if (pos_ == text_.size()) fail(pos_, "is empty; expected an expression in t");
    Expression e = sum(0);
    skip_space();
    if (pos_ != text_.size()) fail(pos_, "unexpected '" + shown(std::string(1, text_[pos_])) + "'");
    return e;
  }

 private:
  [[noreturn]] void fail(std::size_t at, const std::string& message) const {
    ir::SourceLoc where = loc_;
    if (where.line > 0) where.column += static_cast<int>(at);
    throw ir::ModelError(file_, where, what_ + ": " + message + " in expression \"" + shown(text_) + "\"");
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

  static Expression binary(Expression::Kind kind, Expression a, Expression b, ir::SourceLoc loc) {
    Expression e;
    e.kind = kind;
    e.loc = loc;
    e.args.push_back(std::move(a));
    e.args.push_back(std::move(b));
    return e;
  }

  Expression sum(int depth) {
    enter(depth);
    Expression e = product(depth + 1);
    for (;;) {
      skip_space();
      const std::size_t at = pos_;
      if (accept('+')) e = binary(Expression::Kind::kAdd, std::move(e), product(depth + 1), here(at));
      else if (accept('-')) e = binary(Expression::Kind::kSubtract, std::move(e), product(depth + 1), here(at));
      else return e;
    }
  }

  Expression product(int depth) {
    enter(depth);
    Expression e = unary(depth + 1);
    for (;;) {
      skip_space();
      const std::size_t at = pos_;
      if (accept('*')) e = binary(Expression::Kind::kMultiply, std::move(e), unary(depth + 1), here(at));
      else if (accept('/')) e = binary(Expression::Kind::kDivide, std::move(e), unary(depth + 1), here(at));
      else return e;
    }
  }

  Expression unary(int depth) {
    enter(depth);
    skip_space();
    const std::size_t at = pos_;
    if (accept('-')) {
      Expression e;
      e.kind = Expression::Kind::kNegate;
      e.loc = here(at);
      e.args.push_back(unary(depth + 1));
      return e;
    }
    if (accept('+')) return unary(depth + 1);
    Expression base = primary(depth + 1);
    skip_space();
    const std::size_t op = pos_;
    if (accept('^')) return binary(Expression::Kind::kPower, std::move(base), unary(depth + 1), here(op));
    return base;
  }

  Expression primary(int depth) {
    enter(depth);
    skip_space();
    if (pos_ == text_.size()) fail(pos_, "ends where a number, t, a function or '(' was expected");
    const std::size_t at = pos_;
    const char c = text_[pos_];
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number();
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      while (pos_ < text_.size() &&
             (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_'))
        ++pos_;
      const std::string name = text_.substr(at, pos_ - at);
      if (name == "t") {
        Expression e;
        e.kind = Expression::Kind::kTime;
        e.loc = here(at);
        return e;
      }
      if (name == "pi") {
        Expression e = Expression::number(kPi);
        e.loc = here(at);
        return e;
      }
      for (const auto& f : ir::kExpressionFunctions) {
        if (name != f.name) continue;
        if (!accept('(')) fail(pos_, "expected '(' after " + name);
        Expression e;
        e.kind = Expression::Kind::kCall;
        e.function = name;
        e.loc = here(at);
        e.args.push_back(sum(depth + 1));
        while (accept(',')) e.args.push_back(sum(depth + 1));
        if (!accept(')')) fail(pos_, "expected ')' or ',' in the arguments of " + name);
        if (static_cast<int>(e.args.size()) != f.arity)
          fail(at, name + " takes " + std::to_string(f.arity) + " argument" + (f.arity == 1 ? "" : "s") +
                       ", got " + std::to_string(e.args.size()));
        return e;
      }
      fail(at, "unknown name '" + shown(name) + "' (allowed: " + allowed_names() + ")");
    }
    if (accept('(')) {
      Expression e = sum(depth + 1);
      if (!accept(')')) fail(pos_, "expected ')'");
      return e;
    }
    fail(at, "unexpected '" + shown(std::string(1, c)) + "'");
  }

  Expression number() {
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
    Expression e = Expression::number(v);
    e.loc = here(at);
    return e;
  }

  const std::string& text_;
  const std::string& file_;
  ir::SourceLoc loc_;
  const std::string& what_;
  std::size_t pos_ = 0;
};

}  // namespace

ir::Expression parse_expression(const std::string& text, const std::string& file, ir::SourceLoc loc,
                                const std::string& what) {
  return ExpressionParser(text, file, loc, what).parse();
}

}  // namespace mbfe::frontend
