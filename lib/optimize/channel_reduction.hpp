// One animation channel reduced under a surface budget (internal to lib/optimize, docs/DESIGN.md §3.12).
#pragma once

#include "levers.hpp"

#include "dqskin/asset.hpp"

#include <vector>

namespace dqskin::optimize_detail {

// The surface distance, in scene units, that the difference between two values of `channel` may cause:
// the channel-space difference (an angle for rotations, a length for translations, the largest component
// for scales, each weight's) times the node's lever.
class ChannelError {
public:
  ChannelError(const Channel& channel, const NodeLevers& levers);
  double operator()(const float* a, const float* b) const;

private:
  TargetPath path_;
  double lever_;
  std::vector<double> weight_levers_;
};

// The times a CUBICSPLINE channel is sampled at for its linear equivalent: 8 a segment, its keys among
// them (float times, strictly increasing). The search judges a clip at these too (judged_times).
std::vector<float> cubic_sample_times(const Channel& channel);

// `channel` sampled at `times` (sample_channel, as every command samples) as LINEAR keys of the same target.
Channel sampled_at(const Channel& channel, const std::vector<float>& times);

struct ReducedChannel {
  bool dropped = false;  // the channel goes: the node's rest value is within the budget at every key
  Channel channel;       // else its keys (a subset of the input's, or one key when it does not change)
};

// What reduce_channel may change besides removing keys.
struct ReductionLevers {
  bool drop = true;            // a channel at its node's rest value goes
  bool interpolation = true;   // LINEAR becomes STEP, CUBICSPLINE becomes LINEAR, where either is smaller
};

// `channel` with the keys a viewer needs so that its value stays within `budget` (scene units, through
// ChannelError) of the input's:
// - LINEAR channels by a Douglas–Peucker split (reduce_keyframes; rotations compared with the
//   shortest-path slerp the viewer does), which holds at every time, as the difference of two linear
//   segments is largest at their ends; then, where fewer keys do, as STEP: runs whose held value is within
//   the budget of every key of the run and of the next run's first, so that the linear segments between
//   them never leave it either (exact to the budget at every time, not only at keys);
// - STEP channels lose keys that repeat the previous value;
// - CUBICSPLINE channels become LINEAR where that takes fewer bytes (three values a key against one): the
//   Hermite curve sampled 8 times a segment, reduced as above with half the budget, and kept only if the
//   linear keys are within the budget at 32 points of every segment; else they stay as they are.
// A channel whose every key is within the budget of its first becomes one key; with `levers.drop`, one
// whose every key is within the budget of the node's rest value (`rest`, components floats) is dropped.
// `rest` is null for weights (never dropped).
ReducedChannel reduce_channel(const Channel& channel, const NodeLevers& levers, double budget, const float* rest,
                              ReductionLevers allowed, unsigned threads);

}  // namespace dqskin::optimize_detail
