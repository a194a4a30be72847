// How a sharded bake deals its work (docs/DESIGN.md §6.5): by cost, so that one long clip spreads over
// every shard as evenly as many short ones. plan_inputs deals whole clips' files round robin, which gives
// one shard all of a clip's textures and morph animation; here the frames of every clip, one after
// another, are cut into N runs of equal cost, each shard taking one run: its per-frame files and, where
// the textures can be cut (texture::sliceable, bone textures checked frame by frame), its slice of them.
// What cannot be cut (the morph animation, textures that cannot) goes whole to the least loaded shard
// first, largest first, and that shard's run is shorter by as much. Every shard computes the same deal.
#pragma once

#include "dqskin/bake.hpp"
#include "../job/job_plan.hpp"

#include <vector>

namespace dqskin::bake_detail {

// Sets each clip's frame_mine, clip_mine (the clip's head: its other whole-animation files), morph_mine
// and texture range for this shard. Leaves the round-robin deal of plan_inputs unsharded and with
// --combine-clips (a texture of every clip goes with its first clip).
void deal_bake_shares(std::vector<InputPlan>& plans, const BakeOptions& options);

}  // namespace dqskin::bake_detail
