// ModelParser: bodies, their joints and points, and the loads on bodies.
#include "frontend/model_parser.h"

#include <cmath>

namespace mbfe::frontend {

void ModelParser::parse_bodies(const MapView& top, const Field& field) {
  const auto items = bounded_list(top, field, limits_.max_bodies, "max_bodies");
  const bool spatial = model_.dimension == 3;
  // Why a spatial model has limits of its own, in every message about them.
  const std::string spatial_reason =
      " of a spatial model: its generated solver would take too long to compile (docs/performance.md, \"Model size "
      "and compile time\")";
  if (spatial && static_cast<long>(items.size()) > limits_.max_spatial_bodies)
    top.fail(field.value_loc, field.key + ": " + std::to_string(items.size()) + " entries, more than the limit of " +
                                  std::to_string(limits_.max_spatial_bodies) + " (ParseLimits::max_spatial_bodies)" +
                                  spatial_reason);
  long total_points = 0, velocities = 0;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const MapView view(file_, items[i],
                       item_context(items[i], "body", i, limits_.max_name_length), "",
                       field.value_loc);
    model_.bodies.push_back(parse_body(view));
    const Body& body = model_.bodies.back();
    velocities += velocity_count(body.joint.type);
    if (spatial && velocities > limits_.max_spatial_velocities)
      view.fail(body.loc, view.prefixed("the joints up to here have " + std::to_string(velocities) +
                                        " velocity coordinates (a free joint 6, a spherical one 3, the others 1), "
                                        "more than the limit of " + std::to_string(limits_.max_spatial_velocities) +
                                        " (ParseLimits::max_spatial_velocities)" + spatial_reason));
    total_points += static_cast<long>(body.points.size());
    if (total_points > limits_.max_points) {
      const NamedPoint& last = body.points.back();
      view.fail(last.loc, view.prefixed("point '" + last.name + "': the bodies hold " + std::to_string(total_points) +
                                        " named points up to here, more than the limit of " +
                                        std::to_string(limits_.max_points) + " (ParseLimits::max_points)"));
    }
    body_by_name_.emplace(body.name, static_cast<int>(i));
    auto& points = point_by_name_.emplace_back();
    for (std::size_t k = 0; k < body.points.size(); ++k) {
      points.emplace(body.points[k].name, static_cast<int>(k));
    }
  }
}

Body ModelParser::parse_body(const MapView& view) {
  view.allow({"name", "parent", "joint", "mass", "inertia", "com", "points"});
  Body body;
  body.loc = view.loc();
  const Field& name = view.require("name");
  body.name = view.identifier(name, limits_.max_name_length);
  claim_coordinate_name(view, name, body.name);

  const Field& parent = view.require("parent");
  body.parent = parent_index(view, parent, body.name);
  if (model_.dimension == 3) {
    parse_spatial_body(view, body);
    claim_joint_coordinate_names(view, name, body);
    return body;
  }
  body.joint = parse_joint(view.sub(view.require("joint")));
  body.mass = view.number_at_least(view.require("mass"), 0.0);
  body.inertia = view.number_at_least(view.require("inertia"), 0.0);
  body.com = view.vec2_or("com", {0.0, 0.0});
  if (const Field* points = view.find("points")) body.points = parse_points(view, *points);
  return body;
}

/// Parents come before their children, which also rules out cycles.
int ModelParser::parent_index(const MapView& view, const Field& field, const std::string& child) const {
  const std::string name = view.identifier(field, limits_.max_name_length);
  if (name == kGround) return -1;
  if (name == child) {
    view.fail(field.value_loc, view.prefixed("a body cannot be its own parent"));
  }
  const int index = body_index(name);
  if (index >= 0) return index;
  view.fail(
      field.value_loc,
      view.prefixed("unknown parent " + quoted(name) +
                    " (a parent must be listed before its children; the root is 'ground')"));
}

Joint ModelParser::parse_joint(const MapView& view) {
  view.allow({"type", "at", "axis", "motion"});
  Joint joint;
  joint.loc = view.loc();
  const Field& type = view.require("type");
  if (type.value.IsScalar() && (type.value.Scalar() == "spherical" || type.value.Scalar() == "free")) {
    view.fail(type.value_loc, view.prefixed("joint.type: a " + type.value.Scalar() +
                                            " joint exists in spatial models only (add 'dimension: 3' at the "
                                            "top of the file); a planar joint is revolute or prismatic"));
  }
  joint.type = view.choice(type, {"revolute", "prismatic"}) == 0 ? JointType::kRevolute : JointType::kPrismatic;
  joint.at = view.vec2_or("at", {0.0, 0.0});
  if (const Field* motion = view.find("motion")) {
    joint.motion = view.expression(*motion);
    joint.motion_loc = motion->value_loc;
  }
  const Field* axis = view.find("axis");
  if (joint.type == JointType::kRevolute) {
    if (axis) {
      view.fail(
          axis->key_loc,
          view.prefixed(
              "joint.axis applies to prismatic joints only (a revolute joint turns about z)"));
    }
    return joint;
  }
  const Field& axis_field = view.require("axis");
  const Vec2 direction = view.vec2(axis_field);
  const double norm = std::hypot(direction[0], direction[1]);
  if (!(norm > 0.0) || !std::isfinite(norm)) {
    view.fail(axis_field.value_loc,
              view.prefixed("joint.axis must be a non-zero, finite direction"));
  }
  joint.axis = {direction[0] / norm, direction[1] / norm};
  return joint;
}

std::vector<NamedPoint> ModelParser::parse_points(const MapView& body, const Field& field) {
  const MapView view = body.sub(field);
  std::vector<NamedPoint> points;
  for (const Field& entry : view.fields()) {
    const std::string problem = identifier_problem(entry.key, limits_.max_name_length);
    if (!problem.empty()) {
      view.fail(entry.key_loc, view.prefixed("point '" + shown(entry.key) + "' " + problem));
    }
    NamedPoint point{entry.key, {0.0, 0.0}, {0.0, 0.0, 0.0}, entry.key_loc};
    if (model_.dimension == 3) point.position3 = view.vec3(entry);
    else point.position = view.vec2(entry);
    points.push_back(point);
  }
  return points;
}

void ModelParser::parse_loads(const MapView& top, const Field& field) {
  const auto items = top.list(field);
  std::unordered_map<std::string, SourceLoc> names;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const MapView view(file_, items[i], item_context(items[i], "load", i, limits_.max_name_length), "",
                       field.value_loc);
    Load load = parse_load(view);
    load.name = optional_item_name(view, names);
    model_.loads.push_back(std::move(load));
  }
}

std::string ModelParser::optional_item_name(const MapView& view,
                                            std::unordered_map<std::string, SourceLoc>& names) const {
  const Field* name = view.find("name");
  if (!name) return "";
  const std::string text = view.identifier(*name, limits_.max_name_length);
  const auto [it, inserted] = names.emplace(text, name->value_loc);
  if (!inserted) {
    view.fail(name->value_loc, view.prefixed("duplicate load name (first used at line " +
                                             std::to_string(it->second.line) + ")"));
  }
  return text;
}

Load ModelParser::parse_load(const MapView& view) {
  Load load;
  load.loc = view.loc();
  const int type = view.choice(view.require("type"), {"force", "torque", "spring_damper"});
  if (type == 0) {
    view.allow({"name", "type", "body", "point", "value", "start", "stop"});
    load.type = LoadType::kForce;
    load.body = existing_body(view, view.require("body"));
    if (const Field* point = view.find("point")) {
      load.point = existing_point(view, *point, load.body);
    }
    if (model_.dimension == 3) parse_spatial_load_value(view, load);
    else load.force = view.expression_pair(view.require("value"));
    load.window = time_window(view);
  } else if (type == 1) {
    view.allow({"name", "type", "body", "value", "start", "stop"});
    load.type = LoadType::kTorque;
    load.body = existing_body(view, view.require("body"));
    if (model_.dimension == 3) parse_spatial_load_value(view, load);
    else load.torque = view.expression(view.require("value"));
    load.window = time_window(view);
  } else {
    view.allow({"name", "type", "joint", "stiffness", "damping", "rest", "start", "stop"});
    load.type = LoadType::kSpringDamper;
    const Field& joint = view.require("joint");
    load.body = existing_body(view, joint);
    const JointType joint_type = model_.bodies[load.body].joint.type;
    if (joint_type == JointType::kSpherical || joint_type == JointType::kFree) {
      view.fail(joint.value_loc,
                view.prefixed("a spring_damper acts on one joint coordinate; body " +
                              quoted(model_.bodies[load.body].name) + " has a " +
                              (joint_type == JointType::kSpherical ? "spherical" : "free") +
                              " joint (expected a revolute or prismatic one)"));
    }
    load.stiffness = at_least_or(view, "stiffness", 0.0);
    load.damping = at_least_or(view, "damping", 0.0);
    load.rest = view.number_or("rest", 0.0);
    load.window = time_window(view);
  }
  return load;
}

TimeWindow ModelParser::time_window(const MapView& view) {
  TimeWindow window;
  const Field* start = view.find("start");
  const Field* stop = view.find("stop");
  if (start) window.start = view.number(*start);
  if (stop) window.stop = view.number(*stop);
  if (start && stop && !(window.start < window.stop)) {
    view.fail(stop->value_loc, view.prefixed("stop must be after start (got start " +
                                             format_number(window.start) + " s, stop " +
                                             format_number(window.stop) + " s)"));
  }
  return window;
}

/// An optional number >= 0, 0 when absent.
double ModelParser::at_least_or(const MapView& view, const std::string& key, double minimum) {
  const Field* field = view.find(key);
  return field ? view.number_at_least(*field, minimum) : 0.0;
}

}  // namespace mbfe::frontend
