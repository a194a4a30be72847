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

struct ReducedChannel {
  bool dropped = false;  // the channel goes: the node's rest value is within the budget at every key
  Channel channel;       // else its keys (a subset of the input's, or one key when it does not change)
};

// `channel` with the keys a viewer needs so that every input key is reproduced within `budget` (scene
// units, through ChannelError): LINEAR channels by a Douglas–Peucker split (reduce_keyframes; rotations
// are compared with the shortest-path slerp the viewer does), STEP channels lose keys that repeat the
// previous value, CUBICSPLINE channels are kept. A channel whose every key is within the budget of its
// first becomes one key; with `may_drop`, one whose every key is within the budget of the node's rest
// value (`rest`, components floats) is dropped. `rest` is null for weights (never dropped).
ReducedChannel reduce_channel(const Channel& channel, const NodeLevers& levers, double budget, const float* rest,
                              bool may_drop, unsigned threads);

}  // namespace dqskin::optimize_detail
