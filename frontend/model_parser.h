// The walk of one parsed YAML document into a Model (frontend/parse_model.h
// is the entry): a MapView per thing of the model, every value checked and
// every cross reference resolved. Private to the front end; its methods are
// spread over the files named for the sections they read (model_parser.cpp,
// parse_bodies.cpp, parse_spatial_bodies.cpp, parse_beams.cpp,
// parse_contacts.cpp, parse_constraints.cpp).
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <unordered_map>
#include <vector>

#include "frontend/parse_model.h"
#include "frontend/yaml_reader.h"
#include "ir/model.h"

namespace mbfe::frontend {

// The front end fills the IR: its types are used unqualified here.
using namespace mbfe::ir;

/// The name a parent takes for the ground frame; no body may take it.
constexpr const char* kGround = "ground";

/// 'name', as written (shortened, unprintable bytes escaped), for messages.
inline std::string quoted(const std::string& name) { return "'" + shown(name) + "'"; }

/// Walks one parsed YAML document into a Model.
class ModelParser {
 public:
  ModelParser(const std::string& file, const ParseLimits& limits, Model& model)
      : file_(file), limits_(limits), model_(model) {}

  void parse(const YAML::Node& root);

 private:
  /// All expressions in t together within ParseLimits::max_expression_nodes.
  void check_expression_budget(const MapView& top) const;

  // ---- names -------------------------------------------------------------

  /// Bodies and beams both name coordinates, so they share one namespace.
  void claim_coordinate_name(const MapView& view, const Field& field, const std::string& name);

  int body_index(const std::string& name) const;

  int beam_index(const std::string& name) const;

  /// A reference to an existing body by name, e.g. a load's `body:`.
  int existing_body(const MapView& view, const Field& field) const;

  int existing_point(const MapView& view, const Field& field, int body) const;

  /// The list under `field`, refused when longer than `limit`.
  std::vector<YAML::Node> bounded_list(const MapView& view, const Field& field, long limit, const char* limit_name) const;

  // ---- bodies ------------------------------------------------------------

  void parse_bodies(const MapView& top, const Field& field);

  Body parse_body(const MapView& view);

  /// Parents come before their children, which also rules out cycles.
  int parent_index(const MapView& view, const Field& field, const std::string& child) const;

  Joint parse_joint(const MapView& view);

  std::vector<NamedPoint> parse_points(const MapView& body, const Field& field);

  // ---- spatial bodies (dimension: 3) ------------------------------------

  /// The mass properties, points and joint of a body of a spatial model.
  void parse_spatial_body(const MapView& view, Body& body);

  Joint parse_spatial_joint(const MapView& view);

  /// Ixx, Iyy, Izz, Ixy, Ixz, Iyz, refused unless a physical inertia tensor.
  InertiaTensor parse_inertia_tensor(const MapView& view, const Field& field) const;

  /// The names <body>_qw, ... of a spherical or free joint's coordinates
  /// join the coordinate namespace.
  void claim_joint_coordinate_names(const MapView& view, const Field& name, const Body& body);

  /// A force or torque load of a spatial model (3-vectors, ground frame).
  void parse_spatial_load_value(const MapView& view, Load& load);

  /// Beams, contacts and links are planar only: refused at their key.
  void refuse_planar_only_sections(const MapView& top) const;

  // ---- loads on bodies ---------------------------------------------------

  void parse_loads(const MapView& top, const Field& field);

  Load parse_load(const MapView& view);

  /// The optional `name:` of a load (an identifier, unique among `names`,
  /// the loads of the same list); empty when absent.
  std::string optional_item_name(const MapView& view, std::unordered_map<std::string, SourceLoc>& names) const;

  /// The optional `start` / `stop` (s) of a load; stop after start.
  static TimeWindow time_window(const MapView& view);

  /// An optional number >= 0, 0 when absent.
  static double at_least_or(const MapView& view, const std::string& key, double minimum);

  // ---- beams -------------------------------------------------------------

  void parse_beams(const MapView& top, const Field& field);

  Beam parse_beam(const MapView& view);

  /// Element count, within the per-beam and whole-model limits.
  int parse_elements(const MapView& view, const Field& field);

  void parse_section(const MapView& view, Beam& beam);

  void parse_material(const MapView& view, Beam& beam);

  /// Node index of position `at` along the beam, which must fall on a node.
  int node_at(const MapView& view, const Field& field, const Beam& beam) const;

  std::vector<Support> parse_supports(const MapView& beam_view, const Field& field, const Beam& beam);
  std::vector<BeamPointMass> parse_point_masses(const MapView& beam_view, const Field& field, const Beam& beam);

  void parse_damping(const MapView& view, Beam& beam);

  /// Point loads into beam.loads, moving loads into beam.moving_loads.
  void parse_beam_loads(const MapView& beam_view, const Field& field, Beam& beam);

  Adjustment parse_adjustment(const MapView& view);

  /// `profile:` and `camber:` of a beam into beam.profile (parse_profile.cpp);
  /// a profile table is read here, relative to the model file.
  void parse_profile(const MapView& beam_view, Beam& beam) const;

  // ---- contacts ----------------------------------------------------------

  void parse_contacts(const MapView& top, const Field& field);
  void parse_links(const MapView& top, const Field& field);
  /// Beams joined by links share one adjustment when it has scope 'joined'.
  void check_joined_adjustments(const MapView& top) const;
  BeamPointRef parse_beam_point(const MapView& link_view, const Field& field) const;

  void parse_contact_position(const MapView& view, Contact& contact) const;

  // ---- closed loops ------------------------------------------------------

  void parse_constraints(const MapView& top, const Field& field);

  LoopEnd parse_loop_end(const MapView& loop_view, const Field& field) const;

  /// A direction of the model's dimension, normalised; zero refused.
  Vec3 unit_direction(const MapView& view, const Field& field) const;

  // ---- initial state and simulation -------------------------------------

  void parse_initial(const MapView& view);

  /// `{body_name: value, ...}` into one value per coordinate, model order:
  /// `velocities` picks v (else q). A spherical or free joint takes a list; a
  /// quaternion is stored scaled to unit length (initial.scaled_quaternions
  /// says which were not).
  void parse_coordinates(const MapView& view, std::vector<double>& values, bool velocities);

  void parse_simulation(const MapView& view);

  void check_something_moves(const MapView& top) const;

  // ---- output columns (parse_output_columns.cpp) ------------------------

  /// Every column the model's runs write has a name of its own, and `t` and
  /// `phi_abs` are the runs': a body, contact or link whose column would take
  /// another's name is refused at its name.
  void check_output_columns(const MapView& top) const;

  /// The beam whose coordinate column `column` is (B_w<k>, B_dw<k>, with or
  /// without _dot; its node k in `node`), or -1.
  int beam_of_column(const std::string& column, int& node) const;

  const std::string& file_;
  const ParseLimits& limits_;
  Model& model_;
  // Name -> index lookups, so that a model of many bodies parses in linear time.
  std::unordered_map<std::string, SourceLoc> coordinate_names_;
  std::unordered_map<std::string, int> body_by_name_;
  std::unordered_map<std::string, int> beam_by_name_;
  std::vector<std::unordered_map<std::string, int>> point_by_name_;  // per body
  std::vector<SourceLoc> contact_name_locs_, link_name_locs_;       // per contact, per link
  long long total_beam_dofs_ = 0;
};

}  // namespace mbfe::frontend
