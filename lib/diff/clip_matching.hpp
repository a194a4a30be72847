// Which clip of B is compared with which clip of A, at which times, and what the two files' animations
// already say before anything is deformed (internal to lib/diff).
#pragma once

#include "dqskin/asset.hpp"
#include "dqskin/geometry_diff.hpp"

#include <string>
#include <vector>

namespace dqskin::diff_detail {

// A clip of A and its partner in B; -1 on both sides for the rest pose (neither file animates).
struct ClipPair {
  int a = -1, b = -1;
};

struct ClipMatch {
  std::vector<ClipPair> pairs;              // in A's order
  std::vector<AnimationFinding> findings;   // unmatched clips, index matches with other names
};

// Pairs A's clips `selected` (indices into a.clips) with B's: by name first, then by index among the clips
// still unpaired. A selected clip without a partner is a failure finding, a B clip nobody selected and
// nobody paired a warning (only when every clip of A is selected). Throws InputError when no pair is left
// but one of the files animates ("no clip in common").
ClipMatch match_clips(const Asset& a, const Asset& b, const std::vector<size_t>& selected);

// What a report calls a clip: its name, or "#index" when it has none.
std::string clip_label(const Asset& asset, int clip);

// What a report calls a node: its name, or "node N" when it has none.
std::string node_label(const Asset& asset, int node);

// Notes on one pair: channels (node and path) animated in one file only, and per channel in both a
// changed key count or interpolation; and a changed duration. Notes do not fail a diff: optimizers drop
// constant tracks and resample on purpose. What they change is measured on the vertices.
std::vector<AnimationFinding> compare_animations(const Asset& a, const Clip& clip_a, const Asset& b, const Clip& clip_b,
                                                 const std::string& label);

// The default comparison times of a pair: every key time of either clip (times closer than 10 µs merged)
// and the midpoint between consecutive ones, where resampling and dropped keys show most. {0} for the
// rest pose.
std::vector<double> comparison_times(const Clip* a, const Clip* b);

}  // namespace dqskin::diff_detail
