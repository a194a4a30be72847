// Decoding of mesh primitives (internal to the loader).
#pragma once

#include "accessor.hpp"
#include "dqskin/asset.hpp"

namespace dqskin::gltf {

// Fills asset.meshes from the model: attributes, indices, skin influences, morph targets, generated
// normals. Checks every accessor; throws InputError.
void read_meshes(const tinygltf::Model& model, const AccessorReader& reader, Asset& asset);

}  // namespace dqskin::gltf
