// `--set PATH=VALUE` put into a model's YAML tree before the tree is
// validated, so that every error still points into the model file.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "ir/model_error.h"
#include "ir/model_override.h"

namespace mbfe::frontend {

/// Where an override landed in the file: the position of the value it
/// replaced, or of the map it added its key to.
struct AppliedOverride {
  ir::SourceLoc loc;
  /// Columns loc.column .. loc.column + span - 1 of loc.line hold the value
  /// as far as messages are concerned: an expression's error points inside
  /// it, an item of a list VALUE at its own column.
  int span = 1;
  /// A key added to a map (or removed from it): loc is the map's, which its
  /// other keys share, so a message there is this override's only when it
  /// names the key, or is exactly at loc.
  bool added = false;
  std::string key;         // PATH's last key: what a message about it names
  std::string assignment;  // "PATH=VALUE", as the user wrote it
};

/// Whether VALUE is a YAML flow list or map (`[0, 300]`, `{expression: ...}`):
/// its first character that is not a space is `[` or `{`. Any other VALUE is
/// one scalar, taken as written (`20*t`, `hertz`, `2e6`).
bool is_flow_collection(const std::string& value);

/// VALUE as the YAML node it stands for. A flow list or map is read as YAML
/// whose marks lie at `at` and after (so that a message about one of its items
/// points into the file where the value it replaced was); a scalar is the text.
/// @throws ir::ModelError in `file` at `at`, naming `flag`, when a flow VALUE
///         is not one YAML list or map (or is beyond the limits of a file).
YAML::Node override_value(const std::string& value, ir::SourceLoc at, const std::string& file, const std::string& flag);

/// Writes VALUE into `node`: a scalar into the node itself, which keeps its
/// place in the file; a flow list or map (override_value, marked at `at`) in
/// place of what the node held. @throws ir::ModelError as override_value.
void put_value(YAML::Node& node, const std::string& value, ir::SourceLoc at, const std::string& file,
               const std::string& flag);

/// The node `key` leads to from `node`: a map's value under `key`; in a list
/// of maps, the item whose `name:` is `key`; in a list of other values
/// (numbers, strings, lists), the item at index `key` (0, 1, ...). An
/// undefined node when there is none, with `why` saying so ("has no item
/// named 'x' (...)", "has no key 'x'", "has 2 items, no item 1... ").
/// `where` names `node` in `why` ("'loads'", "the model").
YAML::Node path_child(const YAML::Node& node, const std::string& key, const std::string& where, std::string& why);

/// Writes each override's value into `root` (later overrides of the same
/// PATH win). PATH follows the file's maps and, in a list, the item whose
/// `name:` is the key (or, in a list of numbers, its index); its last key may
/// be new to its map (`law` on a contact that does not say it), every other key
/// must exist. An empty VALUE removes the key from its map
/// (`contacts.tyre.stiffness=` before law hertz); a flow list or map replaces
/// a list or map (or a value) whole.
/// @throws ir::ModelError in `file` at the deepest node PATH reaches, saying
///         which key is missing and that PATH came from --set.
std::vector<AppliedOverride> apply_overrides(YAML::Node root, const ir::ModelOverrides& overrides,
                                             const std::string& file);

/// `error` with "(the value came from --set PATH=VALUE)" appended when it is
/// at the position of one of `applied` (within its span); otherwise `error`
/// unchanged. Of several overrides there (keys added to one map), the last
/// whose key the message names as a word, else the last.
ir::ModelError blame_override(const ir::ModelError& error, const std::vector<AppliedOverride>& applied);

/// The SHA-256 recorded for a model read with overrides: the file's bytes,
/// then one line "--set PATH=VALUE" per override, hashed (the file's own
/// SHA-256 when there are none), so a changed value is a changed model.
std::string overridden_sha256(const std::string& text, const ir::ModelOverrides& overrides);

}  // namespace mbfe::frontend
