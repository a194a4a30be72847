// Materials, textures, samplers, images and cameras (internal to the loader): what the renderer and the
// mesh writers need of a file's appearance, every index checked.
#pragma once

#include "dqskin/asset.hpp"

#include <tiny_gltf.h>

namespace dqskin::gltf {

// Fills asset.materials, textures, images and cameras (meshes must be read already: their material
// indices are checked here). Never throws for a bad value or reference here: that part is dropped (or
// its default used) and asset.warnings names the object and the problem.
void read_appearance(const tinygltf::Model& model, Asset& asset);

}  // namespace dqskin::gltf
