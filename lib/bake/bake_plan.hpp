// What a bake will do, decided before anything is deformed (internal to bake.cpp): the inputs with
// their clips, frame times and names, and which units of work belong to this shard.
#pragma once

#include "dqskin/bake.hpp"

#include <memory>

namespace dqskin::bake_detail {

struct ClipPlan {
  const Clip* clip = nullptr;     // null: the rest pose of a file without animations
  std::string name;               // the clip's name, for the manifest
  std::string folder;             // <stem>/<anim>, relative to the output folder
  std::vector<double> times;      // every frame of the clip under the FrameSpec
  std::vector<int> numbers;       // each frame's number in file names (its index on the fps grid)
  double fps = 0;                 // 0 when the times are keys or explicit
  std::vector<bool> frame_mine;   // per frame: its per-frame outputs belong to this shard
  bool clip_mine = false;         // the clip's whole-animation outputs (vat, bones, mtl) belong to this shard
  int number_width = 4;

  std::string frame_file(size_t frame, const char* extension) const;
  // Frames to deform: all of them when whole-animation textures are due, else the shard's own.
  std::vector<size_t> frames_to_deform(unsigned formats) const;
};

struct InputPlan {
  std::string path;
  std::string stem;  // output folder name: the file name without its extension
  std::unique_ptr<Asset> asset;
  int scene = -1;
  std::vector<MeshInstance> instances;
  std::vector<int> skins;  // skins used by the instances, in index order (bones outputs)
  std::vector<ClipPlan> clips;
  std::string error;  // why the input cannot be baked; then nothing else is set
};

// Loads and plans every input; the shards' units are numbered over all inputs in order, so every shard
// computes the same numbering. Throws InputError when two inputs would write to the same folder.
std::vector<InputPlan> plan_bake(const std::vector<std::string>& inputs, const BakeOptions& options, double& load_seconds);

// The files one clip writes, relative to the output folder, for the formats asked for.
std::vector<std::string> planned_files(const InputPlan& input, const ClipPlan& clip, unsigned formats);

// Folder and file names: letters, digits, '.', '-' and '_' kept, anything else '_'.
std::string safe_name(const std::string& name);

}  // namespace dqskin::bake_detail
