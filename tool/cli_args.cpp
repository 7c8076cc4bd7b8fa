#include "tool/cli_args.h"

#include <map>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace mbfe::tool {

std::string request_flag(const std::string& field) {
  static const std::map<std::string, std::string> flags = {
      {"integrator", "--integrator"}, {"step", "--step"},       {"t_end", "--t-end"},
      {"every", "--every"},           {"adjust", "--adjust"},   {"probes", "--probe"},
      {"formulation", "--formulation"}, {"static_start", "--start"}, {"strict", "--strict"}};
  const auto it = flags.find(field);
  return it == flags.end() ? field : it->second;
}

ParsedArgs::ParsedArgs(const std::vector<std::string>& args, const std::set<std::string>& value_flags,
                       const std::set<std::string>& bool_flags,
                       const std::map<std::string, std::set<std::string>>& optional_value_flags) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    // "--name" or a one-letter "-o"; anything else (including "-0.5") is positional.
    const bool long_flag = arg.rfind("--", 0) == 0 && arg.size() > 2;
    const bool short_flag = arg.size() == 2 && arg[0] == '-' && std::isalpha(static_cast<unsigned char>(arg[1]));
    if (!long_flag && !short_flag) {
      positional_.push_back(arg);
      continue;
    }
    std::string name = arg.substr(long_flag ? 2 : 1);
    std::optional<std::string> inline_value;
    if (const auto eq = name.find('='); eq != std::string::npos) {
      inline_value = name.substr(eq + 1);
      name = name.substr(0, eq);
    }
    if (const auto optional = optional_value_flags.find(name); optional != optional_value_flags.end()) {
      if (inline_value)
        values_[name] = *inline_value;
      else if (i + 1 < args.size() && optional->second.count(args[i + 1]))
        values_[name] = args[++i];
      else
        values_[name] = "";
      every_value_[name].push_back(values_[name]);
    } else if (bool_flags.count(name)) {
      if (inline_value) throw UsageError("flag --" + name + " takes no value");
      bools_.insert(name);
    } else if (value_flags.count(name)) {
      if (inline_value) {
        values_[name] = *inline_value;
      } else {
        if (i + 1 >= args.size()) throw UsageError("flag --" + name + " needs a value");
        values_[name] = args[++i];
      }
      every_value_[name].push_back(values_[name]);
    } else {
      throw UsageError("unknown flag " + arg + " (see --help)");
    }
  }
}

bool ParsedArgs::has(const std::string& flag) const {
  return bools_.count(flag) > 0 || values_.count(flag) > 0;
}

std::optional<std::string> ParsedArgs::value(const std::string& flag) const {
  auto it = values_.find(flag);
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

std::vector<std::string> ParsedArgs::values(const std::string& flag) const {
  auto it = every_value_.find(flag);
  return it == every_value_.end() ? std::vector<std::string>{} : it->second;
}

ir::ModelOverrides model_overrides(const ParsedArgs& parsed) {
  ir::ModelOverrides overrides;
  for (const std::string& assignment : parsed.values("set")) {
    ir::ModelOverride o = ir::split_override(assignment);
    if (o.path.empty())
      throw UsageError("--set: expected PATH=VALUE (e.g. --set loads.front_susp.stiffness=2e6), got '" + assignment +
                       "'");
    overrides.push_back(std::move(o));
  }
  return overrides;
}

double parse_number(const std::string& text, const std::string& what) {
  if (text.empty()) throw UsageError(what + ": expected a number, got an empty string");
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || errno == ERANGE)
    throw UsageError(what + ": expected a number, got '" + text + "'");
  if (!std::isfinite(v)) throw UsageError(what + ": expected a finite number, got '" + text + "'");
  return v;
}

std::optional<double> ParsedArgs::number(const std::string& flag) const {
  auto v = value(flag);
  if (!v) return std::nullopt;
  return parse_number(*v, "--" + flag);
}

std::optional<std::vector<double>> ParsedArgs::numbers(const std::string& flag) const {
  auto v = value(flag);
  if (!v) return std::nullopt;
  std::vector<double> out;
  if (v->empty()) return out;
  std::size_t start = 0;
  while (true) {
    const auto comma = v->find(',', start);
    const std::string item = v->substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    out.push_back(parse_number(item, "--" + flag + " entry " + std::to_string(out.size() + 1)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

}  // namespace mbfe::tool
