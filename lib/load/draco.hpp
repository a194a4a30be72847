// KHR_draco_mesh_compression (internal to the loader): primitives whose attributes and indices are a Draco
// mesh in a buffer view, decoded with Google's Draco library (the extension's reference codec). Spec:
// https://github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Khronos/KHR_draco_mesh_compression
//
// The decoded values are written in each accessor's own layout (componentType, normalized) into a buffer
// of their own, and the accessors pointed at them: from then on the primitive is read as an uncompressed
// one (mesh.cpp), with the same checks, and the .glb writer's copy of TEXCOORD_n and COLOR_n
// (source_document.hpp) sees them too. Morph targets are never compressed (the spec keeps them in ordinary
// accessors).
#pragma once

#include <tiny_gltf.h>

#include <cstdint>

namespace dqskin::gltf {

struct DracoEstimate {
  uint64_t decoded = 0;    // bytes written for the accessors (each accessor once)
  uint64_t transient = 0;  // the largest Draco mesh while it is decoded
};

// What decode_draco() will allocate, from the accessors' declared counts: decode_draco() holds libdraco to
// it, refusing a stream whose counts (faces, points, attributes and their components) exceed what the
// accessors declare before libdraco allocates for them.
DracoEstimate estimate_draco(const tinygltf::Model& model);

// Decodes every primitive with the extension. Its `attributes` map names the unique ids of the Draco
// attributes; each must exist with the accessor's number of components, and the accessors' counts must be
// the decoded point count (attributes) and three times the face count (indices). Throws InputError
// ("mesh 0 primitive 1: KHR_draco_mesh_compression ...").
void decode_draco(tinygltf::Model& model);

}  // namespace dqskin::gltf
