#include "default_input.hpp"
#include "console.hpp"

#include "dqskin/error.hpp"

#include <stdlib.h>  // mkdtemp

#include <cstdio>
#include <filesystem>
#include <iostream>

namespace dqskin::cli {

std::string unpack_default_input(const std::string& command, std::string& out_dir, bool quiet) {
  std::string folder = (std::filesystem::temp_directory_path() / ("dqskin-" + command + "-XXXXXX")).string();
  if (!::mkdtemp(folder.data())) throw OutputError(folder + ": cannot create a temporary folder");
  const std::string input = folder + "/" + kDefaultInputName;
  std::FILE* f = std::fopen(input.c_str(), "wb");
  const bool written = f && std::fwrite(kDefaultInput.data(), 1, kDefaultInput.size(), f) == kDefaultInput.size();
  const bool closed = f && std::fclose(f) == 0;
  if (!written || !closed) throw OutputError(input + ": cannot write");
  if (out_dir.empty()) out_dir = folder + "/out";
  if (!quiet)
    print_error(std::string("no input given: ") + (command == "bake" ? "baking" : "rendering") + " the bundled " +
                kDefaultInputName + " into " + out_dir);
  return input;
}

}  // namespace dqskin::cli
