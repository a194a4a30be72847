// The loader's checked reading of a file's structure without its meshes (internal to lib/load): for
// readers that need the node hierarchy, skins and animations exactly as the loader reads them, but read
// the mesh data themselves, more leniently (skin_data.cpp, which must see influences the loader refuses).
#pragma once

#include "animation_origins.hpp"
#include "dqskin/asset.hpp"
#include "dqskin/load.hpp"

#include <tiny_gltf.h>

#include <cstdint>
#include <string>

namespace dqskin::gltf {

// An Asset with nodes, scenes, skins and clips read and checked as load_asset reads them (required
// extensions, the memory estimate against options.max_memory, Draco primitives decoded in `model`), and
// no meshes or materials. `json_bytes`: what parsing the JSON took (ParsedModel). `animations`, when given,
// receives where each clip channel comes from and the duplicate channels (animations.hpp). Throws
// InputError.
Asset read_structure(tinygltf::Model& model, uint64_t json_bytes, const std::string& path, const LoadOptions& options,
                     AnimationOrigins* animations = nullptr);

}  // namespace dqskin::gltf
