// What a vertex-animation texture must know before its first texel (internal to lib/texture and lib/bake):
// measured over every frame of the clip, in order. The bounds of the stored values (what the remap maps to
// [0, 1]), each frame's and the clip's bounds of the animated mesh (for culling), and whether the clip
// loops. For houdini the first frame becomes the rest the offsets are taken from.
#pragma once

#include "vat_side_files.hpp"

#include <vector>

namespace dqskin::texture {

class VatMeasure {
public:
  // `encoding` must hold the layout and, for openvat, the rest positions; houdini's are set from frame 0.
  explicit VatMeasure(VatEncoding& encoding) : e_(encoding) {}
  // Several clips (docs/DESIGN.md §4.9): frame ranges whose loops are measured each; without, one clip of
  // every frame.
  VatMeasure(VatEncoding& encoding, const std::vector<VatClipEntry>& clips);

  // Frame f of `frames`, in order from 0.
  void add(const FrameView& frame, size_t f, size_t frames);

  // The texture's figures, into `info` (frame_bounds, clip_bounds, loops; and each clip's loop in
  // info.clips, whose frame ranges must be set), and the remap bounds into the encoding when the format
  // remaps (decimal_bounds of what is stored; houdini's embedded bounds).
  void finish(VatClipInfo& info, const std::string& what);

private:
  VatEncoding& e_;
  Box stored_;
  std::vector<Box> frame_bounds_;
  std::vector<std::pair<size_t, size_t>> clips_;  // first frame, frame count; empty: one clip
  std::vector<float> first_;                       // the current clip's first frame
  std::vector<double> loop_gaps_;                  // per clip: how far its last pose is from its first
  size_t frames_ = 0;
};

// Every position of a frame, 3 floats per vertex in the VAT's vertex order.
std::vector<float> all_positions(const FrameView& frame);

}  // namespace dqskin::texture
