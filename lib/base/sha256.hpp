// SHA-256 digests for the bake manifest (inputs and outputs), as lowercase hex.
#pragma once

#include <initializer_list>
#include <span>
#include <string>

namespace dqskin {

std::string sha256_hex(std::span<const char> bytes);

// Digest of the pieces one after the other, as of their concatenation (a file written in parts).
std::string sha256_hex(std::initializer_list<std::span<const char>> pieces);

// Digest of a whole file, read in chunks. Throws InputError naming the file when it cannot be read.
std::string sha256_file(const std::string& path);

}  // namespace dqskin
