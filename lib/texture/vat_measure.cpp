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

void VatMeasure::add(const FrameView& frame, size_t f, size_t frames) {
  assert(f == frame_bounds_.size());
  frames_ = frames;
  if (f == 0) {
    first_ = all_positions(frame);
    if (e_.layout.format.profile == VatProfile::kHoudini) e_.rest = first_;
  }
  Box box;
  size_t v = 0;
  for (const PrimitiveView& p : frame.primitives)
    for (size_t i = 0; i < p.vertices; ++i, ++v) {
      const glm::vec3 position(p.positions[3 * i], p.positions[3 * i + 1], p.positions[3 * i + 2]);
      box.add(glm::dvec3(position));
      stored_.add(stored_position(e_, v, position));
      if (f + 1 == frames)
        loop_gap_ = std::max(loop_gap_, glm::length(glm::dvec3(position) -
                                                    glm::dvec3(first_[3 * v], first_[3 * v + 1], first_[3 * v + 2])));
    }
  frame_bounds_.push_back(box);
}

void VatMeasure::finish(VatClipInfo& info, const std::string& what) {
  info.frame_bounds = frame_bounds_;
  info.clip_bounds = Box();
  for (const Box& b : frame_bounds_) info.clip_bounds.add(b);
  // A clip loops when its last pose is its first, to a millionth of its size (float noise aside).
  info.loops = frames_ > 1 && loop_gap_ <= 1e-6 * info.clip_bounds.diagonal();
  const VatFormat& f = e_.layout.format;
  e_.stored = stored_;
  e_.remapped = f.profile == VatProfile::kOpenVat || is_png(f.type);
  if (e_.remapped)
    e_.bounds = f.profile == VatProfile::kHoudini ? houdini_encoded_bounds(info.clip_bounds, e_.layout, what)
                                                  : decimal_bounds(stored_);
}

}  // namespace dqskin::texture
