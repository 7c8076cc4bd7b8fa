// Reading a model description file (YAML) into the validated model IR.
#pragma once

#include <string>

#include "ir/model.h"
#include "ir/model_error.h"

namespace mbfe::frontend {

/// Upper bounds that keep an absurd file from exhausting the machine.
struct ParseLimits {
  std::size_t max_file_bytes = 16u << 20;  // 16 MiB
  int max_bodies = 2000;
  int max_beam_elements = 200000;   // per beam
  long max_total_beam_dofs = 2000000;
  std::size_t max_name_length = 128;
  /// Collections nested deeper than this are refused before yaml-cpp, whose
  /// recursive parser could otherwise exhaust the stack; real models nest 5.
  int max_nesting_depth = 64;
  /// YAML values (scalars and collections) in the file, estimated before
  /// yaml-cpp builds its tree, which costs it about 500 bytes and 5 us per
  /// value: 100,000 is twice a 2000-body model and bounds the tree near 50 MB.
  long max_yaml_values = 100000;
  /// Numbers, names and operators of all expressions in t together (one
  /// expression holds at most kMaxExpressionNodes, frontend/expression_parser.h):
  /// ten of the largest, whose generated code compiles in about 30 s.
  long max_expression_nodes = 100000;
};

/// Reads and validates `path`. @throws ir::ModelError on any problem, with the
/// position of the offending key or value.
ir::Model load_model_file(const std::string& path, const ParseLimits& limits = {});

/// Same, from text already in memory; `display_path` is used in messages.
ir::Model parse_model_text(const std::string& text, const std::string& display_path,
                       const ParseLimits& limits = {});

}  // namespace mbfe::frontend
