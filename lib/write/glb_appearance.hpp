// What a .glb frame takes from the source file unchanged (internal to lib/write, lib/texture and lib/bake: the
// glb frames, the morph-target animation and the VAT rest mesh): the appearance objects copied as JSON with
// every reference checked, the images' bytes, and the vertex attributes that do not move (texture
// coordinates, colours, indices), written once into the start of the BIN chunk. The container itself is
// asset/glb_container.hpp.
#pragma once

#include "../asset/glb_container.hpp"
#include "dqskin/asset.hpp"
#include "glb_output.hpp"
#include "dqskin/skinning.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace dqskin::glb {


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
