// The triangles of a mesh primitive, for everything that draws or writes faces (renderer, PLY/OBJ, glb)
// and for the loader's generated normals. Nothing here depends on how the asset was loaded.
#pragma once

#include "dqskin/asset.hpp"

#include <cstdint>
#include <vector>

namespace dqskin {

// The vertex indices of each triangle of a triangle-mode primitive (list, strip or fan), in the order
// that keeps the front face (glTF §3.7.2.1 for strips: odd triangles are swapped); empty for other modes.
std::vector<uint32_t> triangle_list(const Primitive& primitive);

// Smooth vertex normals of a triangle primitive: each triangle's area-weighted normal summed at its
// vertices, normalised; vertices on no (non-degenerate) triangle get +z. Handles all three triangle modes.
std::vector<glm::vec3> smooth_normals(const Primitive& primitive);

}  // namespace dqskin
