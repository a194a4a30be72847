// `dqskin optimize`: a glTF file's animations made smaller under an error budget measured on the skinned
// surface, not per channel (docs/DESIGN.md §3.12, docs/commands/optimize.md).
#pragma once

#include "dqskin/load.hpp"
#include "dqskin/skinning.hpp"

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

namespace dqskin {

struct OptimizeOptions {
  LoadOptions load;
  double max_error = 0;          // scene units; with max_error_percent < 0
  double max_error_percent = -1; // ≥ 0: the budget is this share of the rest pose's bounding-box diagonal
  BlendMode mode = BlendMode::kLbs;  // the skinning the file's runtime does (viewers and engines: LBS)
  bool remove_keys = true;           // keys of LINEAR and STEP channels that interpolation reproduces
  bool drop_channels = true;         // channels that stay within the budget of the node's rest value
  bool convert_interpolation = true; // LINEAR to STEP, CUBICSPLINE to LINEAR, where smaller within the budget
  bool share_times = true;           // LINEAR channels resampled onto one shared grid of key times, where smaller
  bool quantize_rotations = true;    // float rotation outputs stored as normalized shorts (glTF 2.0 §3.11)
  bool quantize_weights = true;      // float morph weights in [0, 1] or [-1, 1] stored as normalized integers
  unsigned threads = 0;              // 0: every core
  const std::atomic<bool>* cancel = nullptr;
};

// One clip's figures, measured on the written file read back against the input, by the CPU reference.
struct ClipOptimization {
  std::string name;
  size_t channels_before = 0, channels_after = 0;
  size_t keys_before = 0, keys_after = 0;
  double max_error = 0, p99_error = 0;  // scene units, over every vertex at every judged time
  double max_error_time = 0;            // seconds
  std::string max_error_joint;          // the joint weighing most on the worst vertex (a rigid mesh: its node)
  size_t judged_times = 0;              // every key time and every midpoint between two
  double scale_factor = 0;              // the search's result (docs/DESIGN.md §3.12); 0: kept as it was
};

struct OptimizeSummary {
  std::string input, output;
  double budget = 0;    // scene units
  double diagonal = 0;  // of the rest pose's bounding box
  BlendMode mode = BlendMode::kLbs;
  std::vector<ClipOptimization> clips;
  uint64_t animation_bytes_before = 0, animation_bytes_after = 0;
  uint64_t file_bytes_before = 0, file_bytes_after = 0;
  std::vector<std::string> notes;
};

// Writes `output` (.glb): `input` with each clip's channels reduced so that the deformed surface stays
// within the budget of the input's at every key time and midpoint, measured on the file read back.
// Throws InputError (a bad budget, a file without animation or that cannot be written back) and
// OutputError; nothing is left at `output` then.
OptimizeSummary optimize(const std::string& input, const std::string& output, const OptimizeOptions& options);

}  // namespace dqskin
