// The front end on closed loops (`constraints:`), planar and spatial: ends by
// named point or coordinates, the ground as an end, the axis, and the
// refusals with their file:line:col.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "frontend/parse_model.h"
#include "tests/support/model_error.h"

namespace mbfe::frontend {
using namespace mbfe::ir;
namespace {

constexpr double kUlpTol = 1e-15;  // an axis divided by its length

std::string error_of(const std::string& text) { return test::model_error_of(text); }

constexpr const char* kFourBar = R"(model: four_bar
bodies:
  - {name: crank, parent: ground, joint: {type: revolute}, mass: 1, inertia: 0.1, points: {end: [0.3, 0]}}
  - {name: coupler, parent: crank, joint: {type: revolute, at: [0.3, 0]}, mass: 1, inertia: 0.1, points: {end: [1, 0]}}
  - {name: rocker, parent: ground, joint: {type: revolute, at: [1, 0]}, mass: 1, inertia: 0.1, points: {end: [0.8, 0]}}
constraints:
  - {name: loop, type: point, a: {body: coupler, point: end}, b: {body: rocker, point: end}}
  - {name: track, type: prismatic, a: {body: ground, at: [0, 2]}, b: {body: rocker, at: [0.4, 0.1]}, axis: [3, 4]}
)";

TEST(ParseConstraints, PlanarLoopsByPointAndByCoordinates) {
  const Model m = parse_model_text(kFourBar, "four_bar.yaml");
  ASSERT_EQ(m.constraints.size(), 2u);
  const LoopConstraint& loop = m.constraints[0];
  EXPECT_EQ(loop.name, "loop");
  EXPECT_EQ(loop.type, LoopType::kPoint);
  EXPECT_EQ(loop.a.body, 1);
  EXPECT_EQ(loop.a.point, 0);
  EXPECT_EQ(loop.a.at, (Vec3{1.0, 0.0, 0.0}));
  EXPECT_EQ(loop.b.body, 2);
  EXPECT_EQ(loop.b.at, (Vec3{0.8, 0.0, 0.0}));
  EXPECT_EQ(loop_rows(loop.type, m.dimension), 2);
  const LoopConstraint& track = m.constraints[1];
  EXPECT_EQ(track.type, LoopType::kPrismatic);
  EXPECT_EQ(track.a.body, -1);  // the ground
  EXPECT_EQ(track.a.point, -1);
  EXPECT_EQ(track.a.at, (Vec3{0.0, 2.0, 0.0}));
  EXPECT_EQ(track.b.at, (Vec3{0.4, 0.1, 0.0}));
  EXPECT_NEAR(track.axis[0], 0.6, kUlpTol);
  EXPECT_NEAR(track.axis[1], 0.8, kUlpTol);
  EXPECT_EQ(track.axis[2], 0.0);
}

TEST(ParseConstraints, SpatialLoopsAndTheirRows) {
  const Model m = parse_model_text(R"(model: m
dimension: 3
bodies:
  - {name: a, parent: ground, joint: {type: revolute, axis: [0, 0, 1]}, mass: 1, inertia: [1, 1, 1, 0, 0, 0], points: {p: [1, 2, 3]}}
  - {name: b, parent: ground, joint: {type: spherical}, mass: 1, inertia: [1, 1, 1, 0, 0, 0]}
constraints:
  - {name: hinge, type: revolute, a: {body: a, point: p}, b: {body: b, at: [0, 0, 1]}, axis: [0, 2, 0]}
  - {name: ball, type: point, a: {body: a, at: [0, 0, 0]}, b: {body: ground, at: [1, 1, 1]}}
)",
                                   "m.yaml");
  ASSERT_EQ(m.constraints.size(), 2u);
  EXPECT_EQ(m.constraints[0].a.at, (Vec3{1.0, 2.0, 3.0}));
  EXPECT_EQ(m.constraints[0].axis, (Vec3{0.0, 1.0, 0.0}));
  EXPECT_EQ(loop_rows(m.constraints[0].type, 3), 5);
  EXPECT_EQ(loop_rows(m.constraints[1].type, 3), 3);
  EXPECT_EQ(loop_rows(LoopType::kPrismatic, 3), 5);
  EXPECT_EQ(loop_rows(LoopType::kPrismatic, 2), 2);
}

std::string with_loop(const std::string& loop) {
  return std::string(R"(model: m
bodies:
  - {name: a, parent: ground, joint: {type: revolute}, mass: 1, inertia: 0.1, points: {p: [1, 0]}}
  - {name: b, parent: a, joint: {type: revolute, at: [1, 0]}, mass: 1, inertia: 0.1}
constraints:
)") + loop;
}

TEST(ParseConstraints, Refusals) {
  EXPECT_EQ(error_of(with_loop("  - {name: c, type: point, a: {body: a, point: p}, b: {body: a, at: [0, 0]}}\n")),
            "models/x.yaml:6:55: constraint 'c': a constraint joins two different bodies (both ends are on body 'a')");
  EXPECT_EQ(error_of(with_loop("  - {name: c, type: point, a: {body: ground, point: p}, b: {body: a, at: [0, 0]}}\n")),
            "models/x.yaml:6:46: constraint 'c': the ground has no named points: give a.at, coordinates in the "
            "ground frame");
  EXPECT_EQ(error_of(with_loop("  - {name: c, type: point, a: {body: a, point: p, at: [0, 0]}, b: {body: b, at: [0, 0]}}\n")),
            "models/x.yaml:6:51: constraint 'c': give a.point (a named point) or a.at (coordinates in the body "
            "frame), not both");
  EXPECT_EQ(error_of(with_loop("  - {name: c, type: point, a: {body: a}, b: {body: b, at: [0, 0]}}\n")),
            "models/x.yaml:6:31: constraint 'c': missing required key 'a.point' (a named point of the body) or "
            "'a.at' (coordinates in its frame)");
  EXPECT_EQ(error_of(with_loop("  - {name: c, type: point, a: {body: a, point: q}, b: {body: b, at: [0, 0]}}\n")),
            "models/x.yaml:6:48: constraint 'c': body 'a' has no point 'q'");
  EXPECT_EQ(error_of(with_loop("  - {name: c, type: revolute, a: {body: a, point: p}, b: {body: b, at: [0, 0]}, axis: [0, 1]}\n")),
            "models/x.yaml:6:81: constraint 'c': 'axis' is not allowed for a planar revolute constraint (it turns "
            "about z)");
  EXPECT_EQ(error_of(with_loop("  - {name: c, type: prismatic, a: {body: a, point: p}, b: {body: b, at: [0, 0]}, axis: [0, 0]}\n")),
            "models/x.yaml:6:88: constraint 'c': axis must be a non-zero, finite direction");
  EXPECT_EQ(error_of(with_loop("  - {name: c, type: point, a: {body: a, point: p}, b: {body: b, at: [0, 0]}}\n"
                               "  - {name: c, type: point, a: {body: a, point: p}, b: {body: b, at: [0, 0]}}\n")),
            "models/x.yaml:7:12: constraint 'c': duplicate constraint name (first used at line 6)");
  EXPECT_EQ(error_of(with_loop("  - {name: c, type: hinge, a: {body: a, point: p}, b: {body: b, at: [0, 0]}}\n")),
            "models/x.yaml:6:21: constraint 'c': type: expected one of point, revolute, prismatic, got 'hinge'");
}

}  // namespace
}  // namespace mbfe::frontend
