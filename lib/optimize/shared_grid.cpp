#include "shared_grid.hpp"

#include "dqskin/animation.hpp"

#include <algorithm>
#include <cmath>
#include <set>

namespace dqskin::optimize_detail {
namespace {

constexpr size_t kLargestStep = 8;

// Whether `candidate` (LINEAR) reproduces every key of `input` within `budget`. Both are piecewise linear
// (slerp for rotations) between keys the candidate's grid shares with the input's union, so the error
// between keys is bounded by the error at them (docs/DESIGN.md §3.12).
bool within(const Channel& input, const Channel& candidate, const ChannelError& error, double budget) {
  const size_t n = size_t(input.components);
  std::vector<float> a(n), b(n);
  for (size_t k = 0; k < input.times.size(); ++k) {
    const std::vector<double> v = sample_channel(candidate, double(input.times[k]));
    for (size_t c = 0; c < n; ++c) a[c] = input.values[k * n + c], b[c] = float(v[c]);
    if (error(a.data(), b.data()) > budget) return false;
  }
  return true;
}

}  // namespace

void share_grid(const Clip& clip, std::vector<ReducedChannel>& reduced, const std::vector<bool>& eligible,
                const std::vector<size_t>& value_bytes, const Levers& levers, double budget) {
  std::set<float> union_times;
  for (size_t i = 0; i < clip.channels.size(); ++i)
    if (eligible[i]) union_times.insert(clip.channels[i].times.begin(), clip.channels[i].times.end());
  if (union_times.size() < 3) return;
  const std::vector<float> all(union_times.begin(), union_times.end());

  // Bytes with every channel on its own keys (times shared where equal are counted once per channel: an
  // upper bound, as the writer shares equal time accessors).
  size_t own_total = 0;
  for (size_t i = 0; i < clip.channels.size(); ++i)
    if (eligible[i]) own_total += reduced[i].channel.times.size() * (4 + value_bytes[i]);

  size_t best_total = own_total;
  std::vector<std::pair<size_t, Channel>> best_members;
  for (size_t step = 1; step <= kLargestStep && all.size() / step >= 2; ++step) {
    std::vector<float> grid;
    for (size_t k = 0; k < all.size(); k += step) grid.push_back(all[k]);
    if (grid.back() != all.back()) grid.push_back(all.back());
    size_t total = grid.size() * 4;  // the grid's one time accessor
    std::vector<std::pair<size_t, Channel>> members;
    for (size_t i = 0; i < clip.channels.size(); ++i) {
      if (!eligible[i]) continue;
      const size_t own = reduced[i].channel.times.size() * (4 + value_bytes[i]);
      const size_t on_grid = grid.size() * value_bytes[i];
      // A channel whose keys do not reach the grid's ends stays on its own (it clamps outside them).
      const Channel& input = clip.channels[i];
      if (on_grid >= own || input.times.front() != grid.front() || input.times.back() != grid.back()) {
        total += own;
        continue;
      }
      Channel candidate = sampled_at(input, grid);
      if (!within(input, candidate, ChannelError(input, levers.nodes[size_t(input.node)]), budget)) {
        total += own;
        continue;
      }
      total += on_grid;
      members.emplace_back(i, std::move(candidate));
    }
    if (!members.empty() && total < best_total) {
      best_total = total;
      best_members = std::move(members);
    }
  }
  for (auto& [i, channel] : best_members) reduced[i].channel = std::move(channel);
}

}  // namespace dqskin::optimize_detail
