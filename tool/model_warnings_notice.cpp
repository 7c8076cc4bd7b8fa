#include "tool/model_warnings_notice.h"

#include <iostream>

#include "api/model_warnings.h"

namespace mbfe::tool {

std::vector<std::string> announce_model_warnings(const ir::Model& model) {
  std::vector<std::string> warnings = model_warnings(model);
  for (const std::string& w : warnings) std::cerr << w << "\n";
  return warnings;
}

nlohmann::json warnings_json(const std::vector<std::string>& warnings) {
  nlohmann::json out = nlohmann::json::array();
  for (const std::string& w : warnings) out.push_back(w);
  return out;
}

}  // namespace mbfe::tool
