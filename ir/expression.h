// A closed-form expression in time t: the value of a load that varies with
// time, or the motion of a driven joint.
//
// The front end parses the model file's text into this tree
// (frontend/expression_parser.h); the generator turns the tree into GiNaC and
// prints C++ from it, the runtime evaluates it directly. The text itself never
// reaches generated code.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "ir/source_loc.h"

namespace mbfe::ir {

/// One node of an expression tree.
struct Expression {
  enum class Kind {
    kNumber,  // `value`
    kTime,    // t
    kNegate,  // -args[0]
    kAdd, kSubtract, kMultiply, kDivide, kPower,  // args[0] op args[1]
    kCall,    // function(args...), one of kFunctions
  };
  Kind kind = Kind::kNumber;
  double value = 0.0;
  std::string function;  // kCall only
  std::vector<Expression> args;
  SourceLoc loc;

  static Expression number(double v);

  /// The value at time t (IEEE arithmetic: may be inf or NaN).
  double evaluate(double t) const;
  /// True when t does not occur.
  bool is_constant() const;
};

/// The functions an expression may call, with their argument counts.
struct ExpressionFunction {
  const char* name;
  int arity;
};
inline constexpr ExpressionFunction kExpressionFunctions[] = {
    {"sin", 1}, {"cos", 1}, {"tan", 1}, {"exp", 1}, {"log", 1}, {"sqrt", 1},
    {"abs", 1}, {"min", 2}, {"max", 2}, {"step", 1}};

/// step(x): 0 for x < 0, 1 for x >= 0 (so step(t - a) switches on at t = a).
double unit_step(double x);

/// When a load acts: start <= t < stop (seconds).
struct TimeWindow {
  double start = -std::numeric_limits<double>::infinity();
  double stop = std::numeric_limits<double>::infinity();
  bool contains(double t) const { return t >= start && t < stop; }
  bool always() const { return start == -std::numeric_limits<double>::infinity() &&
                               stop == std::numeric_limits<double>::infinity(); }
};

}  // namespace mbfe::ir
