// Checks on the raw bytes of a model file, made before yaml-cpp sees them.
//
// yaml-cpp parses nested collections recursively, so a file of a million `[`
// could exhaust the stack; it also takes any bytes. This scan rejects what is
// not text, what nests absurdly deep and what would make yaml-cpp allocate
// gigabytes, cheaply and without recursion.
#pragma once

#include <optional>
#include <string>

#include "ir/model.h"

namespace mbfe::frontend {

/// Why a text must not be handed to the YAML parser, and where.
struct TextProblem {
  ir::SourceLoc loc;  // 1-based line and byte column
  std::string message;
};

/// Returns the first byte that makes `text` not a text file: a NUL or other
/// control character (tab, LF and CR are fine) or a malformed UTF-8 sequence.
std::optional<TextProblem> find_non_text(const std::string& text);

/// The first at most `max_bytes` bytes of `text`, fewer when that would cut a
/// UTF-8 sequence in two: what a message shows of a long value stays valid
/// UTF-8 (JSON writers and Python refuse anything else).
std::string utf8_prefix(const std::string& text, std::size_t max_bytes);

/// Returns the first place where collections nest deeper than `max_depth`,
/// counting flow brackets `[` `{`, block indentation levels and compact
/// sequence dashes (`- - x`), or where the file holds more than `max_values`
/// YAML values (yaml-cpp spends about 500 bytes on each: a 16 MiB file of
/// `0,0,0,...` would take 4 GB). A heuristic scanner, not a YAML parser:
/// quoted strings, comments and block scalars are skipped so that brackets in
/// text do not count; values are estimated from their separators (`,` `:` `-`
/// `[` `{`), which over-counts only a little.
std::optional<TextProblem> find_excess_structure(const std::string& text, int max_depth,
                                                 long max_values);

/// Returns where a second YAML document starts: a `---` line after content,
/// or content after a `...` line. yaml-cpp's LoadAll, which could tell, loops
/// without end allocating memory on some inputs (a document that starts with
/// `,`; yaml-cpp issue #1040, fixed after 0.7), so the parser loads one
/// document with Load, which is safe, and asks this scan about the rest.
std::optional<ir::SourceLoc> find_second_document(const std::string& text);

}  // namespace mbfe::frontend
