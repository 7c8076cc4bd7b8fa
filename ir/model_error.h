// Bad user input in a model: the one error type every layer throws for it.
#pragma once

#include <stdexcept>
#include <string>

#include "ir/source_loc.h"

namespace mbfe::ir {

/// Bad user input. what() is the full message, `file:line:col: what is wrong`
/// (`file: what is wrong` when the position is unknown); the command-line tool
/// prints it and exits with status 2.
class ModelError : public std::runtime_error {
 public:
  ModelError(const std::string& file, SourceLoc loc, const std::string& message);
  const std::string& file() const { return file_; }
  SourceLoc loc() const { return loc_; }
  /// The message without the `file:line:col: ` prefix.
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  SourceLoc loc_;
  std::string message_;
};

}  // namespace mbfe::ir
