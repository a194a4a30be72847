// SHA-256 through OpenSSL's EVP interface (libcrypto), which picks the CPU's SHA instructions.
#include "sha256.hpp"

#include "dqskin/error.hpp"

#include <openssl/evp.h>

#include <cstdio>
#include <memory>
#include <vector>

namespace dqskin {
namespace {

struct Digest {
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> context{EVP_MD_CTX_new(), &EVP_MD_CTX_free};
  Digest() {
    if (!context || EVP_DigestInit_ex(context.get(), EVP_sha256(), nullptr) != 1) throw std::bad_alloc();
  }
  void add(const void* data, size_t bytes) { EVP_DigestUpdate(context.get(), data, bytes); }
  std::string hex() {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int length = 0;
    EVP_DigestFinal_ex(context.get(), digest, &length);
    static const char* digits = "0123456789abcdef";
    std::string out;
    for (unsigned int i = 0; i < length; ++i) {
      out += digits[digest[i] >> 4];
      out += digits[digest[i] & 15];
    }
    return out;
  }
};

}  // namespace

struct Sha256::Impl {
  Digest digest;
};
Sha256::Sha256() : impl_(std::make_unique<Impl>()) {}
Sha256::~Sha256() = default;
void Sha256::add(std::span<const char> bytes) { impl_->digest.add(bytes.data(), bytes.size()); }
std::string Sha256::hex() { return impl_->digest.hex(); }

std::string sha256_hex(std::span<const char> bytes) {
  Digest d;
  d.add(bytes.data(), bytes.size());
  return d.hex();
}

std::string sha256_hex(std::initializer_list<std::span<const char>> pieces) {
  Digest d;
  for (std::span<const char> piece : pieces) d.add(piece.data(), piece.size());
  return d.hex();
}

std::string sha256_file(const std::string& path) {
  std::unique_ptr<std::FILE, decltype(&std::fclose)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw InputError(path + ": cannot be read");
  Digest d;
  std::vector<char> chunk(size_t(1) << 20);
  size_t n = 0;
  while ((n = std::fread(chunk.data(), 1, chunk.size(), file.get())) > 0) d.add(chunk.data(), n);
  if (std::ferror(file.get())) throw InputError(path + ": cannot be read");
  return d.hex();
}

}  // namespace dqskin
