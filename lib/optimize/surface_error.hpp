// The surface error of one clip against another on the same mesh (internal to lib/optimize): both
// deformed at the same times, vertex by vertex.
#pragma once

#include "dqskin/asset.hpp"
#include "dqskin/deformer.hpp"
#include "dqskin/skinning.hpp"

#include <limits>
#include <string>
#include <vector>

namespace dqskin::optimize_detail {

struct SurfaceError {
  double max = 0;
  double p99 = 0;         // the 99th percentile of every vertex at every time (to 1/2048 of the scale, or the max)
  double max_time = 0;    // where the max was found
  size_t max_instance = 0, max_primitive = 0, max_vertex = 0;
  size_t samples = 0;     // times
};

// The times a clip is judged at: every key time of every channel of `clip`, the times a CUBICSPLINE
// channel's linear equivalent may put its keys at (cubic_sample_times), and the midpoint between each two
// consecutive ones.
std::vector<double> judged_times(const Clip& clip);

// `candidate` against `reference` at `times`, on `asset`'s mesh instances, deformed by `backend` in
// `mode`. `candidate_asset` is the asset the candidate clip belongs to (the same mesh; may be `asset`).
// `scale` (the budget) sets the p99's resolution. A search that only asks whether the error is within a
// bound passes it as `stop_above`: the measurement ends with the first chunk of times past it (max is then
// a lower bound past the bound, the p99 not measured), and begins
// with the chunk holding `look_first` (the time a previous candidate failed at; < 0: in order).
SurfaceError surface_error(const Asset& asset, const Clip& reference, const Asset& candidate_asset,
                           const Clip& candidate, const std::vector<MeshInstance>& instances,
                           const std::vector<double>& times, double scale, BlendMode mode, Backend backend,
                           unsigned threads, double stop_above = std::numeric_limits<double>::infinity(),
                           double look_first = -1);

// The name of the joint with the largest weight on a vertex (or the rigid instance's node), for reports.
std::string vertex_joint(const Asset& asset, const std::vector<MeshInstance>& instances, size_t instance,
                         size_t primitive, size_t vertex);

}  // namespace dqskin::optimize_detail
