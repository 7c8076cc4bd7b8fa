// Model description file (YAML) -> validated model IR.
//
// Three stages: the raw bytes are checked (size, text, nesting depth, number
// of values) so that nothing absurd reaches yaml-cpp; yaml-cpp builds a tree, and any exception
// it throws becomes a ModelError at its mark; the tree is walked section by
// section against the schema of the model format (docs/model-format.md),
// each value checked and each cross reference resolved to an index.
#include "frontend/parse_model.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <new>
#include <sstream>
#include <unordered_map>

#include "frontend/capped_file.h"
#include "frontend/expand_train.h"
#include "frontend/model_overrides.h"
#include "frontend/model_parser.h"
#include "frontend/sha256.h"
#include "frontend/text_guard.h"
#include "frontend/yaml_reader.h"

namespace mbfe::frontend {

// The front end fills the IR: its types are used unqualified here.
using namespace mbfe::ir;

namespace {

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

Model parse_model_text(const std::string& text, const std::string& display_path, const ParseLimits& limits,
                       const ir::ModelOverrides& overrides, std::string* expanded) {
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
    const std::vector<AppliedOverride> applied = apply_overrides(root, overrides, display_path);
    Model model;
    model.source_path = display_path;
    model.source_sha256 = overridden_sha256(text, overrides);
    try {
      const SourceLoc train = expand_train(root, display_path, limits.max_name_length);
      try {
        ModelParser(display_path, limits, model).parse(root);
      } catch (const ModelError& error) {
        // What `train:` generated has no position of its own.
        if (error.loc().line > 0 || train.line == 0) throw;
        throw ModelError(display_path, train, error.message() + " (in what train: generated)");
      }
    } catch (const ModelError& error) {
      throw blame_override(error, applied);
    }
    if (expanded) {
      YAML::Emitter out;
      out << root;
      *expanded = std::string(out.c_str()) + "\n";
    }
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

Model load_model_file(const std::string& path, const ParseLimits& limits, const ir::ModelOverrides& overrides) {
  return parse_model_text(read_model_file(path, limits), path, limits, overrides);
}

std::string read_model_file(const std::string& path, const ParseLimits& limits) {
  // Refused before reading: a huge file must not be loaded into memory. A
  // pipe or special file (/dev/zero) is read to one byte past the limit.
  const CappedRead read = read_capped_file(path, limits.max_file_bytes, FileKinds::kAlsoStreams);
  if (read.fault == ReadFault::kTooLarge)
    throw ModelError(path, {1, 1}, read.why + " (ParseLimits::max_file_bytes)");
  if (!read) throw ModelError(path, {}, read.why);
  return read.text;
}

}  // namespace mbfe::frontend
