#include "frontend/model_overrides.h"

#include <sstream>

#include "frontend/sha256.h"
#include "frontend/yaml_reader.h"

namespace mbfe::frontend {

namespace {

std::string spelled(const ir::ModelOverride& o) { return o.path + "=" + o.value; }

std::vector<std::string> split_keys(const std::string& path) {
  std::vector<std::string> keys;
  std::string key;
  std::istringstream in(path);
  while (std::getline(in, key, '.')) keys.push_back(key);
  if (!path.empty() && path.back() == '.') keys.push_back("");
  return keys;
}

/// The position of `node`, else of the nearest ancestor that has one.
ir::SourceLoc located(const YAML::Node& node, ir::SourceLoc fallback) {
  const ir::SourceLoc loc = location_of(node);
  return loc.line > 0 ? loc : fallback;
}

}  // namespace

std::vector<AppliedOverride> apply_overrides(YAML::Node root, const ir::ModelOverrides& overrides,
                                             const std::string& file) {
  std::vector<AppliedOverride> applied;
  for (const ir::ModelOverride& o : overrides) {
    const std::string flag = "--set " + shown(spelled(o));
    const auto fail = [&](ir::SourceLoc loc, const std::string& why) {
      throw ir::ModelError(file, loc, flag + ": " + why);
    };
    const std::vector<std::string> keys = split_keys(o.path);
    if (keys.empty()) fail({1, 1}, "expected PATH=VALUE with a PATH such as loads.front_susp.stiffness");
    for (const std::string& key : keys)
      if (key.empty()) fail({1, 1}, "PATH '" + shown(o.path) + "' has an empty key");
    // yaml-cpp's Node::operator= writes into the node referred to; reset()
    // moves a Node to refer to another one.
    YAML::Node node;
    node.reset(root);
    ir::SourceLoc loc = located(root, {1, 1});
    std::string where = "the model";
    for (std::size_t k = 0; k < keys.size(); ++k) {
      const std::string& key = keys[k];
      const bool last = k + 1 == keys.size();
      if (node.IsSequence()) {
        YAML::Node found;
        for (YAML::Node item : node) {
          if (item.IsMap() && item["name"] && item["name"].IsScalar() && item["name"].Scalar() == key) {
            found.reset(item);
            break;
          }
        }
        if (!found.IsDefined() || found.IsNull())
          fail(loc, where + " has no item named '" + shown(key) +
                        "' (an item of a list is reached by its name: key)");
        node.reset(found);
      } else if (node.IsMap()) {
        if (last && o.value.empty()) {  // PATH= removes the key
          if (!node[key]) fail(loc, where + " has no key '" + shown(key) + "' to remove");
          node.remove(key);
          applied.push_back({loc, spelled(o)});
          break;
        }
        if (!node[key]) {
          if (!last) fail(loc, where + " has no key '" + shown(key) + "'");
          node[key] = o.value;  // a key new to its map: the validation judges it
          applied.push_back({loc, spelled(o)});
          break;
        }
        const YAML::Node child = node[key];
        node.reset(child);
      } else {
        fail(loc, where + " is " + describe(node) + ", which has no key '" + shown(key) + "'");
      }
      loc = located(node, loc);
      where = "'" + key + "'";
      if (last) {
        if (!node.IsScalar() && !node.IsNull())
          fail(loc, "PATH leads to " + describe(node) + ", not to a single value");
        node = o.value;
        applied.push_back({loc, spelled(o)});
      }
    }
  }
  return applied;
}

ir::ModelError blame_override(const ir::ModelError& error, const std::vector<AppliedOverride>& applied) {
  // The last override written at a position is the one the file holds there.
  for (auto it = applied.rbegin(); it != applied.rend(); ++it) {
    if (it->loc.line == error.loc().line && it->loc.column == error.loc().column)
      return ir::ModelError(error.file(), error.loc(),
                            error.message() + " (the value came from --set " + shown(it->assignment) + ")");
  }
  return error;
}

std::string overridden_sha256(const std::string& text, const ir::ModelOverrides& overrides) {
  if (overrides.empty()) return sha256_hex(text);
  std::string bytes = text;
  for (const ir::ModelOverride& o : overrides) bytes += "--set " + spelled(o) + "\n";
  return sha256_hex(bytes);
}

}  // namespace mbfe::frontend
