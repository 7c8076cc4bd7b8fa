// Reading a model description file (YAML) into the validated model IR.
#pragma once

#include <string>

#include "ir/model.h"
#include "ir/model_error.h"
#include "ir/model_override.h"

namespace mbfe::frontend {

/// Upper bounds that keep an absurd file from exhausting the machine.
struct ParseLimits {
  std::size_t max_file_bytes = 16u << 20;  // 16 MiB
  /// A profile table (`profile: {file: ...}`): rows of s and offset, about
  /// 20 bytes each, so some 3 million rows (a 500 km line sampled every
  /// 0.25 m, or 3 km every millimetre). Read whole, and kept as doubles.
  std::size_t max_table_bytes = std::size_t{64} << 20;  // 64 MiB
  /// The generated solver of a chain of 200 bodies with a point on each
  /// compiles in about 35 s at -O3 (docs/performance.md, "Model size and
  /// compile time"); the compile grows faster than the body count.
  int max_bodies = 200;
  /// Named points of all bodies together: each gets a position kernel as
  /// long as its body's path to the ground.
  int max_points = 200;
  /// A spatial model (dimension: 3) costs more to compile per body: its
  /// bodies and their velocity coordinates (1 a revolute or prismatic joint,
  /// 3 a spherical, 6 a free one) are bounded so that the largest model
  /// allowed compiles within the planar limit's budget (docs/performance.md,
  /// "Model size and compile time").
  int max_spatial_bodies = 50;
  int max_spatial_velocities = 100;
  int max_beam_elements = 200000;   // per beam
  long max_total_beam_dofs = 2000000;
  std::size_t max_name_length = 128;
  /// Collections nested deeper than this are refused before yaml-cpp, whose
  /// recursive parser could otherwise exhaust the stack; real models nest 5.
  int max_nesting_depth = 64;
  /// YAML values (scalars and collections) in the file, estimated before
  /// yaml-cpp builds its tree, which costs it about 500 bytes and 5 us per
  /// value: 100,000 bounds the tree near 50 MB (a body takes about a dozen).
  long max_yaml_values = 100000;
  /// Numbers, names and operators of all expressions in t together (as many
  /// as one expression may hold, kMaxExpressionNodes, frontend/expression_parser.h).
  /// The loads on bodies all land in one generated function, whose compile
  /// time grows as its square: 10,000 nodes add about 5,000 operations to it.
  long max_expression_nodes = 10000;
};

/// Reads and validates `path`, with `overrides` (`--set PATH=VALUE`) written
/// into it first (frontend/model_overrides.h). @throws ir::ModelError on any
/// problem, with the position of the offending key or value; an error at a
/// value an override wrote says so.
ir::Model load_model_file(const std::string& path, const ParseLimits& limits = {},
                          const ir::ModelOverrides& overrides = {});

/// Same, from text already in memory; `display_path` is used in messages.
/// `expanded`, when given, gets the model as the solver is made from it, as
/// YAML: the overrides written in and a `train:` expanded into its bodies,
/// loads and contacts (`mbfe generate --expanded`); comments are not kept.
ir::Model parse_model_text(const std::string& text, const std::string& display_path, const ParseLimits& limits = {},
                           const ir::ModelOverrides& overrides = {}, std::string* expanded = nullptr);

/// The text of the file `path` (as load_model_file reads it: at most
/// limits.max_file_bytes, a directory or a device refused).
/// @throws ir::ModelError naming the file and why.
std::string read_model_file(const std::string& path, const ParseLimits& limits = {});

}  // namespace mbfe::frontend
