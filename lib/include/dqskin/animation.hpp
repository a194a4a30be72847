// Animation sampling (docs/DESIGN.md §2.2): a Clip at a time gives a Pose, and frame times say
// which times a bake samples.
#pragma once

#include "dqskin/asset.hpp"

#include <optional>
#include <string>
#include <vector>

namespace dqskin {

// A node's motion on the ground (docs/DESIGN.md §3.11): its world origin projected on glTF's ground plane
// (x and z; y is up) and its heading, the twist of its world rotation about +Y, in radians in [-π, π].
struct GroundMotion {
  double x = 0, z = 0, yaw = 0;
};

// The ground motion of a node whose world matrix is `world` (its rotation: the nearest one, for a matrix
// with scale).
GroundMotion ground_motion(const Mat4<double>& world);
// M = T(x, 0, z) · Ry(yaw), and its inverse Ry(-yaw) · T(-x, 0, -z), both rigid.
Mat4<double> ground_matrix(const GroundMotion& g);
Mat4<double> ground_matrix_inverse(const GroundMotion& g);

// Every node's world matrix and morph weights at one time.
struct Pose {
  std::vector<Mat4<double>> world;           // per node
  std::vector<std::vector<double>> weights;  // per node: its mesh's morph weights (empty without targets)
  // For a clip with an in_place_root: the root's ground motion M that was taken out, every world matrix
  // being M⁻¹ · its world matrix in the file's scene (docs/DESIGN.md §3.11).
  std::optional<GroundMotion> removed;
};

// Samples `clip` at `time` seconds (glTF time: clip time 0 is 0 s, not the first key). Channels clamp
// outside their key range. Nodes without channels keep their rest transform; clip may be null for the
// rest pose. Follows glTF 2.0 §3.11 and Appendix C: STEP, LINEAR (rotations by shortest-path slerp),
// CUBICSPLINE (Hermite with the key tangents scaled by the key interval; rotations renormalised). A clip
// with an in_place_root gives the pose in place: its root's ground motion removed from every node.
Pose sample_pose(const Asset& asset, const Clip* clip, double time);

// One channel's value at `time`: components() floats widened to double (rotation as x, y, z, w).
std::vector<double> sample_channel(const Channel& channel, double time);

// The clips a command works on: "all" (every clip, in file order), a clip name, or a clip index. Throws
// InputError naming the clips there are when nothing matches.
std::vector<size_t> select_clips(const Asset& asset, const std::string& which);

// Which times to sample. Frame i of the default grid is start + i / fps, never an accumulated sum; the
// grid runs from the clip start (0 s, or the first key with from_first_key) to its last key inclusive.
struct FrameSpec {
  double fps = 30;
  bool from_first_key = false;
  // Frames first..last (inclusive) of the grid, every step-th.
  std::optional<int> first, last;
  int step = 1;
  bool keys = false;          // every key time of the clip instead of the grid
  std::vector<double> times;  // explicit times in seconds instead of the grid (when non-empty)
};

// The frame times of a clip under spec, in increasing order for the grid and keys, as given for explicit
// times. Throws InputError for a spec that cannot be satisfied (fps ≤ 0, a range outside the grid).
std::vector<double> frame_times(const Clip& clip, const FrameSpec& spec);

// The number of frames of the clip's fps grid under spec (its fps and start; not first, last or step).
// Throws InputError for fps ≤ 0 or a grid of more frames than dqskin takes.
int grid_frame_count(const Clip& clip, const FrameSpec& spec);

// Parses "A:B" or "A:B:step" into spec.first/last/step. Throws InputError naming the problem.
void parse_frame_range(const std::string& text, FrameSpec& spec);

// Parses "0,0.5,1.25" into seconds. Throws InputError naming the problem.
std::vector<double> parse_times(const std::string& text);

}  // namespace dqskin
