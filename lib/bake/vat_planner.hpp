// The VAT planner (internal to lib/bake): given --max-size, --pot, --max-error and --max-bytes, chooses the
// texel type and a frame decimation (every k-th frame of the grid; the runtime interpolates between
// baked frames, as PlayCanvas and Houdini's shaders do) that fit the budget. It deforms the clip at every
// frame and halfway between frames once, and measures for each decimation the largest distance between a
// vertex and its linear interpolation between the kept frames; each type's error is the bound its
// encoding allows (texture/vat_codec.hpp). Bytes are the GPU memory of the images (uncompressed), what a
// texture budget is about.
#pragma once

#include "bake_plan.hpp"
#include "../texture/vat_codec.hpp"

#include "dqskin/deformer.hpp"

#include <optional>
#include <string>
#include <vector>

namespace dqskin::bake_detail {

// One choice the planner weighed.
struct VatChoice {
  texture::VatFormat format;
  size_t step = 1;     // every step-th frame of the clip's grid
  double fps = 0;      // the texture's frame rate (0: the clips' times are not a grid of one rate)
  size_t frames = 0;   // frames the texture holds, over every clip
  uint64_t bytes = 0;  // GPU memory of every image, uncompressed
  size_t width = 0, height = 0, pages = 0;
  double encoding_error = 0;       // the encoding's bound, scene units
  double interpolation_error = 0;  // measured between the kept frames (at frames and midpoints)
  std::string unfit;               // why the layout cannot hold it (empty when it can)
  double error() const { return encoding_error + interpolation_error; }
};

struct VatPlan {
  std::vector<VatChoice> choices;  // in the order weighed: types from the most precise, steps ascending
  size_t chosen = 0;
  std::vector<std::vector<double>> times;  // per clip, the frames of the chosen texture
  std::vector<double> fps;                 // per clip, its frames' rate (0: not a grid)
  double diagonal = 0;        // of the clip's bounding box, for relative errors
  std::string budget;         // the budget in words, for messages: "--max-error 1 mm, --max-bytes 4.00 MiB"
};

// Whether the options ask the planner to choose (a --max-error or --max-bytes).
bool planner_active(const TextureOptions& options);

// Weighs every choice for the clips of `set` (one decimation and type for all of them) and picks one: with --max-error, the fewest bytes within it (then the
// smallest error); without, the smallest error within --max-bytes (then the fewest bytes). `rest` holds
// the rest positions openvat's offsets start from (empty otherwise). Throws InputError naming the clip
// when nothing fits, saying what would come closest.
VatPlan plan_vat(Deformer& deformer, const InputPlan& input, const TextureClips& set, const TextureOptions& options,
                 const std::vector<float>& rest);

// The plans of every texture of `input` this shard bakes, as tables for --dry-run, deformed on the CPU (a dry
// run starts no GPU). Throws InputError as plan_vat does.
std::vector<std::string> dry_run_plans(const InputPlan& input, const BakeOptions& options);

// The plan as a table for --dry-run: one line per choice, the chosen one marked.
std::vector<std::string> describe(const VatPlan& plan, const std::string& what);

}  // namespace dqskin::bake_detail
