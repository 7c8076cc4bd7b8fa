#include "frontend/sha256.h"

#include <openssl/evp.h>

#include <memory>
#include <stdexcept>

namespace mbfe::frontend {

std::string sha256_hex(const std::string& bytes) { return sha256_hex_of_parts({std::string_view(bytes)}); }

std::string sha256_hex_of_parts(std::initializer_list<std::string_view> parts) {
  // EVP is OpenSSL 3's supported interface; the low-level SHA256_* calls are
  // deprecated there.
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(), &EVP_MD_CTX_free);
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int digest_length = 0;
  bool ok = ctx && EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) == 1;
  for (std::string_view part : parts) ok = ok && EVP_DigestUpdate(ctx.get(), part.data(), part.size()) == 1;
  if (!ok || EVP_DigestFinal_ex(ctx.get(), digest, &digest_length) != 1) {
    throw std::runtime_error("sha256_hex: OpenSSL EVP digest failed");
  }
  static const char kHex[] = "0123456789abcdef";
  std::string hex;
  hex.reserve(2 * digest_length);
  for (unsigned int i = 0; i < digest_length; ++i) {
    hex.push_back(kHex[digest[i] >> 4]);
    hex.push_back(kHex[digest[i] & 0x0f]);
  }
  return hex;
}

}  // namespace mbfe::frontend
