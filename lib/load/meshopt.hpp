// EXT_meshopt_compression (internal to the loader): buffer views whose bytes are stored compressed in
// another buffer, decoded with meshoptimizer (the extension's reference codec) into the uncompressed bytes
// the accessors then read as usual. Spec:
// https://github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Vendor/EXT_meshopt_compression
//
// A buffer may hold no data: a fallback buffer (extensions.EXT_meshopt_compression.fallback: true) or one
// without uri that is not a .glb's BIN chunk (only buffer 0 of a .glb is). tinygltf 2.7 cannot be told
// so: it fails on a .gltf buffer without uri, and in a .glb it copies the BIN chunk into every buffer
// without uri (wrong data for buffer 1 and up, or an error when the fallback's byteLength exceeds the
// chunk). Such buffers are only ever addressed by compressed views, so precheck lists them, parse_model
// gives tinygltf a one-byte placeholder for each, and decode_meshopt() points the views at their decoded
// bytes; nothing reads the placeholder.
#pragma once

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <cstdint>
#include <vector>

namespace dqskin::gltf {

// Which buffers hold no data (see above), per buffer. `glb`: the file is a .glb (its buffer 0 without uri
// is the BIN chunk). The document's values have passed check_schema_values.
std::vector<bool> dataless_buffers(const nlohmann::json& doc, bool glb);

// Checks bufferView `view`'s EXT_meshopt_compression object, if any, against the spec's rules: required
// properties, mode and filter names, byteStride × count == the view's byteLength, the stride each mode and
// filter allows, the compressed range inside a buffer with data (byteLength as declared). A view without
// the extension must not use a dataless buffer. Returns the bytes decoding it allocates (its byteLength), 0
// without the extension. Throws InputError ("bufferView 3: EXT_meshopt_compression ...").
uint64_t check_meshopt_view(const nlohmann::json& doc, size_t view, const std::vector<uint64_t>& buffer_lengths,
                            const std::vector<bool>& dataless);

// Decodes every compressed view of `model` (read from `doc`, the JSON precheck checked and tinygltf read)
// into a buffer of its own appended to model.buffers, and points the view at it (byteOffset 0). Placeholder
// buffers of `dataless` are emptied. Throws InputError ("bufferView 3: EXT_meshopt_compression data is
// malformed (...)").
void decode_meshopt(tinygltf::Model& model, const nlohmann::json& doc, const std::vector<bool>& dataless);

}  // namespace dqskin::gltf
