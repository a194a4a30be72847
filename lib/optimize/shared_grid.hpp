// Channels moved onto one shared grid of key times where that takes fewer bytes (internal to lib/optimize,
// docs/DESIGN.md §3.12): a channel with its own reduced keys pays a time for every key, while channels on
// one grid share a single time accessor.
#pragma once

#include "channel_reduction.hpp"
#include "levers.hpp"

#include "dqskin/asset.hpp"

#include <vector>

namespace dqskin::optimize_detail {

// For `clip`'s channels (the input's) and their reductions: the grid is every s-th time of the union of the
// eligible channels' input key times (s = 1 … 8, the last time always). A channel joins the grid of step s
// when its input sampled there, interpolated as the viewer does, stays within `budget` (scene units) at
// every input key, and the grid's values cost fewer bytes than its own keys; the step with the fewest bytes
// in all, grid times included, is taken, or none. `value_bytes[i]` is what one key's value of channel i
// takes as stored. Only eligible channels (LINEAR in and out, not dropped) are considered.
void share_grid(const Clip& clip, std::vector<ReducedChannel>& reduced, const std::vector<bool>& eligible,
                const std::vector<size_t>& value_bytes, const Levers& levers, double budget);

}  // namespace dqskin::optimize_detail
