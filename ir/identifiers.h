// Which names may reach generated C++.
#pragma once

#include <string>

namespace mbfe::ir {

/// True for [A-Za-z_][A-Za-z0-9_]*.
bool is_identifier(const std::string& name);

/// True for C++ keywords and alternative operator tokens (`int`, `class`,
/// `and`, ...), and for names the language reserves to the implementation
/// (a double underscore anywhere, or an underscore then a capital letter).
bool is_reserved_in_cpp(const std::string& name);

}  // namespace mbfe::ir
