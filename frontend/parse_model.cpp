// Model description file (YAML) -> validated model IR.
//
// Three stages: the raw bytes are checked (size, text, nesting depth, number
// of values) so that
// nothing absurd reaches yaml-cpp; yaml-cpp builds a tree, and any exception
// it throws becomes a ModelError at its mark; the tree is walked section by
// section against the schema of the model format (docs/model-format.md),
// each value checked and each cross reference resolved to an index.
#include "frontend/parse_model.h"

#include <sys/stat.h>
#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <new>
#include <sstream>
#include <unordered_map>

#include "frontend/sha256.h"
#include "ir/beam_nodes.h"
#include "frontend/text_guard.h"
#include "frontend/yaml_reader.h"

namespace mbfe::frontend {

// The front end fills the IR: its types are used unqualified here.
using namespace mbfe::ir;
namespace {

// The name a parent takes for the ground frame; no body may take it.
constexpr const char* kGround = "ground";

std::string quoted(const std::string& name) { return "'" + shown(name) + "'"; }

/// Walks one parsed YAML document into a Model.
class ModelParser {
 public:
  ModelParser(const std::string& file, const ParseLimits& limits, Model& model)
      : file_(file), limits_(limits), model_(model) {}

  void parse(const YAML::Node& root) {
    const MapView top(file_, root, "", "", SourceLoc{1, 1});
    top.allow({"model", "description", "gravity", "bodies", "loads", "beams", "contacts", "initial",
               "simulation"});
    const Field& name = top.require("model");
    model_.name = top.identifier(name, limits_.max_name_length);
    if (const Field* description = top.find("description")) top.text(*description);
    model_.gravity = top.vec2_or("gravity", {0.0, 0.0});
    if (const Field* bodies = top.find("bodies")) parse_bodies(top, *bodies);
    if (const Field* beams = top.find("beams")) parse_beams(top, *beams);
    if (model_.bodies.empty() && model_.beams.empty()) {
      top.fail(name.value_loc, "model " + quoted(model_.name) + " has no bodies and no beams");
    }
    if (const Field* loads = top.find("loads")) parse_loads(top, *loads);
    if (const Field* contacts = top.find("contacts")) parse_contacts(top, *contacts);
    model_.initial.q.assign(model_.bodies.size(), 0.0);
    model_.initial.qd.assign(model_.bodies.size(), 0.0);
    if (const Field* initial = top.find("initial")) parse_initial(top.sub(*initial));
    if (const Field* simulation = top.find("simulation")) {
      parse_simulation(top.sub(*simulation));
    }
  }

 private:
  // ---- names -------------------------------------------------------------

  /// Bodies and beams both name coordinates, so they share one namespace.
  void claim_coordinate_name(const MapView& view, const Field& field, const std::string& name) {
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

  int body_index(const std::string& name) const {
    const auto it = body_by_name_.find(name);
    return it == body_by_name_.end() ? -1 : it->second;
  }

  int beam_index(const std::string& name) const {
    const auto it = beam_by_name_.find(name);
    return it == beam_by_name_.end() ? -1 : it->second;
  }

  /// A reference to an existing body by name, e.g. a load's `body:`.
  int existing_body(const MapView& view, const Field& field) const {
    const std::string name = view.identifier(field, limits_.max_name_length);
    const int index = body_index(name);
    if (index < 0) view.fail(field.value_loc, view.prefixed("unknown body " + quoted(name)));
    return index;
  }

  int existing_point(const MapView& view, const Field& field, int body) const {
    const std::string name = view.identifier(field, limits_.max_name_length);
    const auto& points = point_by_name_[body];
    if (const auto it = points.find(name); it != points.end()) return it->second;
    view.fail(field.value_loc, view.prefixed("body " + quoted(model_.bodies[body].name) +
                                             " has no point " + quoted(name)));
  }

  /// The list under `field`, refused when longer than `limit`.
  std::vector<YAML::Node> bounded_list(const MapView& view, const Field& field, long limit,
                                       const char* limit_name) const {
    std::vector<YAML::Node> items = view.list(field);
    if (static_cast<long>(items.size()) > limit) {
      view.fail(field.value_loc, field.key + ": " + std::to_string(items.size()) +
                                     " entries, more than the limit of " + std::to_string(limit) +
                                     " (ParseLimits::" + limit_name + ")");
    }
    return items;
  }

  // ---- bodies ------------------------------------------------------------

  void parse_bodies(const MapView& top, const Field& field) {
    const auto items = bounded_list(top, field, limits_.max_bodies, "max_bodies");
    for (std::size_t i = 0; i < items.size(); ++i) {
      const MapView view(file_, items[i],
                         item_context(items[i], "body", i, limits_.max_name_length), "",
                         field.value_loc);
      model_.bodies.push_back(parse_body(view));
      const Body& body = model_.bodies.back();
      body_by_name_.emplace(body.name, static_cast<int>(i));
      auto& points = point_by_name_.emplace_back();
      for (std::size_t k = 0; k < body.points.size(); ++k) {
        points.emplace(body.points[k].name, static_cast<int>(k));
      }
    }
  }

  Body parse_body(const MapView& view) {
    view.allow({"name", "parent", "joint", "mass", "inertia", "com", "points"});
    Body body;
    body.loc = view.loc();
    const Field& name = view.require("name");
    body.name = view.identifier(name, limits_.max_name_length);
    claim_coordinate_name(view, name, body.name);

    const Field& parent = view.require("parent");
    body.parent = parent_index(view, parent, body.name);
    body.joint = parse_joint(view.sub(view.require("joint")));
    body.mass = view.number_at_least(view.require("mass"), 0.0);
    body.inertia = view.number_at_least(view.require("inertia"), 0.0);
    body.com = view.vec2_or("com", {0.0, 0.0});
    if (const Field* points = view.find("points")) body.points = parse_points(view, *points);
    return body;
  }

  /// Parents come before their children, which also rules out cycles.
  int parent_index(const MapView& view, const Field& field, const std::string& child) const {
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

  Joint parse_joint(const MapView& view) {
    view.allow({"type", "at", "axis"});
    Joint joint;
    joint.loc = view.loc();
    joint.type = view.choice(view.require("type"), {"revolute", "prismatic"}) == 0
                     ? JointType::kRevolute
                     : JointType::kPrismatic;
    joint.at = view.vec2_or("at", {0.0, 0.0});
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

  std::vector<NamedPoint> parse_points(const MapView& body, const Field& field) {
    const MapView view = body.sub(field);
    std::vector<NamedPoint> points;
    for (const Field& entry : view.fields()) {
      const std::string problem = identifier_problem(entry.key, limits_.max_name_length);
      if (!problem.empty()) {
        view.fail(entry.key_loc, view.prefixed("point '" + shown(entry.key) + "' " + problem));
      }
      points.push_back({entry.key, view.vec2(entry), entry.key_loc});
    }
    return points;
  }

  // ---- loads on bodies ---------------------------------------------------

  void parse_loads(const MapView& top, const Field& field) {
    const auto items = top.list(field);
    for (std::size_t i = 0; i < items.size(); ++i) {
      const MapView view(file_, items[i], "load #" + std::to_string(i + 1), "", field.value_loc);
      model_.loads.push_back(parse_load(view));
    }
  }

  Load parse_load(const MapView& view) {
    Load load;
    load.loc = view.loc();
    const int type = view.choice(view.require("type"), {"force", "torque", "spring_damper"});
    if (type == 0) {
      view.allow({"type", "body", "point", "value"});
      load.type = LoadType::kForce;
      load.body = existing_body(view, view.require("body"));
      if (const Field* point = view.find("point")) {
        load.point = existing_point(view, *point, load.body);
      }
      load.force = view.vec2(view.require("value"));
    } else if (type == 1) {
      view.allow({"type", "body", "value"});
      load.type = LoadType::kTorque;
      load.body = existing_body(view, view.require("body"));
      load.torque = view.number(view.require("value"));
    } else {
      view.allow({"type", "joint", "stiffness", "damping", "rest"});
      load.type = LoadType::kSpringDamper;
      load.body = existing_body(view, view.require("joint"));
      load.stiffness = at_least_or(view, "stiffness", 0.0);
      load.damping = at_least_or(view, "damping", 0.0);
      load.rest = view.number_or("rest", 0.0);
    }
    return load;
  }

  /// An optional number >= 0, 0 when absent.
  static double at_least_or(const MapView& view, const std::string& key, double minimum) {
    const Field* field = view.find(key);
    return field ? view.number_at_least(*field, minimum) : 0.0;
  }

  // ---- beams -------------------------------------------------------------

  void parse_beams(const MapView& top, const Field& field) {
    const auto items = top.list(field);
    for (std::size_t i = 0; i < items.size(); ++i) {
      const MapView view(file_, items[i],
                         item_context(items[i], "beam", i, limits_.max_name_length), "",
                         field.value_loc);
      model_.beams.push_back(parse_beam(view));
      beam_by_name_.emplace(model_.beams.back().name, static_cast<int>(i));
    }
  }

  Beam parse_beam(const MapView& view) {
    view.allow({"name", "origin", "angle", "length", "elements", "section", "material", "supports",
                "damping", "loads", "adjustment", "mass"});
    Beam beam;
    beam.loc = view.loc();
    const Field& name = view.require("name");
    beam.name = view.identifier(name, limits_.max_name_length);
    claim_coordinate_name(view, name, beam.name);

    beam.origin = view.vec2(view.require("origin"));
    beam.angle = view.number_or("angle", 0.0);
    beam.length = view.positive(view.require("length"));
    beam.elements = parse_elements(view, view.require("elements"));
    parse_section(view.sub(view.require("section")), beam);
    parse_material(view.sub(view.require("material")), beam);
    if (const Field* supports = view.find("supports")) {
      beam.supports = parse_supports(view, *supports, beam);
    }
    if (const Field* damping = view.find("damping")) parse_damping(view.sub(*damping), beam);
    if (const Field* loads = view.find("loads")) beam.loads = parse_beam_loads(view, *loads, beam);
    if (const Field* adjustment = view.find("adjustment")) {
      beam.adjustment = parse_adjustment(view.sub(*adjustment));
    }
    if (const Field* mass = view.find("mass")) {
      beam.mass = view.choice(*mass, {"consistent", "lumped"}) == 0 ? MassLumping::kConsistent
                                                                    : MassLumping::kLumped;
    }
    return beam;
  }

  /// Element count, within the per-beam and whole-model limits.
  int parse_elements(const MapView& view, const Field& field) {
    const long long elements = view.whole_number(field);
    if (elements <= 0) {
      view.fail(field.value_loc,
                view.prefixed("elements must be > 0 (got " + shown(field.value.Scalar()) + ")"));
    }
    if (elements > limits_.max_beam_elements) {
      view.fail(field.value_loc, view.prefixed("elements = " + std::to_string(elements) +
                                               " is more than the limit of " +
                                               std::to_string(limits_.max_beam_elements) +
                                               " per beam (ParseLimits::max_beam_elements)"));
    }
    // Two DOFs (w, w') per node, before supports remove some.
    total_beam_dofs_ += 2 * (elements + 1);
    if (total_beam_dofs_ > limits_.max_total_beam_dofs) {
      view.fail(field.value_loc,
                view.prefixed("the beams now have " + std::to_string(total_beam_dofs_) +
                              " DOFs, more than the limit of " +
                              std::to_string(limits_.max_total_beam_dofs) +
                              " (ParseLimits::max_total_beam_dofs)"));
    }
    return static_cast<int>(elements);
  }

  void parse_section(const MapView& view, Beam& beam) {
    if (view.find("shape")) {
      view.allow({"shape", "side"});
      view.choice(*view.find("shape"), {"square"});
      const double side = view.positive(view.require("side"));
      beam.area = side * side;
      beam.second_moment = side * side * side * side / 12.0;
    } else {
      if (view.find("side")) {
        view.fail(view.find("side")->key_loc,
                  view.prefixed("section: 'side' needs 'shape: square' (a section is either "
                                "{shape: square, side: a} or {area: A, inertia: I})"));
      }
      view.allow({"area", "inertia"});
      beam.area = view.positive(view.require("area"));
      beam.second_moment = view.positive(view.require("inertia"));
    }
    if (!std::isfinite(beam.area) || !std::isfinite(beam.second_moment) ||
        beam.second_moment <= 0.0) {
      view.fail(view.loc(),
                view.prefixed("section: area and second moment must be finite and > 0"));
    }
  }

  void parse_material(const MapView& view, Beam& beam) {
    view.allow({"youngs_modulus", "density"});
    beam.youngs_modulus = view.positive(view.require("youngs_modulus"));
    beam.density = view.positive(view.require("density"));
  }

  /// Node index of position `at` along the beam, which must fall on a node.
  int node_at(const MapView& view, const Field& field, const Beam& beam) const {
    const double at = view.number(field);
    if (at < 0.0 || at > beam.length) {
      view.fail(
          field.value_loc,
          view.prefixed(view.what(field) + " must be within [0, " + format_number(beam.length) +
                        "] (the beam's length; got " + shown(field.value.Scalar()) + ")"));
    }
    const ir::NodeOnBeam node = ir::node_on_beam(beam.length, beam.elements, at);
    if (!node.on_node) {
      view.fail(field.value_loc,
                view.prefixed(view.what(field) + " = " + shown(field.value.Scalar()) +
                              " is not at a node (nodes are " + format_number(node.spacing) +
                              " m apart; the nearest is node " + std::to_string(node.nearest) + " at " +
                              format_number(node.nearest * node.spacing) + ")"));
    }
    return static_cast<int>(node.nearest);
  }

  std::vector<Support> parse_supports(const MapView& beam_view, const Field& field,
                                      const Beam& beam) {
    std::vector<Support> supports;
    const auto items = beam_view.list(field);
    for (std::size_t i = 0; i < items.size(); ++i) {
      const MapView view(file_, items[i],
                         "beam " + quoted(beam.name) + ": support #" + std::to_string(i + 1), "",
                         field.value_loc);
      view.allow({"at", "type"});
      Support support;
      support.loc = view.loc();
      const Field& at = view.require("at");
      support.at = view.number(at);
      support.type = view.choice(view.require("type"), {"pinned", "clamped"}) == 0
                         ? SupportType::kPinned
                         : SupportType::kClamped;
      support.node = node_at(view, at, beam);
      for (const Support& earlier : supports) {
        if (earlier.node == support.node) {
          view.fail(at.value_loc, view.prefixed("node " + std::to_string(support.node) +
                                                " already has a support (line " +
                                                std::to_string(earlier.loc.line) + ")"));
        }
      }
      supports.push_back(support);
    }
    return supports;
  }

  void parse_damping(const MapView& view, Beam& beam) {
    view.allow({"rayleigh"});
    const MapView rayleigh = view.sub(view.require("rayleigh"));
    rayleigh.allow({"alpha", "beta"});
    beam.rayleigh_alpha = at_least_or(rayleigh, "alpha", 0.0);
    beam.rayleigh_beta = at_least_or(rayleigh, "beta", 0.0);
  }

  std::vector<BeamPointLoad> parse_beam_loads(const MapView& beam_view, const Field& field,
                                              const Beam& beam) {
    std::vector<BeamPointLoad> loads;
    const auto items = beam_view.list(field);
    for (std::size_t i = 0; i < items.size(); ++i) {
      const MapView view(file_, items[i],
                         "beam " + quoted(beam.name) + ": load #" + std::to_string(i + 1), "",
                         field.value_loc);
      view.allow({"type", "at", "value"});
      view.choice(view.require("type"), {"point"});
      BeamPointLoad load;
      load.loc = view.loc();
      const Field& at = view.require("at");
      load.at = view.number(at);
      load.node = node_at(view, at, beam);
      load.value = view.number(view.require("value"));
      loads.push_back(load);
    }
    return loads;
  }

  Adjustment parse_adjustment(const MapView& view) {
    view.allow({"omega_limit", "margin", "zeta_min", "policy"});
    Adjustment adjustment;
    adjustment.present = true;
    adjustment.loc = view.loc();
    adjustment.omega_limit = view.positive(view.require("omega_limit"));
    if (const Field* margin = view.find("margin")) {
      adjustment.margin = view.number_at_least(*margin, 0.0);
    }
    if (const Field* zeta = view.find("zeta_min")) {
      adjustment.zeta_min = view.number_at_least(*zeta, 0.0);
      if (adjustment.zeta_min >= 1.0) {
        view.fail(zeta->value_loc, view.prefixed(view.what(*zeta) + " must be < 1 (got " +
                                                 shown(zeta->value.Scalar()) + ")"));
      }
    }
    if (const Field* policy = view.find("policy")) {
      constexpr AdjustmentPolicy kPolicies[] = {
          AdjustmentPolicy::kCap, AdjustmentPolicy::kPaperEq25, AdjustmentPolicy::kKeepSlow,
          AdjustmentPolicy::kNone};
      adjustment.policy =
          kPolicies[view.choice(*policy, {"cap", "paper_eq25", "keep_slow", "none"})];
    }
    return adjustment;
  }

  // ---- contacts ----------------------------------------------------------

  void parse_contacts(const MapView& top, const Field& field) {
    const auto items = top.list(field);
    std::unordered_map<std::string, SourceLoc> names;
    for (std::size_t i = 0; i < items.size(); ++i) {
      const MapView view(file_, items[i],
                         item_context(items[i], "contact", i, limits_.max_name_length), "",
                         field.value_loc);
      view.allow({"name", "type", "body", "point", "beam", "at"});
      Contact contact;
      contact.loc = view.loc();
      const Field& name = view.require("name");
      contact.name = view.identifier(name, limits_.max_name_length);
      const auto [it, inserted] = names.emplace(contact.name, name.value_loc);
      if (!inserted) {
        view.fail(name.value_loc, view.prefixed("duplicate contact name (first used at line " +
                                                std::to_string(it->second.line) + ")"));
      }
      contact.type = view.choice(view.require("type"), {"pin", "slider_pin"}) == 0
                         ? ContactType::kPin
                         : ContactType::kSliderPin;
      contact.body = existing_body(view, view.require("body"));
      contact.point = existing_point(view, view.require("point"), contact.body);
      const Field& beam = view.require("beam");
      const std::string beam_name = view.identifier(beam, limits_.max_name_length);
      contact.beam = beam_index(beam_name);
      if (contact.beam < 0) {
        view.fail(beam.value_loc, view.prefixed("unknown beam " + quoted(beam_name)));
      }
      parse_contact_position(view, contact);
      model_.contacts.push_back(contact);
    }
  }

  void parse_contact_position(const MapView& view, Contact& contact) const {
    const Field* at = view.find("at");
    if (contact.type == ContactType::kSliderPin) {
      if (at) {
        view.fail(at->key_loc, view.prefixed("'at' is not allowed for a slider_pin (its "
                                             "position along the beam follows the body)"));
      }
      return;
    }
    const Field& at_field = view.require("at");
    const double length = model_.beams[contact.beam].length;
    contact.at = view.number(at_field);
    if (contact.at < 0.0 || contact.at > length) {
      view.fail(at_field.value_loc,
                view.prefixed("at must be within [0, " + format_number(length) +
                              "], the length of beam " + quoted(model_.beams[contact.beam].name) +
                              " (got " + shown(at_field.value.Scalar()) + ")"));
    }
  }

  // ---- initial state and simulation -------------------------------------

  void parse_initial(const MapView& view) {
    view.allow({"q", "qd"});
    if (const Field* q = view.find("q")) parse_coordinates(view.sub(*q), model_.initial.q);
    if (const Field* qd = view.find("qd")) parse_coordinates(view.sub(*qd), model_.initial.qd);
  }

  /// `{body_name: value, ...}` into one value per body, model order.
  void parse_coordinates(const MapView& view, std::vector<double>& values) const {
    for (const Field& entry : view.fields()) {
      const int body = body_index(entry.key);
      if (body < 0) {
        const std::string hint =
            beam_index(entry.key) >= 0 ? " (beam coordinates are not set here)" : "";
        view.fail(entry.key_loc, view.prefixed(view.what(entry) + ": unknown body '" +
                                               shown(entry.key) + "'" + hint));
      }
      values[body] = view.number(entry);
    }
  }

  void parse_simulation(const MapView& view) {
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

  const std::string& file_;
  const ParseLimits& limits_;
  Model& model_;
  // Name -> index lookups, so that a model of many bodies parses in linear time.
  std::unordered_map<std::string, SourceLoc> coordinate_names_;
  std::unordered_map<std::string, int> body_by_name_;
  std::unordered_map<std::string, int> beam_by_name_;
  std::vector<std::unordered_map<std::string, int>> point_by_name_;  // per body
  long long total_beam_dofs_ = 0;
};

SourceLoc mark_location(const YAML::Mark& mark) {
  if (mark.is_null() || mark.line < 0 || mark.column < 0) return {1, 1};
  return {mark.line + 1, mark.column + 1};
}

/// The one YAML document of `text`; a second one is an error.
YAML::Node load_single_document(const std::string& text, const std::string& file) {
  if (const auto second = find_second_document(text)) {
    throw ModelError(file, *second, "a second YAML document starts here; expected one");
  }
  YAML::Node root = YAML::Load(text);
  if (!root.IsDefined() || root.IsNull()) {
    throw ModelError(file, {1, 1},
                     "the file holds no model (expected a YAML map starting with 'model:')");
  }
  return root;
}

/// yaml-cpp's messages start with "yaml-cpp: error at line ..."; keep the
/// part after the position, since ModelError adds its own.
std::string yaml_message(const YAML::Exception& error) {
  return error.msg.empty() ? std::string("invalid YAML") : "invalid YAML: " + error.msg;
}

}  // namespace

Model parse_model_text(const std::string& text, const std::string& display_path,
                       const ParseLimits& limits) {
  if (text.size() > limits.max_file_bytes) {
    throw ModelError(display_path, {1, 1},
                     "the file is " + std::to_string(text.size()) +
                         " bytes, more than the limit of " + std::to_string(limits.max_file_bytes) +
                         " (ParseLimits::max_file_bytes)");
  }
  if (auto problem = find_non_text(text)) {
    throw ModelError(display_path, problem->loc, problem->message);
  }
  if (auto problem =
          find_excess_structure(text, limits.max_nesting_depth, limits.max_yaml_values)) {
    throw ModelError(display_path, problem->loc, problem->message);
  }
  try {
    const YAML::Node root = load_single_document(text, display_path);
    Model model;
    model.source_path = display_path;
    model.source_sha256 = sha256_hex(text);
    ModelParser(display_path, limits, model).parse(root);
    return model;
  } catch (const ModelError&) {
    throw;
  } catch (const YAML::Exception& error) {
    // Syntax errors, and (should a conversion ever slip in) yaml-cpp's own
    // representation errors: all are about the input, at yaml-cpp's mark.
    throw ModelError(display_path, mark_location(error.mark), yaml_message(error));
  } catch (const std::bad_alloc&) {
    throw ModelError(display_path, {1, 1}, "out of memory while reading the model");
  }
}

Model load_model_file(const std::string& path, const ParseLimits& limits) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) {
    throw ModelError(path, {}, std::string("cannot read: ") + std::strerror(errno));
  }
  if (S_ISDIR(info.st_mode)) throw ModelError(path, {}, "cannot read: is a directory");
  // Refuse before reading: a huge file must not be loaded into memory.
  if (S_ISREG(info.st_mode) && static_cast<std::size_t>(info.st_size) > limits.max_file_bytes) {
    throw ModelError(path, {1, 1},
                     "the file is " + std::to_string(info.st_size) +
                         " bytes, more than the limit of " + std::to_string(limits.max_file_bytes) +
                         " (ParseLimits::max_file_bytes)");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ModelError(path, {}, std::string("cannot read: ") + std::strerror(errno));
  // Read at most one byte past the limit, so a growing or special file
  // (a pipe, /dev/zero) cannot make us read without end.
  std::string text;
  std::vector<char> buffer(1 << 16);
  while (in && text.size() <= limits.max_file_bytes) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    text.append(buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw ModelError(path, {}, "cannot read: I/O error");
  return parse_model_text(text, path, limits);
}

}  // namespace mbfe::frontend
