// Checks of a glTF file's container and JSON that must pass before tinygltf sees it (internal to the
// loader). tinygltf trusts some declared sizes: a GLB buffer of byteLength 0 or an image bufferView past
// its buffer make it index out of range or read past the end; it recurses once per level of JSON nesting;
// it reads any external file a URI names. These checks close those paths, so the loader never reads
// memory or files a file did not provide.
#pragma once

#include "resource_root.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace dqskin::gltf {

// The most levels of arrays and objects a file's JSON may nest. glTF itself needs about ten (a texture
// transform inside a material's texture inside an extension); extras may add some. tinygltf's parser
// recurses once per level and overflows the stack somewhere past ten thousand.
inline constexpr size_t kMaxJsonDepth = 128;

// The JSON part of a .glb (after checking its header and chunk layout, glTF 2.0 §4.4) or the whole of a
// .gltf. Never reads outside `bytes`. Throws InputError.
std::span<const uint8_t> json_chunk(std::span<const uint8_t> bytes, bool glb);

// Throws InputError when the JSON text nests arrays and objects deeper than kMaxJsonDepth. One linear pass
// over the bytes that skips strings; nothing recursive.
void check_nesting(std::span<const uint8_t> json);

struct CheckedJson {
  nlohmann::json doc;  // null when the text is not a JSON object: tinygltf then reports it in its words
  std::vector<std::string> warnings;  // appearance values that were removed (check_schema_values)
  bool changed = false;               // doc differs from the text: tinygltf must read doc, not the text
};

// Parses the JSON (after check_nesting) and checks asset.version/minVersion, every integer the schema
// constrains (check_schema_values), every buffer's byteLength against max_buffer_bytes, that every buffer
// view and image view lies inside the byteLength its buffer declares, and that every external URI stays
// inside `root` (ResourceRoot::check; a missing buffer file is an error, a missing image a warning of the
// loader). Throws InputError.
CheckedJson precheck_json(std::span<const uint8_t> json, uint64_t max_buffer_bytes, const ResourceRoot& root);

}  // namespace dqskin::gltf
