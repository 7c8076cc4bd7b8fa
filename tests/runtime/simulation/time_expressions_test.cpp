// check_time_expressions on beam loads, at the times the header promises:
// a windowed point load where its window opens (the later of t0 and start),
// a moving load where it enters the beam, nothing first used after t_end; an
// expression 1/(t - a) is infinite exactly at a, so each case is a use time
// put on or next to a.
#include <gtest/gtest.h>

#include <string>

#include "frontend/expression_parser.h"
#include "ir/model.h"
#include "ir/model_error.h"
#include "runtime/simulation/time_expressions.h"

namespace mbfe::runtime {
namespace {

ir::Expression expr(const std::string& text) {
  return frontend::parse_expression(text, "loads.yaml", {3, 12}, "load #1: value");
}

ir::Model beam_with(const ir::Beam& b) {
  ir::Model m;
  m.source_path = "loads.yaml";
  m.beams = {b};
  return m;
}

ir::Beam plain_beam() {
  ir::Beam b;
  b.name = "deck";
  b.length = 10.0;
  b.elements = 10;
  return b;
}

ir::Model windowed_load(const std::string& value, double start, double stop) {
  ir::Beam b = plain_beam();
  ir::BeamPointLoad load;
  load.at = 5.0;
  load.value = expr(value);
  load.window = {start, stop};
  b.loads = {load};
  return beam_with(b);
}

ir::Model moving_load(const std::string& value, double start, double speed) {
  ir::Beam b = plain_beam();
  ir::BeamMovingLoad load;
  load.value = expr(value);
  load.start = start;
  load.speed = speed;
  b.moving_loads = {load};
  return beam_with(b);
}

TEST(TimeExpressions, WindowedLoadIsCheckedWhereItsWindowOpens) {
  // Infinite at t = 0.2, where the window opens: refused, at the operator.
  try {
    check_time_expressions(windowed_load("1/(t - 0.2)", 0.2, 0.5), nullptr, 0.0, 1.0);
    FAIL() << "a load infinite where it is first used was accepted";
  } catch (const ir::ModelError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("t = 0.2 s"), std::string::npos) << what;
    EXPECT_NE(what.find("division by zero"), std::string::npos) << what;
  }
  // Opening at 0.3 it is finite there (it never meets t = 0.2).
  EXPECT_NO_THROW(check_time_expressions(windowed_load("1/(t - 0.2)", 0.3, 0.5), nullptr, 0.0, 1.0));
  // Always on: checked at t0.
  EXPECT_THROW(check_time_expressions(windowed_load("1/t", -1.0, 0.5), nullptr, 0.0, 1.0), ir::ModelError);
  EXPECT_NO_THROW(check_time_expressions(windowed_load("1/t", -1.0, 0.5), nullptr, 0.1, 1.0));
  // First used after t_end: not checked.
  EXPECT_NO_THROW(check_time_expressions(windowed_load("1/(t - 2)", 2.0, 3.0), nullptr, 0.0, 1.0));
}

TEST(TimeExpressions, MovingLoadIsCheckedWhereItEntersTheBeam) {
  // From s = -1 m at 2 m/s it enters at t = 0.5 s.
  EXPECT_THROW(check_time_expressions(moving_load("1/(t - 0.5)", -1.0, 2.0), nullptr, 0.0, 1.0), ir::ModelError);
  EXPECT_NO_THROW(check_time_expressions(moving_load("1/(t - 0.4)", -1.0, 2.0), nullptr, 0.0, 1.0));
  // On the beam from the start: checked at t0.
  EXPECT_THROW(check_time_expressions(moving_load("1/t", 3.0, 2.0), nullptr, 0.0, 1.0), ir::ModelError);
  // Entering after t_end: not checked.
  EXPECT_NO_THROW(check_time_expressions(moving_load("1/(t - 0.5)", -1.0, 2.0), nullptr, 0.0, 0.4));
}

}  // namespace
}  // namespace mbfe::runtime
