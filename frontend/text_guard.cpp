#include "frontend/text_guard.h"

#include <cstdint>
#include <vector>

namespace mbfe::frontend {

// The front end fills the IR: its types are used unqualified here.
using namespace mbfe::ir;
namespace {

std::string hex_byte(unsigned char byte) {
  static const char kHex[] = "0123456789ABCDEF";
  return std::string("0x") + kHex[byte >> 4] + kHex[byte & 0x0f];
}

/// Length of the UTF-8 sequence starting at text[i], or 0 when malformed
/// (overlong forms, surrogates and code points above U+10FFFF included).
std::size_t utf8_sequence_length(const std::string& text, std::size_t i) {
  const auto byte = [&](std::size_t k) -> unsigned {
    return k < text.size() ? static_cast<unsigned char>(text[k]) : 0u;
  };
  const auto continuation = [&](std::size_t k, unsigned lo = 0x80, unsigned hi = 0xBF) {
    return byte(k) >= lo && byte(k) <= hi;
  };
  const unsigned b0 = byte(i);
  if (b0 < 0x80) return 1;
  if (b0 >= 0xC2 && b0 <= 0xDF) return continuation(i + 1) ? 2 : 0;
  if (b0 == 0xE0) return continuation(i + 1, 0xA0) && continuation(i + 2) ? 3 : 0;
  if (b0 == 0xED) return continuation(i + 1, 0x80, 0x9F) && continuation(i + 2) ? 3 : 0;
  if (b0 >= 0xE1 && b0 <= 0xEF) return continuation(i + 1) && continuation(i + 2) ? 3 : 0;
  if (b0 == 0xF0) {
    return continuation(i + 1, 0x90) && continuation(i + 2) && continuation(i + 3) ? 4 : 0;
  }
  if (b0 >= 0xF1 && b0 <= 0xF3) {
    return continuation(i + 1) && continuation(i + 2) && continuation(i + 3) ? 4 : 0;
  }
  if (b0 == 0xF4) {
    return continuation(i + 1, 0x80, 0x8F) && continuation(i + 2) && continuation(i + 3) ? 4 : 0;
  }
  return 0;
}

bool is_allowed_control(unsigned char c) { return c == '\t' || c == '\n' || c == '\r'; }

/// Characters after which `[`, `{` or a quote opens a new node in block
/// context (start of line is '\n').
bool opens_node_after(char last) {
  return last == '\n' || last == ':' || last == '-' || last == '?' || last == ',' || last == '[' ||
         last == '{';
}

}  // namespace

std::string utf8_prefix(const std::string& text, std::size_t max_bytes) {
  if (text.size() <= max_bytes) return text;
  std::size_t end = max_bytes;
  // Back over continuation bytes (10xxxxxx) to the lead byte of the sequence
  // the cut falls in, and cut before it.
  while (end > 0 && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80) --end;
  return text.substr(0, end);
}

std::optional<TextProblem> find_non_text(const std::string& text) {
  int line = 1;
  int column = 1;
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == 0) {
      return TextProblem{{line, column}, "not a text file: NUL byte"};
    }
    if ((c < 0x20 && !is_allowed_control(c)) || c == 0x7F) {
      return TextProblem{{line, column}, "not a text file: control character " + hex_byte(c)};
    }
    const std::size_t length = utf8_sequence_length(text, i);
    if (length == 0) {
      return TextProblem{{line, column},
                         "not a text file: invalid UTF-8 (byte " + hex_byte(c) + ")"};
    }
    if (c == '\n') {
      ++line;
      column = 1;
    } else {
      column += static_cast<int>(length);
    }
    i += length;
  }
  return std::nullopt;
}

std::optional<TextProblem> find_excess_structure(const std::string& text, int max_depth,
                                                 long max_values) {
  const auto too_deep = [&](int line, int column, int depth) {
    return TextProblem{{line, column},
                       "collections nest " + std::to_string(depth) +
                           " levels deep here, more than the limit of " +
                           std::to_string(max_depth)};
  };
  // Counting goes on past the limit so that the message can say how many.
  long values = 0;  // estimated from separators; each opens at most one value
  SourceLoc limit_crossed;
  const auto count_value = [&](int line, std::size_t column) {
    if (++values == max_values + 1) limit_crossed = {line, static_cast<int>(column) + 1};
  };
  std::vector<int> block_indents;  // strictly increasing indentation levels
  int flow_depth = 0;
  char quote = 0;                // the open quote character, 0 when none
  int block_scalar_indent = -1;  // >= 0 while inside a `|` or `>` block scalar
  int line = 0;
  std::size_t pos = 0;
  while (pos <= text.size() && (pos < text.size() || line == 0)) {
    ++line;
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    const std::string_view row(text.data() + pos, end - pos);
    pos = end + 1;

    std::size_t indent = 0;
    while (indent < row.size() && row[indent] == ' ') ++indent;
    const bool blank = indent == row.size() || row[indent] == '\r' || row[indent] == '#';
    if (block_scalar_indent >= 0) {
      if (blank || static_cast<int>(indent) > block_scalar_indent) continue;
      block_scalar_indent = -1;
    }
    if (blank && quote == 0) continue;

    std::size_t i = 0;
    if (quote == 0 && flow_depth == 0) {
      // Block context: indentation levels, then compact sequence dashes.
      while (!block_indents.empty() && block_indents.back() > static_cast<int>(indent)) {
        block_indents.pop_back();
      }
      if (block_indents.empty() || block_indents.back() < static_cast<int>(indent)) {
        block_indents.push_back(static_cast<int>(indent));
      }
      int depth = static_cast<int>(block_indents.size());
      i = indent;
      while (i < row.size() && row[i] == '-' &&
             (i + 1 == row.size() || row[i + 1] == ' ' || row[i + 1] == '\r')) {
        if (++depth > max_depth) return too_deep(line, static_cast<int>(i) + 1, depth);
        count_value(line, i);
        i += 2;
        while (i < row.size() && row[i] == ' ') ++i;
      }
      if (depth > max_depth) return too_deep(line, static_cast<int>(indent) + 1, depth);
    }

    const int base_depth = static_cast<int>(block_indents.size());
    char last = '\n';  // last significant character on this line
    char previous = ' ';
    for (; i < row.size(); previous = row[i], ++i) {
      const char c = row[i];
      if (quote != 0) {
        if (quote == '"' && c == '\\') {
          ++i;  // skip the escaped character
        } else if (c == quote) {
          if (quote == '\'' && i + 1 < row.size() && row[i + 1] == '\'') {
            ++i;  // '' inside a single-quoted string
          } else {
            quote = 0;
            last = c;
          }
        }
        continue;
      }
      if (c == ' ' || c == '\t' || c == '\r') continue;
      if (c == '#' && (previous == ' ' || previous == '\t' || i == 0)) break;
      if ((c == '"' || c == '\'') && opens_node_after(last)) {
        quote = c;
        continue;
      }
      const bool separator = c == ',' || c == '[' || c == '{' ||
                             (c == ':' && (i + 1 == row.size() || row[i + 1] == ' ' ||
                                           row[i + 1] == '\r' || flow_depth > 0));
      if (separator) count_value(line, i);
      if ((c == '[' || c == '{') && (flow_depth > 0 || opens_node_after(last))) {
        ++flow_depth;
        if (base_depth + flow_depth > max_depth) {
          return too_deep(line, static_cast<int>(i) + 1, base_depth + flow_depth);
        }
      } else if ((c == ']' || c == '}') && flow_depth > 0) {
        --flow_depth;
      } else if ((c == '|' || c == '>') && flow_depth == 0 && (last == ':' || last == '-')) {
        // A block scalar: its lines are text until the indentation drops back.
        block_scalar_indent = static_cast<int>(indent);
        break;
      }
      last = c;
    }
  }
  if (values > max_values) {
    return TextProblem{limit_crossed, "the file holds about " + std::to_string(values) +
                                          " YAML values, more than the limit of " +
                                          std::to_string(max_values) +
                                          " (ParseLimits::max_yaml_values)"};
  }
  return std::nullopt;
}

std::optional<SourceLoc> find_second_document(const std::string& text) {
  const auto is_marker = [](std::string_view row, std::string_view marker) {
    return row.substr(0, 3) == marker &&
           (row.size() == 3 || row[3] == ' ' || row[3] == '\t' || row[3] == '\r');
  };
  bool seen_content = false;  // of the first document
  bool ended = false;         // a `...` closed the first document
  int line = 0;
  for (std::size_t pos = 0; pos < text.size();) {
    ++line;
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    const std::string_view row(text.data() + pos, end - pos);
    pos = end + 1;
    if (is_marker(row, "---")) {
      if (seen_content || ended) return SourceLoc{line, 1};
      seen_content = row.find_first_not_of(" \t\r", 3) != std::string_view::npos &&
                     row[row.find_first_not_of(" \t\r", 3)] != '#';
      continue;
    }
    if (is_marker(row, "...")) {
      ended = true;
      continue;
    }
    const std::size_t first = row.find_first_not_of(" \t\r");
    const bool content = first != std::string_view::npos && row[first] != '#';
    if (content && ended) return SourceLoc{line, static_cast<int>(first) + 1};
    seen_content = seen_content || content;
  }
  return std::nullopt;
}

}  // namespace mbfe::frontend
