// ModelParser: contacts between a body vertex and a beam.
#include "frontend/model_parser.h"

#include <cmath>

namespace mbfe::frontend {

void ModelParser::parse_contacts(const MapView& top, const Field& field) {
  const auto items = top.list(field);
  std::unordered_map<std::string, SourceLoc> names;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const MapView view(file_, items[i],
                       item_context(items[i], "contact", i, limits_.max_name_length), "",
                       field.value_loc);
    view.allow({"name", "type", "body", "point", "beam", "at", "stiffness", "damping", "unilateral"});
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
      contact.stiffness = view.positive(view.require("stiffness"));
      contact.damping = at_least_or(view, "damping", 0.0);
      if (const Field* u = view.find("unilateral")) contact.unilateral = view.boolean(*u);
    } else {
      for (const char* key : {"stiffness", "damping", "unilateral"}) {
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

}  // namespace mbfe::frontend
