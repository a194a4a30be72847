// The dqskin commands: each one a settings struct that CLI11 fills and a function that runs it.
#pragma once

#include "dqskin/animation.hpp"
#include "dqskin/image_diff.hpp"
#include "dqskin/load.hpp"

#include <CLI/CLI.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace dqskin::cli {

// How every command that reads glTF files reads them (--resource-root, --max-memory), shared so that info,
// bake and render read the same flags the same way.
struct LoadSettings {
  std::vector<std::string> resource_roots;
  std::string max_memory = "2G";
};

// Adds the LoadSettings flags to a command.
void add_load_settings(CLI::App& command, LoadSettings& settings);

// The LoadOptions they ask for. Throws InputError for a size that is not one, or a root that is not a folder.
LoadOptions to_load_options(const LoadSettings& settings);

struct InfoSettings {
  std::vector<std::string> inputs;
  LoadSettings load;
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

// Which animations and frames a command works on (--anim, --fps, --frames, --keys, --times), shared by
// bake and render so that both read the same flags the same way.
struct FrameSelection {
  std::string anim = "all";
  double fps = 30;
  std::string frames, times;
  bool keys = false;
};

// Adds the FrameSelection flags to a command; `verb` goes into the help ("Animation to bake: …").
void add_frame_selection(CLI::App& command, FrameSelection& selection, const char* verb);

// The FrameSpec they ask for. Throws InputError for a bad range or list, or more than one way given.
FrameSpec to_frame_spec(const FrameSelection& selection);

struct BakeSettings {
  std::vector<std::string> inputs;  // empty: the bundled default input
  std::string out_dir;
  LoadSettings load;
  FrameSelection selection;
  std::string shard;
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

struct RenderSettings {
  std::vector<std::string> inputs;
  std::string out_dir;
  LoadSettings load;
  FrameSelection selection;
  std::string shard;
  std::string mode = "dqs";
  std::string backend = "auto";
  int scene = -1;
  std::string size;  // WxH; empty: 512x512, or 512 high in a --camera's aspect ratio
  std::string background = "0.2,0.2,0.2";  // sRGB
  int samples = 4;
  std::string shade = "lit";
  std::string joint;  // --shade weights
  std::optional<double> yaw, pitch, distance, fov;
  bool ortho = false;
  std::string camera;  // a node with a glTF camera
  std::string format = "png";
  bool sheet = false, gif = false;
  int sheet_cell = 256;
  bool quiet = false, json_progress = false, force = false;
};

// Renders every frame of every input's animations into images. Returns an ExitCode.
int run_render(const RenderSettings& settings);

struct DiffSettings {
  std::string a, b;
  DiffThresholds thresholds;  // idiff's defaults
  std::string out_dir;        // heat maps of failing pairs; none when empty
  bool json = false;
  std::string junit;          // JUnit XML report; none when empty
};

// Compares two images or two folders of images. Returns 0 (all pass), 1 (warnings only) or 2 (a failure,
// or a usage or input error).
int run_diff(const DiffSettings& settings);

}  // namespace dqskin::cli
