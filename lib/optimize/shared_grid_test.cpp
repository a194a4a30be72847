// Channels onto one shared grid of key times: only where that takes fewer bytes, within the budget at every
// time (a dense grid measures it here through sample_channel), and never for a channel that does not span
// the grid.
#include "shared_grid.hpp"

#include "dqskin/animation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace dqskin::optimize_detail {
namespace {

// A translation channel of node `node` along x: x(t) = amplitude · sin(speed · t), a key every 1/30 s from
// `first` to `last` key index.
Channel wave(int node, double amplitude, double speed, int first = 0, int last = 60) {
  Channel ch;
  ch.node = node;
  ch.path = TargetPath::kTranslation;
  ch.components = 3;
  for (int k = first; k <= last; ++k) {
    const float t = float(k) / 30.0f;
    ch.times.push_back(t);
    ch.values.insert(ch.values.end(), {float(amplitude * std::sin(speed * double(t))), 0.0f, 0.0f});
  }
  return ch;
}

Levers unit_levers(size_t nodes) {
  Levers levers;
  levers.nodes.resize(nodes);
  for (NodeLevers& l : levers.nodes) l.moves_vertices = true, l.rotation = l.translation = l.scale = 1;
  return levers;
}

double worst_gap(const Channel& input, const Channel& candidate) {
  double worst = 0;
  for (size_t k = 0; k + 1 < input.times.size(); ++k)
    for (int j = 0; j <= 16; ++j) {
      const double t = double(input.times[k]) + (double(input.times[k + 1]) - double(input.times[k])) * j / 16.0;
      worst = std::max(worst, std::abs(sample_channel(input, t)[0] - sample_channel(candidate, t)[0]));
    }
  return worst;
}

size_t own_bytes(const std::vector<ReducedChannel>& reduced) {
  size_t bytes = 0;
  for (const ReducedChannel& r : reduced) bytes += r.channel.times.size() * 16;
  return bytes;
}

// Three busy channels whose own reductions keep most keys: on a grid of every other time they need no time
// of their own, so they go there, and each stays within the budget between keys too.
TEST(SharedGrid, BusyChannelsShareOneGridWithinTheBudget) {
  Clip clip;
  for (int n = 0; n < 3; ++n) clip.channels.push_back(wave(n, 1.0, 8.0 + 0.5 * n));
  std::vector<ReducedChannel> reduced;
  for (const Channel& ch : clip.channels) reduced.push_back({false, ch});  // as if no key could go
  const double budget = 0.06;  // every other key: about ω²h²/8 = 0.045 off between two, every third 0.10
  share_grid(clip, reduced, {true, true, true}, {12, 12, 12}, unit_levers(3), budget);
  for (size_t i = 0; i < reduced.size(); ++i) {
    EXPECT_EQ(reduced[i].channel.times, reduced[0].channel.times) << "one grid";
    EXPECT_LT(reduced[i].channel.times.size(), clip.channels[i].times.size());
    EXPECT_EQ(reduced[i].channel.times.front(), clip.channels[i].times.front());
    EXPECT_EQ(reduced[i].channel.times.back(), clip.channels[i].times.back());
    EXPECT_LE(worst_gap(clip.channels[i], reduced[i].channel), budget);
  }
}

// A channel reduced to a few keys of its own is cheaper than on any grid and keeps them; a channel that
// starts late (it clamps before its first key) is never put on the grid.
TEST(SharedGrid, CheapAndPartialChannelsKeepTheirOwnKeys) {
  Clip clip;
  clip.channels = {wave(0, 1.0, 9.0), wave(1, 1.0, 10.0), wave(2, 1.0, 11.0, 20, 60)};
  std::vector<ReducedChannel> reduced;
  for (const Channel& ch : clip.channels) reduced.push_back({false, ch});
  Channel two_keys = clip.channels[1];
  two_keys.times = {two_keys.times.front(), two_keys.times.back()};
  two_keys.values = {0, 0, 0, 0, 0, 0};
  reduced[1].channel = two_keys;
  share_grid(clip, reduced, {true, true, true}, {12, 12, 12}, unit_levers(3), 0.06);
  EXPECT_LT(reduced[0].channel.times.size(), clip.channels[0].times.size()) << "the busy one moves";
  EXPECT_EQ(reduced[1].channel.times, two_keys.times);
  EXPECT_EQ(reduced[2].channel.times, clip.channels[2].times);
  EXPECT_LE(own_bytes(reduced), own_bytes({{false, clip.channels[0]}, {false, two_keys}, {false, clip.channels[2]}}));
}

// Nothing eligible, or a budget that no grid but the input's own times meets: every channel stays.
TEST(SharedGrid, NoGridWithinTheBudgetChangesNothing) {
  Clip clip;
  for (int n = 0; n < 2; ++n) clip.channels.push_back(wave(n, 1.0, 40.0 + n));  // a key a radian apart
  std::vector<ReducedChannel> reduced;
  for (const Channel& ch : clip.channels) reduced.push_back({false, ch});
  share_grid(clip, reduced, {true, true}, {12, 12}, unit_levers(2), 1e-6);
  for (size_t i = 0; i < reduced.size(); ++i) EXPECT_EQ(reduced[i].channel.times, clip.channels[i].times);
  share_grid(clip, reduced, {false, false}, {12, 12}, unit_levers(2), 10.0);
  for (size_t i = 0; i < reduced.size(); ++i) EXPECT_EQ(reduced[i].channel.times, clip.channels[i].times);
}

}  // namespace
}  // namespace dqskin::optimize_detail
