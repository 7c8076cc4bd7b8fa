// Typed, located access to a yaml-cpp tree for the model parser.
//
// Every accessor either returns a checked value or throws ModelError pointing
// at the offending key or value; no yaml-cpp conversion (`as<T>`) is used, so
// no yaml-cpp exception escapes and numbers are read the same in every locale.
#pragma once

#include <yaml-cpp/yaml.h>

#include <array>
#include <initializer_list>
#include <string>
#include <unordered_map>
#include <vector>

#include "ir/expression.h"
#include "ir/model.h"
#include "frontend/parse_model.h"

namespace mbfe::frontend {

/// 1-based location of a node, or {0, 0} when yaml-cpp has none.
ir::SourceLoc location_of(const YAML::Node& node);

/// The value as written, shortened and with unprintable bytes escaped, for
/// `(got ...)` in messages.
std::string shown(const std::string& text);

/// `node` in words for "expected ..., got <this>": `a map`, `a list of 3
/// items`, `nothing`, `the string "abc"`, `'abc'`.
std::string describe(const YAML::Node& node);

/// A number printed for a message (12 significant digits).
std::string format_number(double value);

/// One `key: value` entry of a map.
struct Field {
  std::string key;
  YAML::Node key_node;
  YAML::Node value;
  ir::SourceLoc key_loc;
  ir::SourceLoc value_loc;  // falls back to key_loc when yaml-cpp gives no mark
};

/// A YAML map seen as the fields of one thing of the model, e.g. body
/// 'link1' or its joint. `context` names the thing ("body 'link1'", empty at
/// the top level); `path` is prepended to key names in messages ("joint.").
class MapView {
 public:
  /// @throws ir::ModelError if `node` is not a map, a key is not a plain string,
  /// or a key appears twice.
  MapView(const std::string& file, const YAML::Node& node, std::string context, std::string path,
          ir::SourceLoc fallback_loc);

  /// @throws ir::ModelError at the first key not in `allowed`.
  void allow(std::initializer_list<const char*> allowed) const;

  const Field* find(const std::string& key) const;
  /// @throws ir::ModelError at the map if `key` is missing.
  const Field& require(const std::string& key) const;
  const std::vector<Field>& fields() const { return fields_; }
  ir::SourceLoc loc() const { return loc_; }

  /// A nested map under `field`, with `path` extended by the field's key.
  MapView sub(const Field& field) const;

  // Checked values. `what` in messages is path + key, e.g. "joint.at".
  double number(const Field& field) const;
  double number_at_least(const Field& field, double minimum) const;  // >= minimum
  double positive(const Field& field) const;                         // > 0
  long long whole_number(const Field& field) const;
  ir::Vec2 vec2(const Field& field) const;
  ir::Vec3 vec3(const Field& field) const;
  /// A list of exactly `count` numbers; `shape` shows it in messages ("[x, y, z]").
  std::vector<double> numbers(const Field& field, std::size_t count, const std::string& shape) const;
  std::string text(const Field& field) const;  // any scalar
  /// true / false.
  bool boolean(const Field& field) const;
  /// A number, or a string holding an expression in t
  /// (frontend/expression_parser.h), located in messages.
  /// `variable`: "t", or "s" for a profile along a beam (frontend/expression_parser.h).
  ir::Expression expression(const Field& field, const std::string& variable = "t") const;
  /// [x, y], each a number or an expression in t.
  std::array<ir::Expression, 2> expression_pair(const Field& field) const;
  /// [x, y, z], each a number or an expression in t.
  std::array<ir::Expression, 3> expression_triple(const Field& field) const;
  /// A list of exactly `count` numbers or expressions in t.
  std::vector<ir::Expression> expressions(const Field& field, std::size_t count, const std::string& shape) const;
  /// A name that may reach generated C++: identifier, not a keyword, at most
  /// `max_length` characters.
  std::string identifier(const Field& field, std::size_t max_length) const;
  /// Index of the value in `choices`.
  int choice(const Field& field, std::initializer_list<const char*> choices) const;
  /// The items of a list; a missing value (`key:` alone) is an empty list.
  std::vector<YAML::Node> list(const Field& field) const;

  // Optional fields with defaults.
  double number_or(const std::string& key, double fallback) const;
  ir::Vec2 vec2_or(const std::string& key, ir::Vec2 fallback) const;
  ir::Vec3 vec3_or(const std::string& key, ir::Vec3 fallback) const;

  /// "<context>: <message>", or the message alone at the top level.
  std::string prefixed(const std::string& message) const;
  /// Display name of a key: path + key.
  std::string what(const Field& field) const { return path_ + field.key; }
  /// "in body 'link1' joint" / "at the top level", for key errors.
  std::string where() const;

  [[noreturn]] void fail(ir::SourceLoc loc, const std::string& message) const;

 private:
  /// Item `i` of the list under `field`, as a field named key[i], located.
  Field component(const Field& field, std::size_t i) const;

  std::string file_;
  YAML::Node node_;
  std::string context_;
  std::string path_;
  ir::SourceLoc loc_;
  std::vector<Field> fields_;
  std::unordered_map<std::string, std::size_t> index_;  // key -> position in fields_
};

/// How messages name the `index`-th (0-based) item of a list of `kind`s:
/// by its `name:` when that is a valid identifier ("body 'link1'"), else by
/// position ("body #3"), so that even a key error before the name is read
/// says which item.
std::string item_context(const YAML::Node& item, const std::string& kind, std::size_t index,
                         std::size_t max_name_length);

/// Validates a name given in an identifier-like role outside a MapView (the
/// keys of `points:` and `initial.q:`). Returns the empty string when fine,
/// otherwise why not.
std::string identifier_problem(const std::string& name, std::size_t max_length);

}  // namespace mbfe::frontend
