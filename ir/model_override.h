// A value of a model file replaced before the file is validated: what
// `mbfe simulate|eval|sweep --set PATH=VALUE` and Python's
// `mbfe.load(path, set={...})` give (docs/model-format.md, "Overriding values").
#pragma once

#include <string>
#include <vector>

namespace mbfe::ir {

/// PATH addresses a key as a sweep file's `vary` paths do: keys of maps
/// joined by '.', an item of a list by its `name:`
/// (`loads.front_susp.stiffness`, `beams.bridge.section.inertia`). VALUE is a
/// YAML scalar, read as the file's own values are (a number, a word, an
/// expression in t); empty, it removes the key PATH names.
struct ModelOverride {
  std::string path;
  std::string value;
};

using ModelOverrides = std::vector<ModelOverride>;

/// "PATH=VALUE" split at its first '='; the path is empty when there is no
/// '=' (the caller says what is wrong).
ModelOverride split_override(const std::string& assignment);

}  // namespace mbfe::ir
