// Where the clips' channels come from in a glTF file, and the channels that repeat a target (internal to
// lib/load and lib/lint; plain data, no tinygltf type): what `dqskin lint` reports and `--fix` rewrites.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace dqskin::gltf {

// Where a clip's channel comes from in the file. A "/meshes/M/weights" KHR_animation_pointer channel gives
// one clip channel per node that draws mesh M, all from the same file channel.
struct ChannelOrigin {
  size_t channel = 0;  // index into the animation's channels
  size_t sampler = 0;  // its sampler
};

// Two channels of one animation with the same target (a node and path, or a mesh's weights), which glTF 2.0
// §3.11 forbids. The first stays in the clip, the second does not. Identical ones (same interpolation, key
// times and values, compared decoded) change nothing; different ones make the file one that cannot be
// deformed (Asset::cannot_deform).
struct DuplicateChannel {
  size_t animation = 0;
  size_t first = 0, second = 0;  // indices into the animation's channels
  bool identical = false;
  std::string message;  // one line naming the animation, both channels and the target
};

struct AnimationOrigins {
  std::vector<std::vector<ChannelOrigin>> channels;  // [clip][clip channel]
  std::vector<DuplicateChannel> duplicates;          // in file order
};

}  // namespace dqskin::gltf
