// One frame of the geometric diff measured (internal to lib/diff): the distance between every compared vertex
// and its corresponding surface point, and the angle between their normals.
#pragma once

#include "correspondence.hpp"
#include "diff_side.hpp"
#include "largest_errors.hpp"

#include "dqskin/geometry_diff.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>
#include <vector>

namespace dqskin::diff_detail {

// The figures of one frame, with what the clip accumulates from it.
struct FrameResult {
  FrameDiff figures;
  double max_a_to_b = 0, max_b_to_a = 0;
  char worst_side = 'A';
  size_t worst_vertex = 0;
  double sum = 0;
  uint64_t samples = 0, over_warn = 0, over_fail = 0;
  std::vector<float> joint_max;  // per joint name of the clip's table
  glm::vec3 low{std::numeric_limits<float>::infinity()}, high{-std::numeric_limits<float>::infinity()};  // A's bounding box
};

// Vertex v of a frame's flat float array (3 per vertex).
inline glm::vec3 at(const std::vector<float>& a, size_t v) { return {a[3 * v], a[3 * v + 1], a[3 * v + 2]}; }

// One direction of one frame: `from`'s compared vertices against the surface points of `onto`, and the
// normals as the correspondence says (its smooth vertices, then its faces). Errors go
// to `largest`, which keeps the frame's largest errors (for its percentile). The normal angle is found through the
// smallest cosine, then measured exactly once (atan2 of |m × n| and m · n: an acos of a rounded cosine
// reads 1e-5 degrees for equal normals).
void measure(const SideFrame& from_frame, const SideFrame& onto_frame, const Correspondence& c, double warn, double fail,
             char side, FrameResult& r, LargestErrors& largest, double& direction_max);

}  // namespace dqskin::diff_detail
