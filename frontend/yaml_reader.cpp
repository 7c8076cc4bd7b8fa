#include "frontend/yaml_reader.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <system_error>

#include "frontend/expression_parser.h"
#include "frontend/text_guard.h"
#include "ir/identifiers.h"

namespace mbfe::frontend {

// The front end fills the IR: its types are used unqualified here.
using namespace mbfe::ir;
namespace {

// Long enough to recognise a value, short enough to keep a message on a line.
constexpr std::size_t kMaxShownChars = 40;

/// yaml-cpp tags a quoted scalar "!" and a plain one "?"; only plain scalars
/// can be numbers.
bool is_quoted(const YAML::Node& node) { return node.Tag() == "!"; }

std::string join(std::initializer_list<const char*> words) {
  std::string out;
  for (const char* word : words) {
    if (!out.empty()) out += ", ";
    out += word;
  }
  return out;
}

/// Parses a YAML plain scalar as a double, locale-independently.
/// Returns false (with `why`) when it is not a number or not finite.
bool parse_double(const std::string& text, double& value, std::string& why) {
  std::string_view digits(text);
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (digits.empty() || end != digits.data() + digits.size() ||
      error == std::errc::invalid_argument) {
    const bool yaml_special = text == ".nan" || text == ".NaN" || text == ".NAN" ||
                              text.find(".inf") != std::string::npos ||
                              text.find(".Inf") != std::string::npos ||
                              text.find(".INF") != std::string::npos;
    why = yaml_special ? "a finite number" : "a number";
    return false;
  }
  if (error == std::errc::result_out_of_range) {
    why = "a finite number within the range of a double";
    return false;
  }
  if (!std::isfinite(value)) {  // from_chars reads "nan" and "inf" too
    why = "a finite number";
    return false;
  }
  return true;
}

}  // namespace

SourceLoc location_of(const YAML::Node& node) {
  if (!node.IsDefined()) return {};
  const YAML::Mark mark = node.Mark();
  if (mark.is_null() || mark.line < 0 || mark.column < 0) return {};
  return {mark.line + 1, mark.column + 1};
}

std::string shown(const std::string& text) {
  std::string out;
  // Never half a UTF-8 character: the message may end up in JSON.
  const std::string head = utf8_prefix(text, kMaxShownChars);
  for (const char byte : head) {
    const auto c = static_cast<unsigned char>(byte);
    if (c < 0x20 || c == 0x7F) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02X", c);
      out += escaped;
    } else {
      out += static_cast<char>(c);
    }
  }
  if (text.size() > kMaxShownChars) {
    out += "... (" + std::to_string(text.size()) + " characters)";
  }
  return out;
}

std::string describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Map:
      return "a map";
    case YAML::NodeType::Sequence:
      return "a list of " + std::to_string(node.size()) + " item" + (node.size() == 1 ? "" : "s");
    case YAML::NodeType::Scalar:
      return is_quoted(node) ? "the string \"" + shown(node.Scalar()) + "\""
                             : "'" + shown(node.Scalar()) + "'";
    case YAML::NodeType::Null:
    case YAML::NodeType::Undefined:
      break;
  }
  return "nothing";
}

std::string format_number(double value) {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out.precision(12);
  out << value;
  return out.str();
}

std::string item_context(const YAML::Node& item, const std::string& kind, std::size_t index,
                         std::size_t max_name_length) {
  if (item.IsMap()) {
    for (auto it = item.begin(); it != item.end(); ++it) {
      if (it->first.IsScalar() && it->first.Scalar() == "name" && it->second.IsScalar() &&
          identifier_problem(it->second.Scalar(), max_name_length).empty()) {
        return kind + " '" + it->second.Scalar() + "'";
      }
    }
  }
  return kind + " #" + std::to_string(index + 1);
}

std::string identifier_problem(const std::string& name, std::size_t max_length) {
  if (name.size() > max_length) {
    return "is " + std::to_string(name.size()) + " characters long, more than the limit of " +
           std::to_string(max_length);
  }
  if (!is_identifier(name)) {
    return "is not an identifier (letters, digits and '_', not starting with a digit)";
  }
  if (is_reserved_in_cpp(name)) return "is reserved in C++";
  return {};
}

MapView::MapView(const std::string& file, const YAML::Node& node, std::string context,
                 std::string path, SourceLoc fallback_loc)
    : file_(file), node_(node), context_(std::move(context)), path_(std::move(path)) {
  loc_ = location_of(node);
  if (loc_.line == 0) loc_ = fallback_loc;
  if (!node.IsMap()) {
    const std::string what =
        path_.empty() ? std::string("the model file") : path_.substr(0, path_.size() - 1);
    fail(loc_, prefixed(what + ": expected a map of keys, got " + describe(node)));
  }
  for (auto it = node.begin(); it != node.end(); ++it) {
    Field field;
    field.key_node = it->first;
    field.value = it->second;
    field.key_loc = location_of(field.key_node);
    if (field.key_loc.line == 0) field.key_loc = loc_;
    // yaml-cpp marks an empty value (`mass:` alone) at the next token, often
    // on a later line; the key is the place to point at.
    field.value_loc = field.value.IsNull() ? SourceLoc{} : location_of(field.value);
    if (field.value_loc.line == 0) field.value_loc = field.key_loc;
    if (!field.key_node.IsScalar()) {
      fail(field.key_loc, "expected a plain key " + where() + ", got " + describe(field.key_node));
    }
    field.key = field.key_node.Scalar();
    // A hash, not a scan: `points:` or `initial.q:` may hold many keys.
    const auto [earlier, inserted] = index_.emplace(field.key, fields_.size());
    if (!inserted) {
      fail(field.key_loc, "duplicate key '" + shown(field.key) + "' " + where() +
                              " (first given at line " +
                              std::to_string(fields_[earlier->second].key_loc.line) + ")");
    }
    fields_.push_back(std::move(field));
  }
}

void MapView::allow(std::initializer_list<const char*> allowed) const {
  for (const Field& field : fields_) {
    bool known = false;
    for (const char* key : allowed) known = known || field.key == key;
    if (!known) {
      fail(field.key_loc, "unknown key '" + shown(field.key) + "' " + where() +
                              " (expected one of: " + join(allowed) + ")");
    }
  }
}

const Field* MapView::find(const std::string& key) const {
  const auto it = index_.find(key);
  return it == index_.end() ? nullptr : &fields_[it->second];
}

const Field& MapView::require(const std::string& key) const {
  if (const Field* field = find(key)) return *field;
  fail(loc_, prefixed("missing required key '" + path_ + key + "'"));
}

MapView MapView::sub(const Field& field) const {
  return MapView(file_, field.value, context_, path_ + field.key + ".", field.value_loc);
}

double MapView::number(const Field& field) const {
  const YAML::Node& value = field.value;
  double result = 0.0;
  std::string expected = "a number";
  if (value.IsScalar() && !is_quoted(value) && parse_double(value.Scalar(), result, expected)) {
    return result;
  }
  fail(field.value_loc,
       prefixed(what(field) + ": expected " + expected + ", got " + describe(value)));
}

double MapView::number_at_least(const Field& field, double minimum) const {
  const double value = number(field);
  if (!(value >= minimum)) {
    fail(field.value_loc, prefixed(what(field) + " must be >= " + format_number(minimum) +
                                   " (got " + shown(field.value.Scalar()) + ")"));
  }
  return value;
}

double MapView::positive(const Field& field) const {
  const double value = number(field);
  if (!(value > 0.0)) {
    fail(field.value_loc,
         prefixed(what(field) + " must be > 0 (got " + shown(field.value.Scalar()) + ")"));
  }
  return value;
}

long long MapView::whole_number(const Field& field) const {
  const double value = number(field);
  // 2^53: beyond it doubles skip integers; far beyond every limit anyway.
  constexpr double kLargestExact = 9007199254740992.0;
  if (value != std::floor(value) || std::fabs(value) > kLargestExact) {
    fail(field.value_loc,
         prefixed(what(field) + ": expected a whole number, got " + shown(field.value.Scalar())));
  }
  return static_cast<long long>(value);
}

Field MapView::component(const Field& field, std::size_t i) const {
  Field component{field.key + "[" + std::to_string(i) + "]", field.key_node, field.value[i], field.key_loc,
                  location_of(field.value[i])};
  if (component.value_loc.line == 0) component.value_loc = field.value_loc;
  return component;
}

std::vector<double> MapView::numbers(const Field& field, std::size_t count, const std::string& shape) const {
  const YAML::Node& value = field.value;
  if (!value.IsSequence() || value.size() != count) {
    fail(field.value_loc, prefixed(what(field) + ": expected a list of " + std::to_string(count) + " numbers " +
                                   shape + ", got " + describe(value)));
  }
  std::vector<double> result(count);
  for (std::size_t i = 0; i < count; ++i) result[i] = number(component(field, i));
  return result;
}

Vec2 MapView::vec2(const Field& field) const {
  const std::vector<double> v = numbers(field, 2, "[x, y]");
  return {v[0], v[1]};
}

ir::Vec3 MapView::vec3(const Field& field) const {
  const std::vector<double> v = numbers(field, 3, "[x, y, z]");
  return {v[0], v[1], v[2]};
}

bool MapView::boolean(const Field& field) const {
  const YAML::Node& value = field.value;
  if (value.IsScalar() && !is_quoted(value)) {
    if (value.Scalar() == "true") return true;
    if (value.Scalar() == "false") return false;
  }
  fail(field.value_loc, prefixed(what(field) + ": expected true or false, got " + describe(value)));
}

ir::Expression MapView::expression(const Field& field, const std::string& variable) const {
  const YAML::Node& value = field.value;
  if (!value.IsScalar()) {
    fail(field.value_loc, prefixed(what(field) + ": expected a number or an expression in " + variable + ", got " +
                                   describe(value)));
  }
  double number = 0.0;
  std::string why;
  if (!is_quoted(value) && parse_double(value.Scalar(), number, why)) {
    return ir::Expression::number(number, field.value_loc);
  }
  ir::SourceLoc start = field.value_loc;
  if (is_quoted(value) && start.line > 0) ++start.column;  // past the opening quote
  const std::string prefix = context_.empty() ? what(field) : context_ + ": " + what(field);
  return parse_expression(value.Scalar(), file_, start, prefix, variable);
}

std::vector<ir::Expression> MapView::expressions(const Field& field, std::size_t count,
                                                const std::string& shape) const {
  const YAML::Node& value = field.value;
  if (!value.IsSequence() || value.size() != count) {
    fail(field.value_loc, prefixed(what(field) + ": expected a list of " + std::to_string(count) + " values " +
                                   shape + ", got " + describe(value)));
  }
  std::vector<ir::Expression> result;
  for (std::size_t i = 0; i < count; ++i) result.push_back(expression(component(field, i)));
  return result;
}

std::array<ir::Expression, 2> MapView::expression_pair(const Field& field) const {
  std::vector<ir::Expression> e = expressions(field, 2, "[x, y]");
  return {std::move(e[0]), std::move(e[1])};
}

std::array<ir::Expression, 3> MapView::expression_triple(const Field& field) const {
  std::vector<ir::Expression> e = expressions(field, 3, "[x, y, z]");
  return {std::move(e[0]), std::move(e[1]), std::move(e[2])};
}

std::string MapView::text(const Field& field) const {
  if (!field.value.IsScalar()) {
    fail(field.value_loc,
         prefixed(what(field) + ": expected a string, got " + describe(field.value)));
  }
  return field.value.Scalar();
}

std::string MapView::identifier(const Field& field, std::size_t max_length) const {
  if (!field.value.IsScalar()) {
    fail(field.value_loc,
         prefixed(what(field) + ": expected a name, got " + describe(field.value)));
  }
  const std::string name = field.value.Scalar();
  const std::string problem = identifier_problem(name, max_length);
  if (!problem.empty()) {
    fail(field.value_loc, prefixed(what(field) + " '" + shown(name) + "' " + problem));
  }
  return name;
}

int MapView::choice(const Field& field, std::initializer_list<const char*> choices) const {
  if (field.value.IsScalar()) {
    int index = 0;
    for (const char* option : choices) {
      if (field.value.Scalar() == option) return index;
      ++index;
    }
  }
  fail(field.value_loc, prefixed(what(field) + ": expected one of " + join(choices) + ", got " +
                                 describe(field.value)));
}

std::vector<YAML::Node> MapView::list(const Field& field) const {
  if (field.value.IsNull()) return {};
  if (!field.value.IsSequence()) {
    fail(field.value_loc,
         prefixed(what(field) + ": expected a list, got " + describe(field.value)));
  }
  std::vector<YAML::Node> items;
  items.reserve(field.value.size());
  for (const YAML::Node& item : field.value) items.push_back(item);
  return items;
}

double MapView::number_or(const std::string& key, double fallback) const {
  const Field* field = find(key);
  return field ? number(*field) : fallback;
}

Vec2 MapView::vec2_or(const std::string& key, Vec2 fallback) const {
  const Field* field = find(key);
  return field ? vec2(*field) : fallback;
}

ir::Vec3 MapView::vec3_or(const std::string& key, ir::Vec3 fallback) const {
  const Field* field = find(key);
  return field ? vec3(*field) : fallback;
}

std::string MapView::prefixed(const std::string& message) const {
  return context_.empty() ? message : context_ + ": " + message;
}

std::string MapView::where() const {
  const std::string sub_path = path_.empty() ? "" : path_.substr(0, path_.size() - 1);
  if (context_.empty()) return sub_path.empty() ? "at the top level" : "in " + sub_path;
  return "in " + context_ + (sub_path.empty() ? "" : " " + sub_path);
}

void MapView::fail(SourceLoc loc, const std::string& message) const {
  throw ModelError(file_, loc, message);
}

}  // namespace mbfe::frontend
