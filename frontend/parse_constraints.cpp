// ModelParser: closed kinematic loops (`constraints:`), planar and spatial.
#include <cmath>

#include "frontend/model_parser.h"

namespace mbfe::frontend {

void ModelParser::parse_constraints(const MapView& top, const Field& field) {
  const auto items = top.list(field);
  std::unordered_map<std::string, SourceLoc> names;
  const bool spatial = model_.dimension == 3;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const MapView view(file_, items[i], item_context(items[i], "constraint", i, limits_.max_name_length), "",
                       field.value_loc);
    view.allow({"name", "type", "a", "b", "axis"});
    LoopConstraint loop;
    loop.loc = view.loc();
    const Field& name = view.require("name");
    loop.name = view.identifier(name, limits_.max_name_length);
    const auto [it, inserted] = names.emplace(loop.name, name.value_loc);
    if (!inserted) {
      view.fail(name.value_loc, view.prefixed("duplicate constraint name (first used at line " +
                                              std::to_string(it->second.line) + ")"));
    }
    loop.type = static_cast<LoopType>(view.choice(view.require("type"), {"point", "revolute", "prismatic"}));
    loop.a = parse_loop_end(view, view.require("a"));
    const Field& b = view.require("b");
    loop.b = parse_loop_end(view, b);
    if (loop.a.body == loop.b.body) {
      view.fail(b.value_loc, view.prefixed("a constraint joins two different bodies (both ends are on " +
                                           (loop.a.body < 0 ? std::string("the ground")
                                                            : "body " + quoted(model_.bodies[loop.a.body].name)) +
                                           ")"));
    }
    // The axis: in space for revolute and prismatic, in the plane for
    // prismatic only (a planar revolute turns about z).
    const bool takes_axis = loop.type == LoopType::kPrismatic || (spatial && loop.type == LoopType::kRevolute);
    const Field* axis = view.find("axis");
    if (takes_axis) {
      loop.axis = unit_direction(view, view.require("axis"));
    } else if (axis) {
      view.fail(axis->key_loc,
                view.prefixed(loop.type == LoopType::kPoint
                                  ? "'axis' is not allowed for a point constraint (it holds every rotation free)"
                                  : "'axis' is not allowed for a planar revolute constraint (it turns about z)"));
    }
    model_.constraints.push_back(loop);
  }
}

LoopEnd ModelParser::parse_loop_end(const MapView& loop_view, const Field& field) const {
  const MapView view = loop_view.sub(field);
  view.allow({"body", "point", "at"});
  LoopEnd end;
  const Field& body = view.require("body");
  const std::string body_name = view.identifier(body, limits_.max_name_length);
  end.body = body_name == kGround ? -1 : existing_body(view, body);
  const Field* point = view.find("point");
  const Field* at = view.find("at");
  if (point && at) {
    view.fail(at->key_loc, view.prefixed("give " + view.what(*point) + " (a named point) or " + view.what(*at) +
                                         " (coordinates in the body frame), not both"));
  }
  if (point) {
    if (end.body < 0) {
      view.fail(point->key_loc, view.prefixed("the ground has no named points: give " + field.key +
                                              ".at, coordinates in the ground frame"));
    }
    end.point = existing_point(view, *point, end.body);
    const NamedPoint& named = model_.bodies[end.body].points[end.point];
    end.at = model_.dimension == 3 ? named.position3 : Vec3{named.position[0], named.position[1], 0.0};
    return end;
  }
  if (!at) {
    view.fail(view.loc(), view.prefixed("missing required key '" + field.key + ".point' (a named point of the "
                                        "body) or '" + field.key + ".at' (coordinates in its frame)"));
  }
  if (model_.dimension == 3) {
    end.at = view.vec3(*at);
  } else {
    const Vec2 planar = view.vec2(*at);
    end.at = {planar[0], planar[1], 0.0};
  }
  return end;
}

}  // namespace mbfe::frontend
