// ModelParser: the top level, names and cross references, the initial state
// and the simulation block.
#include "frontend/model_parser.h"

#include <cmath>

#include "ir/coordinate_layout.h"

namespace mbfe::frontend {

namespace {

/// Index of body `body`'s first entry of q, or of v when `velocities`.
int body_first(const CoordinateLayout& layout, int body, bool velocities) {
  return velocities ? layout.first_velocity[body] : layout.first_position[body];
}

}  // namespace

void ModelParser::parse(const YAML::Node& root) {
  const MapView top(file_, root, "", "", SourceLoc{1, 1});
  top.allow({"model", "description", "gravity", "dimension", "bodies", "loads", "beams", "contacts", "links",
             "constraints", "initial", "simulation",
             "train"});  // expanded and removed before (frontend/expand_train.h)
  const Field& name = top.require("model");
  model_.name = top.identifier(name, limits_.max_name_length);
  if (const Field* description = top.find("description")) top.text(*description);
  if (const Field* dimension = top.find("dimension")) model_.dimension = top.choice(*dimension, {"2", "3"}) + 2;
  if (model_.dimension == 3) {
    refuse_planar_only_sections(top);
    model_.gravity3 = top.vec3_or("gravity", {0.0, 0.0, 0.0});
  } else {
    model_.gravity = top.vec2_or("gravity", {0.0, 0.0});
  }
  if (const Field* bodies = top.find("bodies")) parse_bodies(top, *bodies);
  if (const Field* beams = top.find("beams")) parse_beams(top, *beams);
  if (model_.bodies.empty() && model_.beams.empty()) {
    top.fail(name.value_loc, "model " + quoted(model_.name) + " has no bodies" +
                                 (model_.dimension == 3 ? "" : " and no beams"));
  }
  if (const Field* loads = top.find("loads")) parse_loads(top, *loads);
  check_expression_budget(top);
  if (const Field* contacts = top.find("contacts")) parse_contacts(top, *contacts);
  if (const Field* links = top.find("links")) parse_links(top, *links);
  if (const Field* constraints = top.find("constraints")) {
    // The coupled run (beams) integrates the tree and closes contacts; it
    // has no loop closure, so it would run the linkage open.
    if (!model_.beams.empty())
      top.fail(constraints->key_loc,
               "constraints: a model with beams cannot have closed loops yet: its run would leave them open; "
               "remove the beams, or the constraints");
    parse_constraints(top, *constraints);
  }
  check_joined_adjustments(top);
  check_output_columns(top);
  // Missing coordinates are 0; a missing quaternion is the identity (1, 0, 0, 0).
  const CoordinateLayout layout = coordinate_layout(model_);
  model_.initial.q.assign(layout.num_positions, 0.0);
  model_.initial.qd.assign(layout.num_velocities, 0.0);
  for (std::size_t b = 0; b < model_.bodies.size(); ++b) {
    const JointType type = model_.bodies[b].joint.type;
    if (type == JointType::kSpherical) model_.initial.q[layout.first_position[b]] = 1.0;
    if (type == JointType::kFree) model_.initial.q[layout.first_position[b] + 3] = 1.0;
  }
  if (const Field* initial = top.find("initial")) parse_initial(top.sub(*initial));
  check_something_moves(top);
  if (const Field* simulation = top.find("simulation")) {
    parse_simulation(top.sub(*simulation));
  }
}

/// All expressions in t together within ParseLimits::max_expression_nodes,
/// counted in the order they were read (motions, beam loads, loads).
void ModelParser::check_expression_budget(const MapView& top) const {
  std::vector<const Expression*> expressions;
  for (const Body& body : model_.bodies)
    if (body.joint.motion) expressions.push_back(&*body.joint.motion);
  for (const Beam& beam : model_.beams) {
    for (const BeamPointLoad& load : beam.loads) expressions.push_back(&load.value);
    for (const BeamMovingLoad& load : beam.moving_loads) expressions.push_back(&load.value);
  }
  for (const Load& load : model_.loads) {
    if (load.type == LoadType::kForce) {
      expressions.push_back(&load.force[0]);
      expressions.push_back(&load.force[1]);
    } else if (load.type == LoadType::kTorque) {
      expressions.push_back(&load.torque);
    }
  }
  long total = 0;
  for (const Expression* e : expressions) {
    total += static_cast<long>(e->nodes().size());
    if (total <= limits_.max_expression_nodes) continue;
    const SourceLoc where = e->source().loc.line > 0 ? e->source().loc : e->nodes().back().loc;
    top.fail(where, (e->source().what.empty() ? std::string("this value") : e->source().what) +
                        ": the expressions in t hold " + std::to_string(total) +
                        " numbers, names and operators up to here, more than the limit of " +
                        std::to_string(limits_.max_expression_nodes) + " for the whole model " +
                        "(ParseLimits::max_expression_nodes)");
  }
}

/// Bodies and beams both name coordinates, so they share one namespace.
void ModelParser::claim_coordinate_name(const MapView& view, const Field& field, const std::string& name) {
  if (name == kGround) {
    view.fail(field.value_loc,
              view.prefixed("the name 'ground' is reserved for the ground frame"));
  }
  const auto [it, inserted] = coordinate_names_.emplace(name, field.value_loc);
  if (!inserted) {
    view.fail(field.value_loc,
              view.prefixed("duplicate name " + quoted(name) + " (first used at line " +
                            std::to_string(it->second.line) + ")"));
  }
}

int ModelParser::body_index(const std::string& name) const {
  const auto it = body_by_name_.find(name);
  return it == body_by_name_.end() ? -1 : it->second;
}

int ModelParser::beam_index(const std::string& name) const {
  const auto it = beam_by_name_.find(name);
  return it == beam_by_name_.end() ? -1 : it->second;
}

/// A reference to an existing body by name, e.g. a load's `body:`.
int ModelParser::existing_body(const MapView& view, const Field& field) const {
  const std::string name = view.identifier(field, limits_.max_name_length);
  const int index = body_index(name);
  if (index < 0) view.fail(field.value_loc, view.prefixed("unknown body " + quoted(name)));
  return index;
}

int ModelParser::existing_point(const MapView& view, const Field& field, int body) const {
  const std::string name = view.identifier(field, limits_.max_name_length);
  const auto& points = point_by_name_[body];
  if (const auto it = points.find(name); it != points.end()) return it->second;
  view.fail(field.value_loc, view.prefixed("body " + quoted(model_.bodies[body].name) +
                                           " has no point " + quoted(name)));
}

/// The list under `field`, refused when longer than `limit`.
std::vector<YAML::Node> ModelParser::bounded_list(const MapView& view, const Field& field, long limit, const char* limit_name) const {
  std::vector<YAML::Node> items = view.list(field);
  if (static_cast<long>(items.size()) > limit) {
    view.fail(field.value_loc, field.key + ": " + std::to_string(items.size()) +
                                   " entries, more than the limit of " + std::to_string(limit) +
                                   " (ParseLimits::" + limit_name + ")");
  }
  return items;
}

void ModelParser::parse_initial(const MapView& view) {
  view.allow({"q", "qd", "static"});
  model_.initial.loc = view.loc();
  if (const Field* q = view.find("q")) parse_coordinates(view.sub(*q), model_.initial.q, false);
  if (const Field* qd = view.find("qd")) parse_coordinates(view.sub(*qd), model_.initial.qd, true);
  if (const Field* s = view.find("static")) {
    model_.initial.static_start = view.boolean(*s);
    model_.initial.loc = s->value_loc;
  }
}

/// A model whose every coordinate is driven has nothing left to integrate; and
/// driven joints do not yet combine with constraint contacts (docs/model-format.md).
void ModelParser::check_something_moves(const MapView& top) const {
  for (const Body& body : model_.bodies) {
    if (!body.joint.motion) continue;
    for (const Contact& c : model_.contacts) {
      if (!c.is_constraint()) continue;
      top.fail(body.joint.motion_loc,
               "body " + quoted(body.name) + ": joint.motion: driven joints work with slider_spring contacts; " +
                   "contact " + quoted(c.name) + " is a " + (c.type == ContactType::kPin ? "pin" : "slider_pin") +
                   ", which does not support them yet");
    }
  }
  if (!model_.beams.empty()) return;
  const Body* last_driven = nullptr;
  for (const Body& body : model_.bodies) {
    if (!body.joint.motion) return;
    last_driven = &body;
  }
  top.fail(last_driven->joint.motion_loc,
           "body " + quoted(last_driven->name) +
               ": joint.motion drives the last joint coordinate left; with every coordinate "
               "driven and no beam there is nothing to simulate");
}

/// `{body_name: value, ...}` into one value per coordinate, model order.
void ModelParser::parse_coordinates(const MapView& view, std::vector<double>& values, bool velocities) {
  const CoordinateLayout layout = coordinate_layout(model_);
  for (const Field& entry : view.fields()) {
    const int body = body_index(entry.key);
    if (body < 0) {
      const std::string hint =
          beam_index(entry.key) >= 0 ? " (beam coordinates are not set here)" : "";
      view.fail(entry.key_loc, view.prefixed(view.what(entry) + ": unknown body '" +
                                             shown(entry.key) + "'" + hint));
    }
    if (model_.bodies[body].joint.motion) {
      view.fail(entry.key_loc,
                view.prefixed(view.what(entry) + ": body '" + shown(entry.key) +
                              "' is driven (its joint.motion at line " +
                              std::to_string(model_.bodies[body].joint.motion_loc.line) +
                              " gives q, q' and q'' at every t); its initial value cannot be set"));
    }
    const JointType type = model_.bodies[body].joint.type;
    if (type != JointType::kSpherical && type != JointType::kFree) {
      values[body_first(layout, body, velocities)] = view.number(entry);
      continue;
    }
    const bool spherical = type == JointType::kSpherical;
    const char* shape = velocities ? (spherical ? "[wx, wy, wz]" : "[vx, vy, vz, wx, wy, wz]")
                                   : (spherical ? "[w, x, y, z]" : "[x, y, z, w, qx, qy, qz]");
    const std::vector<double> given =
        view.numbers(entry, velocities ? velocity_count(type) : position_count(type), shape);
    std::copy(given.begin(), given.end(), values.begin() + body_first(layout, body, velocities));
    if (velocities) continue;
    // A quaternion is stored unit; any non-zero one names a rotation.
    double* quaternion = values.data() + body_first(layout, body, false) + (spherical ? 0 : 3);
    const double norm = std::sqrt(quaternion[0] * quaternion[0] + quaternion[1] * quaternion[1] +
                                  quaternion[2] * quaternion[2] + quaternion[3] * quaternion[3]);
    if (!(norm > 0.0) || !std::isfinite(norm)) {
      view.fail(entry.value_loc, view.prefixed(view.what(entry) + ": the quaternion (w, x, y, z) must be "
                                                                  "non-zero and finite (it is normalised)"));
    }
    for (int k = 0; k < 4; ++k) quaternion[k] /= norm;
    // Off unit length by more than a quaternion written with 7 significant
    // digits is (the 1e-6 `mbfe eval --q` accepts): a run says that it
    // scaled it, and --strict refuses it.
    constexpr double kWrittenUnitTol = 1e-6;
    if (std::abs(norm - 1.0) > kWrittenUnitTol)
      model_.initial.scaled_quaternions.push_back({entry.key, norm, entry.value_loc});
  }
}

void ModelParser::parse_simulation(const MapView& view) {
  view.allow({"integrator", "step", "t_end"});
  Simulation& simulation = model_.simulation;
  simulation.loc = view.loc();
  if (const Field* integrator = view.find("integrator")) {
    // The general `lmm:alpha=...:beta=...` form is for the command line (--integrator).
    view.choice(*integrator, {"forward_euler", "backward_euler", "explicit_midpoint", "trapezoid",
                              "rk4", "generalized_alpha", "ab2", "bdf2"});
    simulation.integrator = integrator->value.Scalar();
  }
  if (const Field* step = view.find("step")) simulation.step = view.positive(*step);
  if (const Field* t_end = view.find("t_end")) simulation.t_end = view.positive(*t_end);
}

}  // namespace mbfe::frontend
