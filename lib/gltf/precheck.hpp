// Checks of a glTF file's container and JSON that must pass before tinygltf sees it (internal to the
// loader). tinygltf trusts some declared sizes: a GLB buffer of byteLength 0 or an image bufferView past
// its buffer make it index out of range or read past the end. These checks close those paths, so the
// loader never reads memory a file did not provide.
#pragma once

#include <cstdint>
#include <span>

namespace dqskin::gltf {

// The JSON part of a .glb (after checking its header and chunk layout, glTF 2.0 §4.4) or the whole of a
// .gltf. Throws InputError.
std::span<const uint8_t> json_chunk(std::span<const uint8_t> bytes, bool glb);

// Checks asset.version/minVersion, and that every buffer view and image view lies inside the byteLength
// its buffer declares. Throws InputError; returns quietly for JSON it cannot parse (tinygltf then reports).
void precheck_json(std::span<const uint8_t> json, uint64_t max_buffer_bytes);

}  // namespace dqskin::gltf
