// What a bake will do, in numbers, before it writes anything (internal to bake.cpp): the vertex-frames it
// deforms and the bytes it writes, so that --dry-run can say so and a bake that cannot fit the free space
// of its output's file system is refused at once instead of failing half-way.
#pragma once

#include "bake_plan.hpp"
#include "../write/glb_output.hpp"

#include <cstdint>

namespace dqskin::bake_detail {

struct BakeWork {
  uint64_t vertex_frames = 0;  // vertices × frames deformed
  uint64_t bytes = 0;          // the files this shard writes, manifest included
  uint64_t existing = 0;       // bytes of those files already there (a rerun keeps the equal ones)
  size_t files = 0;
  BakeWork& operator+=(const BakeWork& o);
};

// The work of one planned input. Per-frame file sizes are measured by encoding the rest pose with the real
// writers (`glb`: the input's GlbWriter, or null when glb is not asked for); EXR sizes are their
// uncompressed size (an upper bound: ZIP stores 62-71 % of it), bone textures at 5 texels a joint (the
// most, for skins with scale).
BakeWork estimate_work(const InputPlan& input, const BakeOptions& options, const GlbWriter* glb);

// Bytes free to this process on the file system of `folder` (or its nearest existing ancestor).
uint64_t free_bytes(const std::string& folder);

}  // namespace dqskin::bake_detail
