// Checks of a glTF file's container and JSON that must pass before tinygltf sees it (internal to the
// loader). tinygltf trusts some declared sizes: a GLB buffer of byteLength 0 or an image bufferView past
// its buffer make it index out of range or read past the end; it recurses once per level of JSON nesting;
// it reads any external file a URI names. These checks close those paths, so the loader never reads
// memory or files a file did not provide.
#pragma once

#include "dqskin/load.hpp"
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

// What a JSON text holds, counted in one linear pass over its bytes that skips strings, before anything
// parses it: values (each array element and member) and objects.
struct JsonShape {
  uint64_t values = 0, objects = 0;
};

// The shape of a JSON text. Throws InputError when it nests arrays and objects deeper than kMaxJsonDepth;
// nothing recursive.
JsonShape scan_json(std::span<const uint8_t> json);

// Memory that parsing a JSON text of this shape takes, an upper bound measured on the worst cases: our
// parse and tinygltf's hold a tree each (16 bytes a value and a node per member), tinygltf keeps extras as
// its Value (about 200 bytes each) and every object as a model struct (a Node is about 700 bytes). 2
// million empty nodes in 6 MB of text took 2.0 GB; 2 million zeros in extras 585 MB.
uint64_t json_memory(const JsonShape& shape, uint64_t text_bytes);

struct CheckedJson {
  nlohmann::json doc;  // null when the text is not a JSON object: tinygltf then reports it in its words
  std::vector<std::string> warnings;  // appearance removed (check_schema_values), images refused by the root
  bool changed = false;               // doc differs from the text: tinygltf must read doc, not the text
  uint64_t json_bytes = 0;            // json_memory() of the text
  uint64_t data_bytes = 0;            // what tinygltf will read or copy: buffers, and images once per image
  uint64_t decoded_bytes = 0;         // what decoding EXT_meshopt_compression views allocates
  std::vector<bool> dataless;         // per buffer: holds no data (meshopt.hpp); doc has a placeholder instead
  std::vector<size_t> unviewed_indices;  // Draco primitives' indices accessors given a bufferView for tinygltf
};

// Parses the JSON (after scan_json, and refusing a text whose parse would take more than
// options.max_memory) and checks asset.version/minVersion, every integer the schema constrains
// (check_schema_values), every buffer's byteLength against options.max_file_bytes, that every buffer view
// and image view lies inside the byteLength its buffer declares, that every buffer's URI stays inside
// `root` (ResourceRoot::check; missing is an error too), and that the JSON and the data tinygltf will read
// fit options.max_memory. An image URI that leaves the root is not read: a warning. URIs with '+' are
// rewritten so that tinygltf, which decodes '+' as a space, finds the file they name.
// EXT_meshopt_compression views are checked (meshopt.hpp check_meshopt_view) and their decoded bytes
// counted; buffers without data (meshopt.hpp) are neither checked against max_file_bytes nor read: each is
// replaced in doc by a one-byte data URI for tinygltf. `glb`: the text is a .glb's JSON chunk. Throws
// InputError.
CheckedJson precheck_json(std::span<const uint8_t> json, const LoadOptions& options, const ResourceRoot& root,
                          bool glb = false);

}  // namespace dqskin::gltf
