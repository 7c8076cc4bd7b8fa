// SHA-256 of a byte string, for the model hash in banners and cache keys.
#pragma once

#include <string>

namespace mbfe::frontend {

/// Lowercase hexadecimal SHA-256 digest (64 characters) of `bytes`.
/// @throws std::runtime_error if OpenSSL fails (a bug or an out-of-memory
/// condition, never bad user input).
std::string sha256_hex(const std::string& bytes);

}  // namespace mbfe::frontend
