// Loading glTF 2.0 files into an Asset (docs/DESIGN.md §5).
#pragma once

#include "dqskin/asset.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace dqskin {

// The default of LoadOptions::max_memory and of the commands' --max-memory: 2 GiB, so that a hostile file
// is refused well before it can exhaust a build machine, while the largest real characters (a million
// vertices with morph targets, a few hundred megabytes decoded) load.
inline constexpr uint64_t kDefaultMaxMemory = uint64_t(2) << 30;

struct LoadOptions {
  // Most values (count × components) accepted for an accessor that has no buffer behind it (a sparse
  // accessor without bufferView is "all zeros plus a few values": its count costs memory, not file bytes).
  uint64_t max_unbacked_elements = uint64_t(1) << 26;
  // Largest file, and largest external buffer, that is read (bytes).
  uint64_t max_file_bytes = uint64_t(4) << 30;
  // Most memory loading may take, estimated before each step from what the file declares: the file itself,
  // parsing its JSON (from the text's shape), the buffers and images tinygltf reads (from their declared
  // sizes), and decoding (every use of an accessor counted, morph targets, animation keys, nodes).
  uint64_t max_memory = kDefaultMaxMemory;
  // The caller decodes the images (the renderer): their declared sizes (RGBA, 8 bits) count toward
  // max_memory too.
  bool decoded_images = false;
  // Keep what a .glb frame writer copies from the file (Asset::source), so that it never reads the file
  // again: the checked JSON and every TEXCOORD_n and COLOR_n attribute. Off, the JSON is freed after loading.
  bool keep_source = false;
  // Folders besides the model's own that its external buffers and images may come from (--resource-root).
  // A URI that resolves anywhere else, by "..", an absolute path or a symbolic link, is refused.
  std::vector<std::string> resource_roots;
  // --max-influences: when 1 or more, every vertex of a primitive where some vertex has more joints with
  // weight than this keeps only the `max_influences` largest (its influences merged per joint first, ties
  // to the lower joint index), sorted by weight and renormalized to sum 1, as `lint --fix` writes them;
  // 0 keeps them all. At most kMaxInfluences.
  int max_influences = 0;
  // Throw the first of Asset::cannot_deform. The commands that only describe a file (info, lint) turn it
  // off: they report what they find in every file a viewer opens, and only the commands that deform refuse.
  bool refuse_undeformable = true;
};

// Loads a .gltf (external or data-URI buffers) or .glb file. Images are not decoded. Throws InputError
// with a one-line message naming the problem (not the file) when the file is not a valid glTF 2.0 asset
// that dqskin can deform: unreadable or truncated, not a regular file, malformed or too deeply nested JSON,
// an integer the schema constrains out of its range, indices out of range, data that does not fit its
// buffer, NaN or infinite values, mismatched counts, non-increasing key times, unsupported required
// extensions, an external file outside the resource root, or more memory than options.max_memory.
//
// Primitives without NORMAL get smooth, area-weighted vertex normals. The specification asks viewers for
// flat normals; those split every vertex, which would break dqskin's promise that its outputs keep the
// accessor's vertex order and count (vertex-animation textures, per-vertex comparisons). A renderer can
// still shade such primitives flat; Primitive::normals_generated says which they are.
Asset load_asset(const std::string& path, const LoadOptions& options = {});

// The same from bytes in memory (a .glb when they start with the GLB magic, else .gltf JSON). External
// buffers are looked up in base_dir; name is only used in messages.
Asset load_asset_from_memory(std::span<const uint8_t> bytes, const std::string& name, const std::string& base_dir,
                             const LoadOptions& options = {});

// Whether `path` holds a glTF file, judged by its bytes as load_asset judges them, not by its name: a .vrm
// (a GLB), a .glb saved as .bin or without an extension, a .gltf under another name. True for a regular
// file that starts with the GLB magic "glTF" (§4.4.2) or whose text opens with '{' (a glTF document is a
// JSON object, §5.1), and for any name ending in .gltf or .glb (any case), whatever it holds, so that the
// loader says what such a file is instead. False for folders, files it cannot open, and other files
// (images), which the callers (diff) treat otherwise.
bool is_gltf_file(const std::string& path);

}  // namespace dqskin
