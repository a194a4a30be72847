#include "dqskin/frame_view.hpp"

#include <cassert>

namespace dqskin {

FrameView frame_view(const DeformedBatch& batch, size_t frame) {
  assert(frame < batch.frame_count);
  FrameView view;
  view.primitives.reserve(batch.primitives.size());
  for (const DeformedBatch::Primitive& p : batch.primitives) {
    PrimitiveView v;
    v.vertices = p.vertices;
    auto slice = [&](const std::vector<float>& all, size_t per_vertex) {
      if (all.empty()) return std::span<const float>();
      return std::span<const float>(all).subspan(frame * p.vertices * per_vertex, p.vertices * per_vertex);
    };
    v.positions = slice(p.positions, 3);
    v.normals = slice(p.normals, 3);
    v.tangents = slice(p.tangents, 4);
    view.primitives.push_back(v);
  }
  return view;
}

DeformedBatch to_batch(std::span<const DeformedFrame> frames, size_t first_frame) {
  DeformedBatch batch;
  batch.first_frame = first_frame;
  batch.frame_count = frames.size();
  if (frames.empty()) return batch;
  batch.primitives.resize(frames[0].primitives.size());
  for (size_t i = 0; i < batch.primitives.size(); ++i) {
    DeformedBatch::Primitive& out = batch.primitives[i];
    out.vertices = frames[0].primitives[i].positions.size();
    for (const DeformedFrame& frame : frames) {
      const DeformedPrimitive& p = frame.primitives[i];
      for (const auto& x : p.positions) out.positions.insert(out.positions.end(), {float(x.x), float(x.y), float(x.z)});
      for (const auto& n : p.normals) out.normals.insert(out.normals.end(), {float(n.x), float(n.y), float(n.z)});
      for (const auto& t : p.tangents)
        out.tangents.insert(out.tangents.end(), {float(t.x), float(t.y), float(t.z), float(t.w)});
    }
  }
  return batch;
}

}  // namespace dqskin
