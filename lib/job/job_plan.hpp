// A job's plan (docs/DESIGN.md §2.6), decided before anything is deformed: the inputs, loaded, with
// their scene, mesh instances and clips; per clip the frame times, the numbers and folder its files are
// named by, and which units of work belong to this shard. Every command that walks inputs × clips ×
// frames plans here, so bake, render and the commands to come agree on every frame, name and shard.
#pragma once

#include "dqskin/animation.hpp"
#include "dqskin/job.hpp"
#include "dqskin/load.hpp"
#include "dqskin/skinning.hpp"

#include <memory>
#include <string>
#include <vector>

namespace dqskin {

struct ClipPlan {
  const Clip* clip = nullptr;     // null: the rest pose of a file without animations
  std::string name;               // the clip's name, for reports and manifests
  std::string folder;             // <stem>/<anim>, relative to the output folder
  std::vector<double> times;      // every frame of the clip under the FrameSpec
  std::vector<int> numbers;       // each frame's number in file names (its index on the fps grid)
  double fps = 0;                 // 0 when the times are keys or explicit
  std::vector<bool> frame_mine;   // per frame: its per-frame outputs belong to this shard
  bool clip_mine = false;         // the clip's whole-animation outputs belong to this shard
  // A bake deals some whole-animation work apart (bake/bake_shares.hpp); as planned here, it goes with
  // clip_mine: the morph animation, and frames [texture_first, texture_end) of the clip's textures (a
  // slice that this shard encodes and checks; all frames or none here).
  bool morph_mine = false;
  size_t texture_first = 0, texture_end = 0;
  int number_width = 4;

  // <folder>/frame_NNNN.<extension>
  std::string frame_file(size_t frame, const char* extension) const;
  // The frames whose per-frame outputs are this shard's.
  std::vector<size_t> my_frames() const;
  // Whether this shard has frames of the clip's textures, and whether they are all of them.
  bool has_texture_frames() const { return texture_end > texture_first; }
  bool whole_textures() const { return texture_first == 0 && texture_end == times.size(); }
};

struct InputPlan {
  std::string path;
  std::string stem;  // output folder name: the file name without its extension
  std::unique_ptr<Asset> asset;
  int scene = -1;
  std::vector<MeshInstance> instances;
  std::vector<int> skins;  // skins used by the instances, in index order
  std::vector<ClipPlan> clips;
  std::string error;  // why the input cannot be worked on; then nothing else is set
};

// Loads and plans every input. An input that fails to load or plan keeps its error and takes no units;
// the units are numbered over all inputs in order (a clip's whole-animation outputs one unit, each frame
// one), so every shard computes the same numbering. Adds the loading time to `load_seconds`. Throws
// InputError when two inputs would write to the same folder.
std::vector<InputPlan> plan_inputs(const std::vector<std::string>& inputs, const PlanOptions& options,
                                   double& load_seconds);

// Folder and file names: letters, digits, '.', '-' and '_' kept, anything else '_'.
std::string safe_name(const std::string& name);

}  // namespace dqskin
