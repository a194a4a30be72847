#include "vat_measure.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cassert>

namespace dqskin::texture {

std::vector<float> all_positions(const FrameView& frame) {
  std::vector<float> out;
  for (const PrimitiveView& p : frame.primitives) out.insert(out.end(), p.positions.begin(), p.positions.end());
  return out;
}

VatMeasure::VatMeasure(VatEncoding& encoding, const std::vector<VatClipEntry>& clips) : e_(encoding) {
  for (const VatClipEntry& c : clips) clips_.emplace_back(c.first_frame, c.frame_count);
}

void VatMeasure::add(const FrameView& frame, size_t f, size_t frames) {
  assert(f == frame_bounds_.size());
  frames_ = frames;
  if (clips_.empty()) clips_.emplace_back(0, frames);
  // The clip this frame is in: clips come in order, so it is the last that starts at or before f.
  size_t clip = 0;
  while (clip + 1 < clips_.size() && clips_[clip + 1].first <= f) ++clip;
  const auto [first, count] = clips_[clip];
  if (f == 0 && e_.layout.format.profile == VatProfile::kHoudini) e_.rest = all_positions(frame);
  if (f == first) first_ = all_positions(frame);
  const bool last = f + 1 == first + count;
  if (last) loop_gaps_.resize(clips_.size(), 0.0);
  Box box;
  size_t v = 0;
  for (const PrimitiveView& p : frame.primitives)
    for (size_t i = 0; i < p.vertices; ++i, ++v) {
      const glm::vec3 position(p.positions[3 * i], p.positions[3 * i + 1], p.positions[3 * i + 2]);
      box.add(glm::dvec3(position));
      stored_.add(stored_position(e_, v, position));
      if (last)
        loop_gaps_[clip] = std::max(loop_gaps_[clip], glm::length(glm::dvec3(position) -
                                                                  glm::dvec3(first_[3 * v], first_[3 * v + 1], first_[3 * v + 2])));
    }
  frame_bounds_.push_back(box);
}

void VatMeasure::finish(VatClipInfo& info, const std::string& what) {
  info.frame_bounds = frame_bounds_;
  info.clip_bounds = Box();
  for (const Box& b : frame_bounds_) info.clip_bounds.add(b);
  // A clip loops when its last pose is its first, to a millionth of the texture's size (float noise aside).
  loop_gaps_.resize(clips_.size(), 0.0);
  for (size_t c = 0; c < clips_.size(); ++c) {
    const bool loops = clips_[c].second > 1 && loop_gaps_[c] <= 1e-6 * info.clip_bounds.diagonal();
    if (c < info.clips.size()) info.clips[c].loops = loops;
    if (c == 0) info.loops = loops;
  }
  const VatFormat& f = e_.layout.format;
  e_.stored = stored_;
  e_.remapped = f.profile == VatProfile::kOpenVat || is_png(f.type);
  if (e_.remapped)
    e_.bounds = f.profile == VatProfile::kHoudini ? houdini_encoded_bounds(info.clip_bounds, e_.layout, what)
                                                  : decimal_bounds(stored_);
}

}  // namespace dqskin::texture
