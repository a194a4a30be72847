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

struct BakeSettings {
  std::vector<std::string> inputs;  // empty: the bundled default input
  std::string out_dir;
  std::string anim = "all";
  double fps = 30;
  std::string frames, times, shard;
  bool keys = false;
  std::string mode = "dqs";
  std::string formats = "glb";
  std::string backend = "auto";
  int scene = -1;
  unsigned jobs = 0;
  size_t gpu_memory_mb = 512;
  bool dry_run = false, quiet = false, json_progress = false, force = false, verbose = false;
};

// Bakes every input's animations into the asked formats. Returns an ExitCode.
int run_bake(const BakeSettings& settings);

}  // namespace dqskin::cli
