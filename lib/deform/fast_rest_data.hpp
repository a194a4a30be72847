// What the fast CPU kernel reads (internal to lib/deform): each primitive's rest data in structure-of-arrays
// blocks, and a frame's palette in the kernel's layout.
#pragma once

#include "dqskin/skinning.hpp"
#include "fast_kernel.hpp"

#include <vector>

namespace dqskin::deform {

// One primitive of one mesh instance, owning the arrays its `view` points into (so not copyable: the
// view would point into the source).
struct RestPrimitive {
  size_t instance = 0;  // index into the deformer's instances
  size_t vertices = 0;
  std::vector<float> arrays;          // positions, normals, tangents, weights: blocks · kLanes each
  std::vector<int32_t> joints;        // [k][vertex]
  std::vector<std::vector<float>> morph;  // per target and part (position, normal, tangent) present: 3 arrays
  std::vector<const float*> morph_pointers;
  KernelPrimitive view;

  RestPrimitive() = default;
  RestPrimitive(const RestPrimitive&) = delete;
  RestPrimitive& operator=(const RestPrimitive&) = delete;
  RestPrimitive(RestPrimitive&&) = default;  // vector moves keep their buffers, so the view stays valid

  bool has_normals() const { return view.normal[0] != nullptr; }
  bool has_tangents() const { return view.tangent[0] != nullptr; }
  size_t output_bytes_per_frame() const { return vertices * (12u + (has_normals() ? 12u : 0u) + (has_tangents() ? 16u : 0u)); }
};

// Every primitive of every instance, in deform_frame's order. Influences are gathered as the reference
// does (weights > 0, divided by their sum in double), the largest first; a vertex with no weight at all
// points at the palette's last entry, the identity. Throws InputError for a joint index outside its skin.
std::vector<RestPrimitive> make_rest_data(const Asset& asset, const std::vector<MeshInstance>& instances);

// Packs `joints` into `palette` (joints + 1 entries, the last the identity) for `mode`, and says which
// kernel reads it: lbs reads matrices, dqs the rigid parts and, when any joint is non-rigid, S.
KernelMode pack_palette(const JointTransforms& joints, BlendMode mode, std::vector<float>& palette);

}  // namespace dqskin::deform
