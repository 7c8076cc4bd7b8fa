#include "ir/identifiers.h"

#include <algorithm>
#include <iterator>
#include <string_view>


namespace mbfe::ir {
namespace {

// C++20 keywords, the alternative tokens, and identifiers with special meaning
// that would read confusingly as a variable (`final`, `override`), and the
// macros a generated file may see (`NULL`, `assert`, `errno`).
// clang-format off
constexpr std::string_view kReserved[] = {
    "alignas",   "alignof",     "and",          "and_eq",       "asm",
    "auto",      "bitand",      "bitor",        "bool",         "break",
    "case",      "catch",       "char",         "char16_t",     "char32_t",
    "char8_t",   "class",       "co_await",     "co_return",    "co_yield",
    "compl",     "concept",     "const",        "const_cast",   "consteval",
    "constexpr", "constinit",   "continue",     "decltype",     "default",
    "delete",    "do",          "double",       "dynamic_cast", "else",
    "enum",      "explicit",    "export",       "extern",       "false",
    "final",     "float",       "for",          "friend",       "goto",
    "if",        "import",      "inline",       "int",          "long",
    "module",    "mutable",     "namespace",    "new",          "noexcept",
    "not",       "not_eq",      "nullptr",      "operator",     "or",
    "or_eq",     "override",    "private",      "protected",    "public",
    "register",  "reinterpret_cast", "requires", "return",      "short",
    "signed",    "sizeof",      "static",       "static_assert", "static_cast",
    "struct",    "switch",      "template",     "this",         "thread_local",
    "throw",     "true",        "try",          "typedef",      "typeid",
    "typename",  "union",       "unsigned",     "using",        "virtual",
    "void",      "volatile",    "wchar_t",      "while",        "xor",
    "xor_eq",    "NULL",        "assert",       "errno",
    "std"};  // a model namespace named std would hide ::std inside generated code
// clang-format on

}  // namespace

bool is_identifier(const std::string& name) {
  const auto alpha = [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_';
  };
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  if (name.empty() || !alpha(name[0])) return false;
  return std::all_of(name.begin(), name.end(), [&](char c) { return alpha(c) || digit(c); });
}

bool is_reserved_in_cpp(const std::string& name) {
  if (std::find(std::begin(kReserved), std::end(kReserved), name) != std::end(kReserved)) {
    return true;
  }
  if (name.find("__") != std::string::npos) return true;
  return name.size() >= 2 && name[0] == '_' && name[1] >= 'A' && name[1] <= 'Z';
}

}  // namespace mbfe::ir
