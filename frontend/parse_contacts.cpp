// ModelParser: contacts between a body vertex and a beam.
#include "frontend/model_parser.h"

#include <algorithm>
#include <cmath>

namespace mbfe::frontend {

void ModelParser::parse_contacts(const MapView& top, const Field& field) {
  const auto items = top.list(field);
  std::unordered_map<std::string, SourceLoc> names;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const MapView view(file_, items[i],
                       item_context(items[i], "contact", i, limits_.max_name_length), "",
                       field.value_loc);
    view.allow({"name", "type", "body", "point", "beam", "at", "law", "stiffness", "coefficient", "damping",
                "unilateral", "side"});
    Contact contact;
    contact.loc = view.loc();
    const Field& name = view.require("name");
    contact.name = view.identifier(name, limits_.max_name_length);
    const auto [it, inserted] = names.emplace(contact.name, name.value_loc);
    if (!inserted) {
      view.fail(name.value_loc, view.prefixed("duplicate contact name (first used at line " +
                                              std::to_string(it->second.line) + ")"));
    }
    const Field& type = view.require("type");
    contact.type = static_cast<ContactType>(view.choice(type, {"pin", "slider_pin", "slider_spring"}));
    if (contact.type == ContactType::kSliderSpring) {
      if (const Field* law = view.find("law"))
        contact.law = view.choice(*law, {"linear", "hertz"}) == 1 ? ContactLaw::kHertz : ContactLaw::kLinear;
      // Each law takes its own constant, and only its own.
      const char* constant = contact.law == ContactLaw::kHertz ? "coefficient" : "stiffness";
      const char* other = contact.law == ContactLaw::kHertz ? "stiffness" : "coefficient";
      if (const Field* f = view.find(other)) {
        view.fail(f->key_loc, view.prefixed(std::string("'") + other + "' is not for law " +
                                            (contact.law == ContactLaw::kHertz ? "hertz" : "linear") +
                                            "; expected '" + constant + "' (" +
                                            (contact.law == ContactLaw::kHertz ? "N/m^1.5" : "N/m") + ")"));
      }
      const double value = view.positive(view.require(constant));
      (contact.law == ContactLaw::kHertz ? contact.coefficient : contact.stiffness) = value;
      contact.damping = at_least_or(view, "damping", 0.0);
      if (const Field* u = view.find("unilateral")) contact.unilateral = view.boolean(*u);
      if (const Field* side = view.find("side")) contact.from_below = view.choice(*side, {"above", "below"}) == 1;
    } else {
      for (const char* key : {"law", "stiffness", "coefficient", "damping", "unilateral", "side"}) {
        if (const Field* f = view.find(key)) {
          view.fail(f->key_loc, view.prefixed(std::string("'") + key +
                                              "' is only for a slider_spring contact"));
        }
      }
    }
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
    contact_name_locs_.push_back(name.value_loc);
  }
}

void ModelParser::parse_contact_position(const MapView& view, Contact& contact) const {
  const Field* at = view.find("at");
  if (contact.type != ContactType::kPin) {
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

void ModelParser::parse_links(const MapView& top, const Field& field) {
  const auto items = top.list(field);
  std::unordered_map<std::string, SourceLoc> names;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const MapView view(file_, items[i], item_context(items[i], "link", i, limits_.max_name_length), "",
                       field.value_loc);
    view.allow({"name", "a", "b", "stiffness", "damping", "slack", "rest", "hold"});
    Link link;
    link.loc = view.loc();
    const Field& name = view.require("name");
    link.name = view.identifier(name, limits_.max_name_length);
    const auto [it, inserted] = names.emplace(link.name, name.value_loc);
    if (!inserted) {
      view.fail(name.value_loc, view.prefixed("duplicate link name (first used at line " +
                                              std::to_string(it->second.line) + ")"));
    }
    link.a = parse_beam_point(view, view.require("a"));
    const Field& b = view.require("b");
    link.b = parse_beam_point(view, b);
    const Beam& beam_a = model_.beams[link.a.beam];
    const Beam& beam_b = model_.beams[link.b.beam];
    if (link.a.beam == link.b.beam) {
      view.fail(b.value_loc, view.prefixed("a link joins two different beams (both ends are on " +
                                           quoted(beam_a.name) + ")"));
    }
    // Transverse displacements add up only between parallel beams.
    if (std::abs(std::remainder(beam_a.angle - beam_b.angle, 2.0 * M_PI)) > 1e-9) {
      view.fail(b.value_loc, view.prefixed("beams " + quoted(beam_a.name) + " and " + quoted(beam_b.name) +
                                           " are not parallel (angles " + format_number(beam_a.angle) + " and " +
                                           format_number(beam_b.angle) +
                                           " rad): a link acts on their transverse displacements"));
    }
    link.stiffness = view.positive(view.require("stiffness"));
    link.damping = at_least_or(view, "damping", 0.0);
    if (const Field* slack = view.find("slack")) link.slack = view.boolean(*slack);
    const Field* rest = view.find("rest");
    const Field* hold = view.find("hold");
    if (rest && hold) {
      view.fail(hold->key_loc, view.prefixed("give 'rest' or 'hold', not both ('hold' finds the rest offset)"));
    }
    if (rest) link.rest = view.number(*rest);
    if (hold) link.hold = view.number(*hold);
    model_.links.push_back(link);
    link_name_locs_.push_back(name.value_loc);
  }
}

void ModelParser::check_joined_adjustments(const MapView& top) const {
  auto joined = [](const Adjustment& a) { return a.active() && a.scope == AdjustmentScope::kJoined; };
  for (std::size_t b = 0; b < model_.beams.size(); ++b) {
    if (!joined(model_.beams[b].adjustment)) continue;
    const bool linked = std::any_of(model_.links.begin(), model_.links.end(), [&](const Link& l) {
      return l.a.beam == static_cast<int>(b) || l.b.beam == static_cast<int>(b);
    });
    if (!linked) {
      top.fail(model_.beams[b].adjustment.loc,
               "beam " + quoted(model_.beams[b].name) +
                   ": scope 'joined' adjusts a beam together with the beams links join it to, and no link "
                   "joins it to another beam; use scope 'beam'");
    }
  }
  for (const Link& link : model_.links) {
    const Beam& a = model_.beams[link.a.beam];
    const Beam& b = model_.beams[link.b.beam];
    if (!joined(a.adjustment) && !joined(b.adjustment)) continue;
    const Adjustment& x = a.adjustment;
    const Adjustment& y = b.adjustment;
    if (joined(x) && joined(y) && x.omega_limit == y.omega_limit && x.margin == y.margin &&
        x.zeta_min == y.zeta_min)
      continue;
    // Point at the block that differs from a joined one, or at the link when
    // one beam has none.
    const Beam& odd = joined(x) ? b : a;
    const Beam& other = joined(x) ? a : b;
    top.fail(odd.adjustment.present ? odd.adjustment.loc : link.loc,
             "link " + quoted(link.name) + " joins beam " + quoted(other.name) + ", whose adjustment has scope " +
                 "'joined', to beam " + quoted(odd.name) +
                 ": the beams joined by links are one structure with one adjustment; give " + quoted(odd.name) +
                 " the same block (omega_limit, margin, zeta_min, scope: joined)");
  }
}

BeamPointRef ModelParser::parse_beam_point(const MapView& link_view, const Field& field) const {
  const MapView view = link_view.sub(field);
  view.allow({"beam", "at"});
  BeamPointRef ref;
  const Field& beam = view.require("beam");
  const std::string beam_name = view.identifier(beam, limits_.max_name_length);
  ref.beam = beam_index(beam_name);
  if (ref.beam < 0) view.fail(beam.value_loc, view.prefixed("unknown beam " + quoted(beam_name)));
  const Field& at = view.require("at");
  ref.at = view.number(at);
  const double length = model_.beams[ref.beam].length;
  if (ref.at < 0.0 || ref.at > length) {
    view.fail(at.value_loc, view.prefixed("at must be within [0, " + format_number(length) + "], the length of beam " +
                                          quoted(beam_name) + " (got " + shown(at.value.Scalar()) + ")"));
  }
  return ref;
}

}  // namespace mbfe::frontend
