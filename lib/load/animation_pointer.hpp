// KHR_animation_pointer (internal to lib/load): a channel whose target.path is "pointer" names the
// property it animates with a JSON pointer (RFC 6901) in target.extensions.KHR_animation_pointer.pointer,
// and has no target.node. dqskin animates the pointers that mean what an ordinary channel means: a node's
// translation, rotation, scale or weights, and a mesh's (default) weights; every other one (materials,
// cameras, lights, extensions' properties) is recognised and left to the caller to ignore.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <tiny_gltf.h>

#include <cstddef>
#include <string>
#include <string_view>

namespace dqskin::gltf {

enum class PointerProperty { kNodeTranslation, kNodeRotation, kNodeScale, kNodeWeights, kMeshWeights, kOther };

// What a pointer names. `index` is the node or mesh index for the supported properties (not checked
// against the file); `problem` is non-empty when the string is not a JSON pointer, or names a node or mesh
// by something that is not an array index ("/nodes/01/rotation", "/nodes/x/scale"): the extension asks
// that a pointer name a property the asset defines, so such a pointer is an error, not an ignored one.
struct AnimationPointer {
  PointerProperty property = PointerProperty::kOther;
  size_t index = 0;
  std::string problem;
};
AnimationPointer parse_animation_pointer(std::string_view pointer);

// The pointer string of a channel (target.extensions.KHR_animation_pointer.pointer), or nullptr when the
// channel has none or it is not a string.
const std::string* channel_pointer(const tinygltf::AnimationChannel& channel);

// tinygltf drops a channel whose target has no "node" (it reads node as required) and with it the
// pointer, which would also renumber the channels after it. This rebuilds every animation's channels of
// `model` from `doc`, the JSON it was parsed from: sampler and node (-1 when absent), path ("" when absent
// or not a string) and the KHR_animation_pointer pointer when it is a string.
void restore_channels(tinygltf::Model& model, const nlohmann::json& doc);

}  // namespace dqskin::gltf
