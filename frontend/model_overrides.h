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
  std::string assignment;  // "PATH=VALUE", as the user wrote it
};

/// Writes each override's value into `root` (later overrides of the same
/// PATH win). PATH follows the file's maps and, in a list, the item whose
/// `name:` is the key; its last key may be new to its map (`law` on a
/// contact that does not say it), every other key must exist. An empty VALUE
/// removes the key from its map (`contacts.tyre.stiffness=` before law hertz).
/// @throws ir::ModelError in `file` at the deepest node PATH reaches, saying
///         which key is missing and that PATH came from --set.
std::vector<AppliedOverride> apply_overrides(YAML::Node root, const ir::ModelOverrides& overrides,
                                             const std::string& file);

/// `error` with "(the value came from --set PATH=VALUE)" appended when it is
/// at the position of one of `applied`; otherwise `error` unchanged.
ir::ModelError blame_override(const ir::ModelError& error, const std::vector<AppliedOverride>& applied);

/// The SHA-256 recorded for a model read with overrides: the file's bytes,
/// then one line "--set PATH=VALUE" per override, hashed (the file's own
/// SHA-256 when there are none), so a changed value is a changed model.
std::string overridden_sha256(const std::string& text, const ir::ModelOverrides& overrides);

}  // namespace mbfe::frontend
