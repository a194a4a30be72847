#include "clip_matching.hpp"

#include "dqskin/animation.hpp"
#include "dqskin/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <map>
#include <tuple>

namespace dqskin::diff_detail {
namespace {

const char* interpolation_name(Interpolation interpolation) {
  switch (interpolation) {
    case Interpolation::kStep: return "STEP";
    case Interpolation::kLinear: return "LINEAR";
    case Interpolation::kCubicSpline: return "CUBICSPLINE";
  }
  return "?";
}

std::string seconds(double t) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", t);
  return text;
}

std::string clip_list(const Asset& asset) {
  if (asset.clips.empty()) return "no animations";
  std::string list;
  for (size_t c = 0; c < asset.clips.size() && c < 8; ++c) list += (c ? ", " : "") + clip_label(asset, int(c));
  if (asset.clips.size() > 8) list += ", ...";
  return list;
}

}  // namespace

std::string clip_label(const Asset& asset, int clip) {
  if (clip < 0) return "rest pose";
  const std::string& name = asset.clips[size_t(clip)].name;
  if (!name.empty()) return name;
  std::string label = "#";  // appended, not `"#" + …`: GCC 12 warns falsely (-Wrestrict) on that form
  label += std::to_string(clip);
  return label;
}

std::string node_label(const Asset& asset, int node) {
  const std::string& name = asset.nodes[size_t(node)].name;
  if (!name.empty()) return name;
  std::string label = "node ";
  label += std::to_string(node);
  return label;
}

ClipMatch match_clips(const Asset& a, const Asset& b, const std::vector<size_t>& selected) {
  ClipMatch match;
  if (a.clips.empty() && b.clips.empty()) {
    match.pairs.push_back({});
    return match;
  }
  std::vector<int> partner(selected.size(), -1);
  std::vector<bool> taken(b.clips.size(), false);
  // B's named clips by name, in index order (a map, so that thousands of clips pair in n log n).
  std::map<std::string, std::deque<size_t>> b_named;
  for (size_t c = 0; c < b.clips.size(); ++c)
    if (!b.clips[c].name.empty()) b_named[b.clips[c].name].push_back(c);
  // By name: the first unpaired clip of B with the same (non-empty) name. Only this pass takes clips
  // of B by name, so the first unpaired one is the first left in its list.
  for (size_t s = 0; s < selected.size(); ++s) {
    const std::string& name = a.clips[selected[s]].name;
    const auto same = name.empty() ? b_named.end() : b_named.find(name);
    if (same == b_named.end() || same->second.empty()) continue;
    partner[s] = int(same->second.front()), taken[same->second.front()] = true;
    same->second.pop_front();
  }
  // Then by index, for exporters that rename clips (or leave them unnamed).
  for (size_t s = 0; s < selected.size(); ++s) {
    const size_t index = selected[s];
    if (partner[s] >= 0 || index >= b.clips.size() || taken[index]) continue;
    const std::string& name = a.clips[index].name;
    const bool other_name_in_b = !name.empty() && b_named.count(name);
    if (other_name_in_b) continue;
    partner[s] = int(index), taken[index] = true;
    if (a.clips[index].name != b.clips[index].name)
      match.findings.push_back({DiffStatus::kPass, clip_label(a, int(index)),
                                "matched by index with B's clip " + clip_label(b, int(index)) + " (names differ)"});
  }
  for (size_t s = 0; s < selected.size(); ++s) {
    if (partner[s] >= 0)
      match.pairs.push_back({int(selected[s]), partner[s]});
    else
      match.findings.push_back({DiffStatus::kFail, clip_label(a, int(selected[s])), "clip in A only"});
  }
  if (selected.size() == a.clips.size())
    for (size_t c = 0; c < b.clips.size(); ++c)
      if (!taken[c]) match.findings.push_back({DiffStatus::kWarn, clip_label(b, int(c)), "clip in B only"});
  if (match.pairs.empty())
    throw InputError("no clip in common: A has " + clip_list(a) + "; B has " + clip_list(b));
  return match;
}

std::vector<AnimationFinding> compare_animations(const Asset& a, const Clip& clip_a, const Asset& b, const Clip& clip_b,
                                                 const std::string& label) {
  // Channels are keyed by what they animate, by node name: an optimizer renumbers nodes.
  using Key = std::tuple<std::string, int>;
  auto channels = [](const Asset& asset, const Clip& clip) {
    std::map<Key, const Channel*> map;
    for (const Channel& c : clip.channels) map.emplace(Key{node_label(asset, c.node), int(c.path)}, &c);
    return map;
  };
  const auto in_a = channels(a, clip_a), in_b = channels(b, clip_b);
  std::vector<AnimationFinding> notes;
  auto note = [&](const std::string& text) { notes.push_back({DiffStatus::kPass, label, text}); };
  auto name = [](const Key& key) {
    return std::get<0>(key) + " " + target_path_name(TargetPath(std::get<1>(key)));
  };

  if (std::abs(clip_a.last_key - clip_b.last_key) > 1e-5)
    note("duration " + seconds(clip_a.last_key) + " in A, " + seconds(clip_b.last_key) + " in B");
  for (const auto& [key, channel] : in_a) {
    const auto other = in_b.find(key);
    if (other == in_b.end()) {
      note("channel " + name(key) + " in A only (" + std::to_string(channel->times.size()) + " keys)");
      continue;
    }
    const Channel& c = *other->second;
    if (c.times.size() != channel->times.size())
      note("channel " + name(key) + ": " + std::to_string(channel->times.size()) + " keys in A, " +
           std::to_string(c.times.size()) + " in B");
    if (c.interpolation != channel->interpolation)
      note("channel " + name(key) + ": " + interpolation_name(channel->interpolation) + " in A, " +
           interpolation_name(c.interpolation) + " in B");
  }
  for (const auto& [key, channel] : in_b)
    if (!in_a.count(key)) note("channel " + name(key) + " in B only (" + std::to_string(channel->times.size()) + " keys)");
  return notes;
}

std::vector<double> comparison_times(const Clip* a, const Clip* b) {
  std::vector<double> keys;
  for (const Clip* clip : {a, b})
    if (clip)
      for (const Channel& c : clip->channels) keys.insert(keys.end(), c.times.begin(), c.times.end());
  if (keys.empty()) return {0.0};
  std::sort(keys.begin(), keys.end());
  // Float key times of resampled tracks differ in their last bits; 10 µs is far below any frame interval.
  std::vector<double> merged;
  for (double t : keys)
    if (merged.empty() || t - merged.back() > 1e-5) merged.push_back(t);
  std::vector<double> times;
  times.reserve(2 * merged.size());
  for (size_t i = 0; i < merged.size(); ++i) {
    if (i > 0) times.push_back(0.5 * (merged[i - 1] + merged[i]));
    times.push_back(merged[i]);
  }
  return times;
}

}  // namespace dqskin::diff_detail
