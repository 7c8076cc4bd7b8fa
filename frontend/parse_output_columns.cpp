// ModelParser: the names of the output columns a model's runs write must be
// distinct. A body named `t` gave a header `t,t,...`, bodies `a` and `a_dot`
// two columns `a_dot`; every reader (mbfe stats, Python, a sweep's collect)
// then picked a different one. The columns are those of
// runtime/simulation/rigid_run.cpp, beam_run.cpp and coupled_run.cpp: `t`;
// each body's coordinate, its rate `<body>_dot` and, driven, `<body>_drive`
// (a spherical or free joint: its coordinates and velocities by the names of
// ir/coordinate_layout.h, no `_dot`); `loop_residual` with closed loops;
// each beam's `<beam>_w<node>`, `<beam>_dw<node>` and their rates; in a model
// of bodies and beams `lambda_<contact>` (slider_pin), `lambda_<contact>_1`
// and `_2` (pin), `phi_abs`, `force_<contact>` and `deflection_<contact>`
// (slider_spring) and `tension_<link>`. Probes (`beam@s`) hold an `@` that no
// name has; their own duplicates are refused where they are asked for.
#include <cctype>
#include <string>
#include <unordered_map>

#include "frontend/model_parser.h"
#include "ir/coordinate_layout.h"

namespace mbfe::frontend {

namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

/// Who writes a column, for messages ("body 'a' (its rate)"), and where its
/// name is in the file ({0, 0}: nobody's name, a column every run writes).
struct ColumnOwner {
  std::string who;
  SourceLoc loc;
};

}  // namespace

int ModelParser::beam_of_column(const std::string& column, int& node) const {
  // B_w<k>, B_dw<k>, or either with _dot: k a node 0..elements, written
  // without leading zeros.
  const std::string base = ends_with(column, "_dot") ? column.substr(0, column.size() - 4) : column;
  std::size_t digits = base.size();
  while (digits > 0 && std::isdigit(static_cast<unsigned char>(base[digits - 1]))) --digits;
  const std::string number = base.substr(digits);
  if (number.empty() || number.size() > 9 || (number.size() > 1 && number[0] == '0')) return -1;
  const std::string head = base.substr(0, digits);
  const std::string beam = ends_with(head, "_dw") ? head.substr(0, head.size() - 3)
                           : ends_with(head, "_w") ? head.substr(0, head.size() - 2)
                                                   : std::string();
  const int b = beam.empty() ? -1 : beam_index(beam);
  if (b < 0) return -1;
  node = std::stoi(number);
  return node <= model_.beams[static_cast<std::size_t>(b)].elements ? b : -1;
}

void ModelParser::check_output_columns(const MapView& top) const {
  std::unordered_map<std::string, ColumnOwner> columns;
  auto claim = [&](const std::string& column, const ColumnOwner& owner) {
    if (int node = 0, beam = beam_of_column(column, node); beam >= 0) {
      top.fail(owner.loc, owner.who + " writes the column " + quoted(column) + ", which is a coordinate of beam " +
                              quoted(model_.beams[static_cast<std::size_t>(beam)].name) + " (node " +
                              std::to_string(node) + "); output columns need distinct names: rename one");
    }
    const auto [it, inserted] = columns.emplace(column, owner);
    if (inserted) return;
    if (it->second.loc.line == 0) {
      top.fail(owner.loc, owner.who + " writes the column " + quoted(column) + ", which is reserved for " +
                              it->second.who + "; choose another name");
    }
    top.fail(owner.loc, owner.who + " writes the column " + quoted(column) + ", which " + it->second.who +
                            " (line " + std::to_string(it->second.loc.line) +
                            ") writes too; output columns need distinct names: rename one");
  };
  const bool coupled = !model_.bodies.empty() && !model_.beams.empty();
  columns.emplace("t", ColumnOwner{"the time of every row", {}});
  if (coupled) columns.emplace("phi_abs", ColumnOwner{"the largest constraint residual of a model of bodies and beams", {}});
  auto name_loc = [&](const std::string& name) {
    const auto it = coordinate_names_.find(name);
    return it == coordinate_names_.end() ? SourceLoc{} : it->second;
  };
  if (!model_.constraints.empty() && model_.beams.empty())
    columns.emplace("loop_residual", ColumnOwner{"the largest loop-closure residual of a model with constraints", {}});
  for (const Body& body : model_.bodies) {
    const SourceLoc loc = name_loc(body.name);
    const JointType type = body.joint.type;
    if (type == JointType::kSpherical || type == JointType::kFree) {
      // Its coordinates and velocities by their own names, no `_dot`
      // (<body>_qw, <body>_wx, ...; ir/coordinate_layout.h), and no drive.
      for (const std::string& name : ir::position_names(type, body.name))
        claim(name, {"body " + quoted(body.name) + " (its coordinate " + quoted(name) + ")", loc});
      for (const std::string& name : ir::velocity_names(type, body.name))
        claim(name, {"body " + quoted(body.name) + " (its velocity " + quoted(name) + ")", loc});
      continue;
    }
    claim(body.name, {"body " + quoted(body.name) + " (its coordinate)", loc});
    claim(body.name + "_dot", {"body " + quoted(body.name) + " (its rate)", loc});
    if (body.joint.motion) claim(body.name + "_drive", {"body " + quoted(body.name) + " (its drive)", loc});
  }
  for (std::size_t k = 0; k < model_.contacts.size(); ++k) {
    const Contact& c = model_.contacts[k];
    const ColumnOwner owner{"contact " + quoted(c.name), contact_name_locs_[k]};
    switch (c.type) {
      case ContactType::kPin:
        claim("lambda_" + c.name + "_1", owner);
        claim("lambda_" + c.name + "_2", owner);
        break;
      case ContactType::kSliderPin: claim("lambda_" + c.name, owner); break;
      case ContactType::kSliderSpring:
        claim("force_" + c.name, owner);
        claim("deflection_" + c.name, owner);
        break;
    }
  }
  for (std::size_t k = 0; k < model_.links.size(); ++k)
    claim("tension_" + model_.links[k].name, {"link " + quoted(model_.links[k].name), link_name_locs_[k]});
}

}  // namespace mbfe::frontend
