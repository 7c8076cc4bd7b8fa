// What the front end says of a model text: the what() of the ModelError that
// parsing it throws (file:line:col: what is wrong), or "(accepted)". The
// front end's tests compare it with exact messages.
#pragma once

#include <string>

#include "frontend/parse_model.h"
#include "ir/model_error.h"
#include "ir/model_override.h"

namespace mbfe::test {

inline std::string model_error_of(const std::string& text, const std::string& display_path = "models/x.yaml",
                                  const frontend::ParseLimits& limits = {}, const ir::ModelOverrides& overrides = {}) {
  try {
    frontend::parse_model_text(text, display_path, limits, overrides);
  } catch (const ir::ModelError& error) {
    return error.what();
  }
  return "(accepted)";
}

}  // namespace mbfe::test
