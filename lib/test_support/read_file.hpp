// A file's bytes, for tests comparing outputs (header-only, for the test executables).
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace dqskin::testing_support {

// Every byte of `path`; "" when it cannot be read (the comparison that follows fails and says so).
inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

}  // namespace dqskin::testing_support
