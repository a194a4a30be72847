// Keyframe reduction (internal to lib/): which of a sequence of frames or keys (a morph animation's baked
// frames, an animation channel's keys) a viewer must hold so that interpolation between the held ones
// reproduces every one within a budget (bake --format morph, dqskin optimize).
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

namespace dqskin {

// The error at frame i when a viewer interpolates it linearly between keys a and b (a < i < b), as they are
// stored (quantized, when they are). Called from several threads at once: it must only read.
using InterpolationError = std::function<double(size_t i, size_t a, size_t b)>;

// The keys, ascending, of `frames` frames (frames ≥ 1): the first and the last always, then, by a
// Douglas–Peucker split (Douglas and Peucker 1973, applied to time instead of arc length), the frame of a
// segment that `error` finds worst (the earliest of equals) becomes a key until every frame of every
// segment is within `budget`. The split is deterministic and puts keys at the poses the motion turns
// around, where a greedy forward scan would place them by where it started; neither is minimal, and the
// split only ever divides a segment that misses the budget. Costs O(frames × depth) calls of `error`,
// spread over `threads` threads.
std::vector<size_t> reduce_keyframes(size_t frames, double budget, const InterpolationError& error, unsigned threads);

}  // namespace dqskin
