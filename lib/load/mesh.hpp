// Decoding of mesh primitives (internal to the loader).
#pragma once

#include "accessor.hpp"
#include "dqskin/asset.hpp"

#include <cstddef>
#include <string>

namespace dqskin::gltf {

// The highest n of the primitive's JOINTS_n and WEIGHTS_n attributes (n of up to 9 digits; longer names are
// not influence sets), or -1 when it has none. The loader and lint (skin_data.cpp) bound the sets with it.
int highest_influence_set(const tinygltf::Primitive& p);

// Why a skinned node's primitive without JOINTS_0/WEIGHTS_0 cannot be deformed (Asset::cannot_deform), in
// the words the loader and lint share.
std::string no_influences_reason(size_t node, int mesh, size_t primitive);

// Fills asset.meshes from the model: attributes, indices, skin influences, morph targets, generated
// normals. Checks every accessor; throws InputError.
void read_meshes(const tinygltf::Model& model, const AccessorReader& reader, Asset& asset);

}  // namespace dqskin::gltf
