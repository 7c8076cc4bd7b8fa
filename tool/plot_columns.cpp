#include "tool/plot_columns.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <regex>

namespace mbfe::tool {

std::map<std::string, std::string> sidecar_units(const std::string& csv_path) {
  std::map<std::string, std::string> out;
  std::error_code ec;
  // Not a device or a pipe, and no larger than a sidecar of mbfe gets (its
  // column names: tens of bytes each).
  constexpr std::uintmax_t kMaxSidecarBytes = std::uintmax_t{512} << 20;
  if (!std::filesystem::is_regular_file(csv_path + ".json", ec) ||
      std::filesystem::file_size(csv_path + ".json", ec) > kMaxSidecarBytes || ec)
    return out;
  std::ifstream in(csv_path + ".json");
  if (!in) return out;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    for (const auto& c : j.at("columns")) out[c.at("name").get<std::string>()] = c.at("unit").get<std::string>();
  } catch (const std::exception&) {
    out.clear();  // not ours, or damaged: fall back on the names
  }
  return out;
}

std::string column_unit(const std::string& column, const std::map<std::string, std::string>& sidecar) {
  if (const auto it = sidecar.find(column); it != sidecar.end()) return it->second;
  static const std::regex kRate("(.*)_dot");
  std::smatch m;
  if (std::regex_match(column, m, kRate)) {
    const std::string base = column_unit(m[1].str(), sidecar);
    if (base.empty()) return "";
    return base == "1" ? "1/s" : base + "/s";
  }
  if (column == "t") return "s";
  if (column.rfind("lambda_", 0) == 0 || column.rfind("force_", 0) == 0) return "N";
  if (column.size() > 6 && column.compare(column.size() - 6, 6, "_drive") == 0) return "N";
  if (column == "phi_abs" || column.rfind("deflection_", 0) == 0 || column.find('@') != std::string::npos) return "m";
  static const std::regex kBeamDof(".*_(d?)w[0-9]+");
  if (std::regex_match(column, m, kBeamDof)) return m[1].str().empty() ? "m" : "1";
  return "";
}

std::string quantity_of(const std::string& unit) {
  static const std::map<std::string, std::string> kQuantities = {
      {"m", "displacement"}, {"rad", "angle"},  {"N", "force"},       {"N m", "torque"},
      {"m/s", "velocity"},   {"rad/s", "angular velocity"},           {"1", "slope"},
      {"1/s", "slope rate"}, {"s", "time"},     {"m/s^2", "acceleration"}};
  const auto it = kQuantities.find(unit);
  return it == kQuantities.end() ? "value" : it->second;
}

std::vector<std::vector<std::size_t>> panels_by_unit(const std::vector<std::size_t>& columns,
                                                     const std::vector<std::string>& units) {
  std::vector<std::vector<std::size_t>> panels;
  std::vector<std::string> keys;
  for (std::size_t c : columns) {
    std::size_t k = 0;
    while (k < keys.size() && keys[k] != units[c]) ++k;
    if (k == keys.size()) {
      keys.push_back(units[c]);
      panels.emplace_back();
    }
    panels[k].push_back(c);
  }
  return panels;
}

}  // namespace mbfe::tool
