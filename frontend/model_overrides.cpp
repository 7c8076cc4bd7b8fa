#include "frontend/model_overrides.h"

#include <algorithm>
#include <cctype>
#include <sstream>

#include "frontend/sha256.h"
#include "frontend/text_guard.h"
#include "frontend/yaml_reader.h"

namespace mbfe::frontend {

namespace {

// A flow VALUE is read under the limits of a model file's structure
// (frontend/text_guard.h): it is a few numbers, not a file.
constexpr int kMaxValueDepth = 64;
constexpr long kMaxValueValues = 100000;
constexpr std::size_t kMaxValueBytes = std::size_t{1} << 20;

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

bool is_index(const std::string& key) {
  return !key.empty() && key.size() <= 9 &&
         std::all_of(key.begin(), key.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

/// Whether a message names `key` as a word of its own ('mass', mass:, "mass must").
bool names_word(const std::string& message, const std::string& key) {
  const auto word_char = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (auto at = message.find(key); at != std::string::npos; at = message.find(key, at + 1)) {
    const bool starts = at == 0 || !word_char(message[at - 1]);
    const bool ends = at + key.size() == message.size() || !word_char(message[at + key.size()]);
    if (starts && ends) return true;
  }
  return false;
}

}  // namespace

bool is_flow_collection(const std::string& value) {
  const auto first = value.find_first_not_of(" \t");
  return first != std::string::npos && (value[first] == '[' || value[first] == '{');
}

YAML::Node override_value(const std::string& value, ir::SourceLoc at, const std::string& file,
                          const std::string& flag) {
  if (!is_flow_collection(value)) return YAML::Node(value);
  if (at.line < 1 || at.column < 1) at = {1, 1};
  const auto fail = [&](const std::string& why) { throw ir::ModelError(file, at, flag + ": VALUE " + why); };
  if (value.size() > kMaxValueBytes) fail("is more than " + std::to_string(kMaxValueBytes) + " bytes");
  if (const auto problem = find_non_text(value)) fail(problem->message);
  if (const auto problem = find_excess_structure(value, kMaxValueDepth, kMaxValueValues)) fail(problem->message);
  // Padded so that yaml-cpp marks the value where the one it replaces is:
  // messages about its items then point into the model file.
  const std::string padded = std::string(static_cast<std::size_t>(at.line - 1), '\n') +
                             std::string(static_cast<std::size_t>(at.column - 1), ' ') + value;
  YAML::Node node;
  try {
    if (find_second_document(padded)) fail("holds more than one YAML document");
    node = YAML::Load(padded);
  } catch (const YAML::Exception& e) {
    fail("is not a YAML flow list or map ([0, 300], {expression: ...}): " + (e.msg.empty() ? "invalid YAML" : e.msg));
  }
  if (!node.IsSequence() && !node.IsMap())
    fail("starts as a YAML list or map but is " + describe(node) + " (quote it to give a string)");
  return node;
}

void put_value(YAML::Node& node, const std::string& value, ir::SourceLoc at, const std::string& file,
               const std::string& flag) {
  // A scalar is written into the node, which keeps its mark (its place in
  // the file); a list or map replaces the node's contents, marks and all.
  if (is_flow_collection(value))
    node = override_value(value, at, file, flag);
  else
    node = value;
}

YAML::Node path_child(const YAML::Node& node, const std::string& key, const std::string& where, std::string& why) {
  if (node.IsSequence()) {
    bool any_map = false;
    for (const YAML::Node& item : node) {
      if (!item.IsMap()) continue;
      any_map = true;
      if (item["name"] && item["name"].IsScalar() && item["name"].Scalar() == key) return item;
    }
    if (!any_map && node.size() > 0) {
      // A list of numbers (a vector, a moving load's [fx, fy]): items by index.
      if (is_index(key) && std::stoul(key) < node.size()) return node[std::stoul(key)];
      why = where + " is " + describe(node) + ", which has no item " + shown(key) +
            " (items of a list of values are reached by their index, 0 to " + std::to_string(node.size() - 1) + ")";
      return YAML::Node(YAML::NodeType::Undefined);
    }
    why = where + " has no item named '" + shown(key) + "' (an item of a list is reached by its name: key)";
    return YAML::Node(YAML::NodeType::Undefined);
  }
  if (node.IsMap()) {
    const YAML::Node child = node[key];
    if (child) return child;
    why = where + " has no key '" + shown(key) + "'";
    return YAML::Node(YAML::NodeType::Undefined);
  }
  why = where + " is " + describe(node) + ", which has no key '" + shown(key) + "'";
  return YAML::Node(YAML::NodeType::Undefined);
}

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
    const int span = static_cast<int>(std::max<std::size_t>(o.value.size(), 1));
    // yaml-cpp's Node::operator= writes into the node referred to; reset()
    // moves a Node to refer to another one.
    YAML::Node node;
    node.reset(root);
    ir::SourceLoc loc = located(root, {1, 1});
    std::string where = "the model";
    for (std::size_t k = 0; k < keys.size(); ++k) {
      const std::string& key = keys[k];
      const bool last = k + 1 == keys.size();
      if (last && node.IsMap() && !node[key]) {
        if (o.value.empty()) fail(loc, where + " has no key '" + shown(key) + "' to remove");
        // A key new to its map: the validation judges it, at the map.
        YAML::Node added = node[key];
        put_value(added, o.value, loc, file, flag);
        applied.push_back({loc, span + 2, true, key, spelled(o)});
        break;
      }
      if (last && node.IsMap() && o.value.empty()) {  // PATH= removes the key
        node.remove(key);
        applied.push_back({loc, 1, true, key, spelled(o)});
        break;
      }
      std::string why;
      const YAML::Node child = path_child(node, key, where, why);
      if (!child.IsDefined()) fail(loc, why);
      node.reset(child);
      loc = located(node, loc);
      where = "'" + key + "'";
      if (!last) continue;
      if (o.value.empty()) fail(loc, "an empty VALUE removes a key of a map; " + where + " is an item of a list");
      if (!node.IsScalar() && !node.IsNull() && !is_flow_collection(o.value)) {
        const bool named = node.IsSequence() && node.size() > 0 && node[0].IsMap();
        fail(loc, "PATH leads to " + describe(node) +
                      ", not to a single value: give the whole of it as VALUE in YAML's flow form (" +
                      (node.IsMap() ? "{key: value, ...}) or go on to one of its keys (PATH.key)"
                       : named      ? "[{...}, ...]) or go on to one of its items by its name (PATH.<name>)"
                                    : "[a, b, ...]) or go on to one of its items by its index (PATH.0)"));
      }
      // +2: a quoted value's error columns count its quote.
      put_value(node, o.value, loc, file, flag);
      applied.push_back({loc, span + 2, false, key, spelled(o)});
    }
  }
  return applied;
}

ir::ModelError blame_override(const ir::ModelError& error, const std::vector<AppliedOverride>& applied) {
  const ir::SourceLoc at = error.loc();
  // The last override written at a position is the one the file holds there;
  // keys added to one map share its position, and the message names its key.
  const AppliedOverride* blamed = nullptr;
  for (auto it = applied.rbegin(); it != applied.rend(); ++it) {
    const bool exact = it->loc.line == at.line && it->loc.column == at.column;
    const bool within = it->loc.line == at.line && at.column >= it->loc.column && at.column < it->loc.column + it->span;
    const bool named = names_word(error.message(), it->key);
    if (!exact && !(within && (!it->added || named))) continue;
    if (named) {
      blamed = &*it;
      break;
    }
    if (!blamed) blamed = &*it;
  }
  if (!blamed) return error;
  return ir::ModelError(error.file(), error.loc(),
                        error.message() + " (the value came from --set " + shown(blamed->assignment) + ")");
}

std::string overridden_sha256(const std::string& text, const ir::ModelOverrides& overrides) {
  if (overrides.empty()) return sha256_hex(text);
  std::string bytes = text;
  for (const ir::ModelOverride& o : overrides) bytes += "--set " + spelled(o) + "\n";
  return sha256_hex(bytes);
}

}  // namespace mbfe::frontend
