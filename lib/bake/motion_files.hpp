// A clip's sockets and root motion files (internal to lib/bake; docs/formats.md, "Sockets and root
// motion"): sockets.json and sockets.exr, the world transforms of the nodes --sockets names at every frame,
// and root_motion.json, the ground motion that --root-motion in-place took out of every frame
// (docs/DESIGN.md §3.11). They are whole-animation files: written by the shard that owns the clip.
#pragma once

#include "motion_nodes.hpp"

#include "dqskin/atomic_file.hpp"

#include <string>
#include <utility>
#include <vector>

namespace dqskin::bake_detail {

inline constexpr const char* kSocketsJson = "sockets.json";
inline constexpr const char* kSocketsTexture = "sockets.exr";
inline constexpr const char* kRootMotionJson = "root_motion.json";

// The files `clip` writes for `nodes`, relative to the output folder (none when the clip is not the
// shard's). A clip without animation (a file's rest pose) has no root motion file.
std::vector<std::string> planned_motion_files(const ClipPlan& clip, const MotionNodes& nodes);

// Samples the clip's frames (in place when the clip is, as every other output of the bake) and writes and
// commits planned_motion_files. Returns each file with what commit() did.
std::vector<std::pair<std::string, Committed>> write_motion_files(const InputPlan& input, const ClipPlan& clip,
                                                                  const MotionNodes& nodes, const BakeOptions& options,
                                                                  const CommitOptions& commit);

}  // namespace dqskin::bake_detail
