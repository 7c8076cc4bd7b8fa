// A small, strict command-line reader shared by the subcommands.
//
// Flags are `--name value` or `--name=value`; boolean flags take no value.
// Anything unknown is an error (exit status 2), never silently ignored.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "ir/model_override.h"

namespace mbfe::tool {

/// Bad flags or values on the command line; printed as `mbfe <cmd>: <what>`.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The flag that sets a field of a runtime::SimulationRequest ("step" ->
/// "--step", "t_end" -> "--t-end", "probes" -> "--probe"); the field's own
/// name for one no flag sets.
std::string request_flag(const std::string& field);

class ParsedArgs {
 public:
  /// @param value_flags flags that take a value (without the leading "--").
  /// @param bool_flags flags that take none.
  /// @param optional_value_flags flags whose value may be left out: each
  ///        takes the next argument only when it is one of its choices
  ///        (`--en1990 direct`; `--en1990 --lowpass 30` and `--en1990 acc.csv`
  ///        leave it bare), or a value written `--flag=value`; bare, its
  ///        value() is the empty string.
  /// @throws UsageError on an unknown flag or a missing value.
  ParsedArgs(const std::vector<std::string>& args, const std::set<std::string>& value_flags,
             const std::set<std::string>& bool_flags,
             const std::map<std::string, std::set<std::string>>& optional_value_flags = {});

  bool has(const std::string& flag) const;
  /// The last value given for `flag`.
  std::optional<std::string> value(const std::string& flag) const;
  /// Every value given for a repeatable flag (`--set A=1 --set B=2`), in order.
  std::vector<std::string> values(const std::string& flag) const;
  /// The value parsed as a finite double. @throws UsageError otherwise.
  std::optional<double> number(const std::string& flag) const;
  /// Comma-separated finite doubles ("0.1,0.2"). @throws UsageError otherwise.
  std::optional<std::vector<double>> numbers(const std::string& flag) const;
  const std::vector<std::string>& positional() const { return positional_; }

 private:
  std::map<std::string, std::string> values_;
  std::map<std::string, std::vector<std::string>> every_value_;
  std::set<std::string> bools_;
  std::vector<std::string> positional_;
};

/// The `--set PATH=VALUE` flags, in order. @throws UsageError for one
/// without '=' or with an empty PATH.
ir::ModelOverrides model_overrides(const ParsedArgs& parsed);

/// Parses a finite double; `what` names it in the error message.
double parse_number(const std::string& text, const std::string& what);

}  // namespace mbfe::tool
