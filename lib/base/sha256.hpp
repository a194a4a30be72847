// SHA-256 digests for the bake manifest (inputs and outputs), as lowercase hex.
#pragma once

#include <initializer_list>
#include <memory>
#include <span>
#include <string>

namespace dqskin {

std::string sha256_hex(std::span<const char> bytes);

// Digest of the pieces one after the other, as of their concatenation (a file written in parts).
std::string sha256_hex(std::initializer_list<std::span<const char>> pieces);

// A digest of bytes fed in pieces (a file written from several sources).
class Sha256 {
public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;
  void add(std::span<const char> bytes);
  std::string hex();  // once, at the end

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Digest of a whole file, read in chunks. Throws InputError naming the file when it cannot be read.
std::string sha256_file(const std::string& path);

}  // namespace dqskin
