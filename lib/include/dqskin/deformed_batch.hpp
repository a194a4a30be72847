// What the "deform" stage of docs/DESIGN.md §2.5 hands to the writers and the renderer, whichever deformer
// (GPU or CPU reference) made it: the deformed vertices of consecutive frames, as float arrays.
#pragma once

#include <cstddef>
#include <vector>

namespace dqskin {

// The deformed vertices of several consecutive frames, for every primitive of every instance (in the
// order of deform_frame). Arrays are frame-major: positions[(f · vertices + v) · 3 + c].
struct DeformedBatch {
  size_t first_frame = 0;
  size_t frame_count = 0;
  struct Primitive {
    size_t vertices = 0;
    std::vector<float> positions;  // 3 per vertex
    std::vector<float> normals;    // 3 per vertex, or empty
    std::vector<float> tangents;   // 4 per vertex (w handedness), or empty
  };
  std::vector<Primitive> primitives;
};

}  // namespace dqskin
