// Reading a file's animations into Asset::clips (internal to lib/load): every channel checked as glTF 2.0
// §3.11 and §5.5-5.8 ask, KHR_animation_pointer channels that animate nodes and meshes read as ordinary
// ones, and channels that repeat a target found.
#pragma once

#include "accessor.hpp"
#include "animation_origins.hpp"
#include "dqskin/asset.hpp"

#include <tiny_gltf.h>

namespace dqskin::gltf {

// Appends one Clip per animation of `model` to asset.clips. The nodes must already be read (channels are
// checked against them). Adds to asset.warnings one line per animation with identical duplicates (their
// count) and one per animation with ignored KHR_animation_pointer channels (their pointers), and to
// asset.cannot_deform one line per pair of different duplicates. Throws InputError naming the animation,
// the channel or sampler and the rule for anything else that breaks §3.11 or KHR_animation_pointer.
AnimationOrigins read_animations(const tinygltf::Model& model, const AccessorReader& reader, Asset& asset);

}  // namespace dqskin::gltf
