// Decoding of mesh primitives (internal to the loader).
#pragma once

#include "accessor.hpp"
#include "dqskin/asset.hpp"

namespace dqskin::gltf {

// Fills asset.meshes from the model: attributes, indices, skin influences, morph targets, generated
// normals. Checks every accessor; throws InputError.
void read_meshes(const tinygltf::Model& model, const AccessorReader& reader, Asset& asset);

// Smooth vertex normals of a triangle primitive: each triangle's area-weighted normal summed at its
// vertices, normalised; vertices on no (non-degenerate) triangle get +z. Handles all three triangle modes.
std::vector<glm::vec3> smooth_normals(const Primitive& primitive);

// The vertex indices of each triangle of a triangle-mode primitive (list, strip or fan), in the order
// that keeps the front face (§3.7.2.1 for strips: odd triangles are swapped).
std::vector<uint32_t> triangle_list(const Primitive& primitive);

}  // namespace dqskin::gltf
