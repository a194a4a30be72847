// Reading a file's animations into Asset::clips (internal to lib/gltf): every channel checked as glTF 2.0
// §3.11 and §5.5-5.7 ask, each sampler decoded once per channel that uses it.
#pragma once

#include "accessor.hpp"
#include "dqskin/asset.hpp"

#include <tiny_gltf.h>

namespace dqskin::gltf {

// Appends one Clip per animation of `model` to asset.clips. The nodes must already be read (channels are
// checked against them). Throws InputError naming the animation, the channel or sampler and the rule.
void read_animations(const tinygltf::Model& model, const AccessorReader& reader, Asset& asset);

}  // namespace dqskin::gltf
