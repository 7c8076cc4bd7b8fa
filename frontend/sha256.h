// SHA-256 of a byte string, for the model hash in banners and cache keys.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>

namespace mbfe::frontend {

/// Lowercase hexadecimal SHA-256 digest (64 characters) of `bytes`.
/// @throws std::runtime_error if OpenSSL fails (a bug or an out-of-memory
/// condition, never bad user input).
std::string sha256_hex(const std::string& bytes);

/// The same digest of the concatenation of `parts`, without copying them
/// together (large binary buffers). @throws as sha256_hex.
std::string sha256_hex_of_parts(std::initializer_list<std::string_view> parts);

}  // namespace mbfe::frontend
