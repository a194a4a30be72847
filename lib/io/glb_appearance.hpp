// What a .glb frame takes from the source file unchanged (internal to lib/io, lib/texture and lib/bake: the
// glb frames, the morph-target animation and the VAT rest mesh): the appearance objects copied as JSON with
// every reference checked, the images' bytes, and the vertex attributes that do not move (texture
// coordinates, colours, indices), written once into the start of the BIN chunk; and the pieces every .glb
// writer shares (BinWriter, the container).
#pragma once

#include "dqskin/asset.hpp"
#include "dqskin/glb_output.hpp"
#include "dqskin/skinning.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace dqskin::glb {

using nlohmann::json;

// glTF bufferView.target values (§3.6.2.3 "Buffer views").
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
// accessor.componentType values (§3.6.2.2 "Accessor data types").
constexpr int kShort = 5122;
constexpr int kUnsignedShort = 5123;
constexpr int kUnsignedInt = 5125;
constexpr int kFloat = 5126;

// The GLB BIN chunk being filled and the bufferViews and accessors that describe it.
struct BinWriter {
  std::string bytes;
  json views = json::array();
  json accessors = json::array();

  // Appends `size` bytes as a bufferView of their own, starting on a 4-byte boundary (§3.6.2.4 "Data
  // alignment": every accessor offset must be a multiple of its component size). target 0 = none
  // (images). Returns the view's index.
  int view(const void* data, size_t size, int target);
  // A float accessor of `count` elements of `type` (VEC2 …) over `values`, in a view of its own.
  int floats(std::span<const float> values, size_t count, const char* type);
  // A POSITION accessor (VEC3 float) with the min and max that §3.7.2.1 requires, taken from the floats
  // written.
  int positions(std::span<const float> xyz);
  // Indices as UNSIGNED_SHORT when every index is below 65535, else UNSIGNED_INT: §3.7.2.1 forbids the
  // primitive-restart value (the type's largest) as an index.
  int indices(std::span<const uint32_t> indices);
};

// A .glb file (glTF 2.0 §4.4 "Binary glTF"): a 12-byte header, the JSON chunk padded with spaces, the BIN
// chunk (when not empty) padded with zeros, all little-endian. Throws OutputError past 4 GiB.
std::string glb_container(const json& doc, std::string bin);

// The same file in two parts that are written one after the other: the header, the JSON chunk and the BIN
// chunk's header, then the BIN chunk's bytes, never copied (a morph animation's run to gigabytes).
struct GlbParts {
  std::string head;
  std::string bin;
  size_t size() const { return head.size() + bin.size(); }
};
GlbParts glb_container_parts(const json& doc, std::string bin);

// The .glb of a document whose objects are complete but for the buffer: `bin`'s accessors, views and
// buffer go in, top-level arrays left empty are removed (§5.1 forbids empty ones), extensionsUsed lists
// every extension named in an `extensions` object (§3.12) and `own` (extensions the writer's data needs
// without naming them, such as KHR_mesh_quantization), and extensionsRequired those of `source_required`
// still used, then `own`.
GlbParts finish_glb_parts(json doc, BinWriter bin, const std::vector<std::string>& source_required,
                          const std::vector<std::string>& own = {});
// finish_glb_parts() as one string.
std::string finish_glb(json doc, BinWriter bin, const std::vector<std::string>& source_required,
                       const std::vector<std::string>& own = {});

// n normalised, or `fallback` when n has no direction: zero or non-finite, as degenerate triangles can give
// on the GPU. The validator requires unit normals and tangents (§3.7.2.1).
glm::vec3 unit_or(const glm::dvec3& n, const glm::vec3& fallback);

// A source primitive's attributes that stay the same in every frame.
struct FixedPrimitive {
  json attributes = json::object();  // TEXCOORD_n and COLOR_n → accessor index, decoded to float
  int indices = -1;                  // accessor index, or -1 when the source is not indexed
  int material = -1;                 // checked against the materials, or -1
  json extras;                       // null when none
  json extensions;                   // KHR_materials_variants only (its material indices stay valid)
};

// The parts of a node that do not depend on the frame (name, camera, extensions, extras).
struct FixedNode {
  json fields = json::object();
};

struct Appearance {
  json doc;  // asset, materials, textures, samplers, images, cameras, root extensions and extras
  BinWriter bin;  // embedded images, then the fixed attributes (their accessors and views are in `bin`)
  std::vector<GlbImageFile> image_files;  // GlbImages::kShared: the images the doc references by URI
  std::vector<std::vector<FixedPrimitive>> meshes;  // per source mesh; empty for meshes no instance draws
  std::vector<json> mesh_extras;                   // per source mesh (null when none)
  std::vector<FixedNode> nodes;                    // per source node
  json scene_fields = json::object();              // the chosen scene's name and extras
  std::vector<std::string> source_extensions_required;
};

// Prepares what every frame shares for the meshes that `instances` draw, from the asset and what its loader
// kept of the file (Asset::source; std::invalid_argument without it), its images placed as `images` says.
// Throws InputError when an attribute the frames copy (TEXCOORD_n, COLOR_n) could not be decoded.
Appearance read_appearance(const Asset& asset, const std::vector<MeshInstance>& instances, int scene,
                           GlbImages images = GlbImages::kEmbed);

// The source's look for a .glb that draws the source's primitives under materials of the same indices (the
// meshes beside textures, lib/texture): read_appearance's materials, textures, samplers and images (embedded
// in `bin`) and the source's required extensions; no nodes, meshes, cameras or root extensions.
Appearance read_look(const Asset& asset);

// The file name under which GlbImages::kShared writes image `index` of the asset: "image_<index>.<ext>"
// (png, jpg, webp, ktx2 by the bytes' signature, else by the mime type the file states; bin when neither
// names one of them), or empty when the image is not copied (no bytes, or no format known at all).
std::string shared_image_name(const EncodedImage& image, size_t index);

}  // namespace dqskin::glb
