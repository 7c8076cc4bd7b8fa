// ModelParser: beams, their sections, supports, damping, loads and adjustment.
#include "frontend/model_parser.h"

#include <cmath>

#include "ir/beam_nodes.h"

namespace mbfe::frontend {

void ModelParser::parse_beams(const MapView& top, const Field& field) {
  const auto items = top.list(field);
  for (std::size_t i = 0; i < items.size(); ++i) {
    const MapView view(file_, items[i],
                       item_context(items[i], "beam", i, limits_.max_name_length), "",
                       field.value_loc);
    model_.beams.push_back(parse_beam(view));
    beam_by_name_.emplace(model_.beams.back().name, static_cast<int>(i));
  }
}

Beam ModelParser::parse_beam(const MapView& view) {
  view.allow({"name", "origin", "angle", "length", "elements", "section", "material", "supports",
              "damping", "loads", "adjustment", "mass", "tension", "masses", "profile", "camber"});
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
  beam.tension = at_least_or(view, "tension", 0.0);
  if (const Field* masses = view.find("masses")) beam.masses = parse_point_masses(view, *masses, beam);
  if (const Field* supports = view.find("supports")) {
    beam.supports = parse_supports(view, *supports, beam);
  }
  if (const Field* damping = view.find("damping")) parse_damping(view.sub(*damping), beam);
  if (const Field* loads = view.find("loads")) parse_beam_loads(view, *loads, beam);
  if (const Field* adjustment = view.find("adjustment")) {
    beam.adjustment = parse_adjustment(view.sub(*adjustment));
  }
  if (const Field* mass = view.find("mass")) {
    beam.mass = view.choice(*mass, {"consistent", "lumped"}) == 0 ? MassLumping::kConsistent
                                                                  : MassLumping::kLumped;
  }
  parse_profile(view, beam);
  return beam;
}

/// Element count, within the per-beam and whole-model limits.
int ModelParser::parse_elements(const MapView& view, const Field& field) {
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

void ModelParser::parse_section(const MapView& view, Beam& beam) {
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

void ModelParser::parse_material(const MapView& view, Beam& beam) {
  view.allow({"youngs_modulus", "density"});
  beam.youngs_modulus = view.positive(view.require("youngs_modulus"));
  beam.density = view.positive(view.require("density"));
}

/// Node index of position `at` along the beam, which must fall on a node.
int ModelParser::node_at(const MapView& view, const Field& field, const Beam& beam) const {
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

std::vector<Support> ModelParser::parse_supports(const MapView& beam_view, const Field& field, const Beam& beam) {
  std::vector<Support> supports;
  const auto items = beam_view.list(field);
  for (std::size_t i = 0; i < items.size(); ++i) {
    const MapView view(file_, items[i],
                       "beam " + quoted(beam.name) + ": support #" + std::to_string(i + 1), "",
                       field.value_loc);
    Support support;
    support.loc = view.loc();
    const Field& at = view.require("at");
    support.at = view.number(at);
    constexpr SupportType kTypes[] = {SupportType::kPinned, SupportType::kClamped, SupportType::kSpring};
    support.type = kTypes[view.choice(view.require("type"), {"pinned", "clamped", "spring"})];
    if (support.type == SupportType::kSpring) {
      // An elastic support: spring and damper to the ground on w, a lumped mass at the node.
      view.allow({"at", "type", "stiffness", "damping", "mass"});
      support.stiffness = view.positive(view.require("stiffness"));
      support.damping = at_least_or(view, "damping", 0.0);
      support.mass = at_least_or(view, "mass", 0.0);
    } else {
      view.allow({"at", "type"});
    }
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

std::vector<BeamPointMass> ModelParser::parse_point_masses(const MapView& beam_view, const Field& field,
                                                           const Beam& beam) {
  std::vector<BeamPointMass> masses;
  const auto items = beam_view.list(field);
  for (std::size_t i = 0; i < items.size(); ++i) {
    const MapView view(file_, items[i],
                       "beam " + quoted(beam.name) + ": mass #" + std::to_string(i + 1), "", field.value_loc);
    view.allow({"at", "mass"});
    BeamPointMass m;
    m.loc = view.loc();
    const Field& at = view.require("at");
    m.at = view.number(at);
    m.node = node_at(view, at, beam);
    m.mass = view.positive(view.require("mass"));
    masses.push_back(m);
  }
  return masses;
}

void ModelParser::parse_damping(const MapView& view, Beam& beam) {
  view.allow({"rayleigh"});
  const MapView rayleigh = view.sub(view.require("rayleigh"));
  rayleigh.allow({"alpha", "beta"});
  beam.rayleigh_alpha = at_least_or(rayleigh, "alpha", 0.0);
  beam.rayleigh_beta = at_least_or(rayleigh, "beta", 0.0);
}

void ModelParser::parse_beam_loads(const MapView& beam_view, const Field& field, Beam& beam) {
  const auto items = beam_view.list(field);
  std::unordered_map<std::string, SourceLoc> names;  // point and moving loads share them
  for (std::size_t i = 0; i < items.size(); ++i) {
    const MapView view(file_, items[i],
                       "beam " + quoted(beam.name) + ": " +
                           item_context(items[i], "load", i, limits_.max_name_length),
                       "", field.value_loc);
    const Field& type = view.require("type");
    const std::string name = optional_item_name(view, names);
    if (view.choice(type, {"point", "moving"}) == 0) {
      view.allow({"name", "type", "at", "value", "start", "stop"});
      BeamPointLoad load;
      load.name = name;
      load.loc = view.loc();
      const Field& at = view.require("at");
      load.at = view.number(at);
      load.node = node_at(view, at, beam);
      load.value = view.expression(view.require("value"));
      load.window = time_window(view);
      beam.loads.push_back(load);
      continue;
    }
    // A moving load's `start` is where it is at t0 (m); its time window is
    // the part of the crossing it is on the beam, so it takes no `stop`.
    view.allow({"name", "type", "value", "speed", "start", "t0"});
    BeamMovingLoad load;
    load.name = name;
    load.loc = view.loc();
    load.value = view.expression(view.require("value"));
    const Field& speed = view.require("speed");
    load.speed = view.number(speed);
    if (load.speed == 0.0) {
      view.fail(speed.value_loc, view.prefixed("speed must not be 0 (a load standing still is a "
                                               "'point' load at a node)"));
    }
    load.start = view.number_or("start", 0.0);
    load.t0 = view.number_or("t0", 0.0);
    beam.moving_loads.push_back(load);
  }
}

Adjustment ModelParser::parse_adjustment(const MapView& view) {
  view.allow({"omega_limit", "margin", "zeta_min", "policy", "scope", "tolerance"});
  Adjustment adjustment;
  adjustment.present = true;
  adjustment.loc = view.loc();
  const Field& omega_limit = view.require("omega_limit");
  adjustment.omega_limit_loc = omega_limit.value_loc;
  if (omega_limit.value.IsScalar() && omega_limit.value.Scalar() == "auto") {
    adjustment.omega_limit_auto = true;
  } else {
    adjustment.omega_limit = view.positive(omega_limit);
  }
  if (const Field* tolerance = view.find("tolerance")) {
    if (!adjustment.omega_limit_auto)
      view.fail(tolerance->key_loc, view.prefixed("tolerance goes with omega_limit: auto (it chooses the limit); "
                                                  "omega_limit is given here"));
    adjustment.tolerance = view.positive(*tolerance);
    if (adjustment.tolerance >= 1.0)
      view.fail(tolerance->value_loc, view.prefixed(view.what(*tolerance) + " must be < 1, a relative change (got " +
                                                    shown(tolerance->value.Scalar()) + ")"));
  }
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
  // The default policy is mass: the cap's roots with the original static
  // compliance (docs/damping-adjustment.md, "Which policy is the default").
  adjustment.policy = AdjustmentPolicy::kMass;
  const Field* policy = view.find("policy");
  if (policy != nullptr) {
    constexpr AdjustmentPolicy kPolicies[] = {
        AdjustmentPolicy::kCap, AdjustmentPolicy::kPaperEq25, AdjustmentPolicy::kKeepSlow,
        AdjustmentPolicy::kNone, AdjustmentPolicy::kMass, AdjustmentPolicy::kTruncate};
    adjustment.policy =
        kPolicies[view.choice(*policy, {"cap", "paper_eq25", "keep_slow", "none", "mass", "truncate"})];
  }
  if (const Field* scope = view.find("scope")) {
    adjustment.scope = view.choice(*scope, {"beam", "joined"}) == 0 ? AdjustmentScope::kBeam : AdjustmentScope::kJoined;
    // A joined structure takes only the cap, so there the cap is the default.
    if (adjustment.scope == AdjustmentScope::kJoined && policy == nullptr) adjustment.policy = AdjustmentPolicy::kCap;
    // The joined structure is adjusted in the low-rank form, which needs one
    // uniform cap for every changed mode.
    if (adjustment.scope == AdjustmentScope::kJoined && adjustment.policy != AdjustmentPolicy::kCap) {
      view.fail(scope->value_loc, view.prefixed("scope 'joined' takes policy 'cap' (the joined structure is "
                                                "adjusted in the low-rank form, one cap for every changed mode)"));
    }
  }
  return adjustment;
}

}  // namespace mbfe::frontend
