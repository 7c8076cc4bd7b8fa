// JSON as text, for files and standard output, that never fails on the bytes
// of a string: invalid UTF-8 (a path given on the command line, a message
// quoting a file's bytes) is written as U+FFFD instead of making
// nlohmann::json throw type_error.316 (which left a sweep point without its
// result file, "missing" for ever).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace mbfe {

/// `j` as text; `indent` < 0: on one line.
inline std::string json_text(const nlohmann::json& j, int indent = -1) {
  return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace mbfe
