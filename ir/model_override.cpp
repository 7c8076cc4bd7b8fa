#include "ir/model_override.h"

namespace mbfe::ir {

ModelOverride split_override(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos) return {"", assignment};
  return {assignment.substr(0, eq), assignment.substr(eq + 1)};
}

}  // namespace mbfe::ir
