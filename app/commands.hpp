// The dqskin commands: each one a settings struct that CLI11 fills and a function that runs it.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace dqskin::cli {

struct InfoSettings {
  std::vector<std::string> inputs;
  bool json = false;
};

// Prints facts about each input. Returns an ExitCode.
int run_info(const InfoSettings& settings);

struct BenchSettings {
  bool json = false;
  bool quick = false;
  std::string backend = "auto";
  size_t gpu_memory_mb = 512;
};

// Measures vertex-frames per second of every deformation path. Returns an ExitCode.
int run_bench(const BenchSettings& settings);

}  // namespace dqskin::cli
