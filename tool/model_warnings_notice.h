// The model's warnings (api/model_warnings.h: likely unit mistakes, a joint
// that moves no mass) as every command that reads a model gives them: one a
// line on stderr, before the command's own output, and under "warnings" in
// its JSON output. A warning never changes the exit status.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ir/model.h"

namespace mbfe::tool {

/// Prints each warning of `model` on stderr and returns them, in file order.
std::vector<std::string> announce_model_warnings(const ir::Model& model);

/// `warnings` as a JSON array of strings (empty array when none).
nlohmann::json warnings_json(const std::vector<std::string>& warnings);

}  // namespace mbfe::tool
