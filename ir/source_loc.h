// Where something was written in a model file, for error messages.
#pragma once

namespace mbfe::ir {

/// Position of a key or value in the model file; 1-based, 0 when unknown.
struct SourceLoc {
  int line = 0;
  int column = 0;
};

}  // namespace mbfe::ir
