// One deformed frame as the writers see it (docs/DESIGN.md §2.5): float arrays
// per primitive of every mesh instance, whichever deformer produced them. The GPU path hands out
// DeformedBatches (many frames, float); the CPU reference DeformedFrames (one frame, double) are
// converted once, so every writer has one input type.
#pragma once

#include "dqskin/deformed_batch.hpp"
#include "dqskin/skinning.hpp"

#include <span>
#include <vector>

namespace dqskin {

// Borrowed arrays; the batch they come from must outlive the view.
struct PrimitiveView {
  size_t vertices = 0;
  std::span<const float> positions;  // 3 per vertex, world space
  std::span<const float> normals;    // 3 per vertex (unit), or empty when the primitive has none
  std::span<const float> tangents;   // 4 per vertex (xyz unit, w handedness ±1), or empty
};

// Every primitive of every instance, instances in order, primitives in mesh order (as deform_frame).
struct FrameView {
  std::vector<PrimitiveView> primitives;
};

// Frame `frame` (0-based within the batch) of a batch.
FrameView frame_view(const DeformedBatch& batch, size_t frame);

// CPU reference frames as one batch in float (frames must all have the same primitives).
DeformedBatch to_batch(std::span<const DeformedFrame> frames, size_t first_frame);

}  // namespace dqskin
