#include "ir/model_error.h"

namespace mbfe::ir {

ModelError::ModelError(const std::string& file, SourceLoc loc, const std::string& message)
    : std::runtime_error(loc.line > 0 ? file + ":" + std::to_string(loc.line) + ":" +
                                            std::to_string(loc.column) + ": " + message
                                      : file + ": " + message),
      file_(file),
      loc_(loc),
      message_(message) {}

}  // namespace mbfe::ir
