// Sizes in bytes as people write them: "2G", "512M", "1.5GiB" on the command line (--max-memory), and
// "2.00 GiB" in messages.
#pragma once

#include <cstdint>
#include <string>

namespace dqskin {

// "2.00 GiB", "512.0 MiB", "12.3 KiB", "900 bytes": binary units, three significant digits.
std::string byte_size(uint64_t bytes);

// A byte count from "4294967296", "4G", "4GiB", "512M", "64k", "1.5G" (K, M, G, T in powers of 1024, an
// optional "iB" or "B", case-insensitive). Throws InputError naming `what` (the flag) for anything else,
// zero, or more than 2^63.
uint64_t parse_byte_size(const std::string& text, const std::string& what);

}  // namespace dqskin
