// The source file's appearance and fixed attributes for the .glb writer (glb_appearance.hpp). Objects are
// copied as JSON, so that properties dqskin does not model (extensions, extras) survive; every index in
// them is checked, and a reference to something that was not copied is removed rather than left dangling.
#include "glb_appearance.hpp"

#include "../asset/source_document.hpp"
#include "../base/byte_size.hpp"
#include "dqskin/error.hpp"
#include "dqskin/version.hpp"
#include "vertex_sharing.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>

namespace dqskin::glb {
namespace {

static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian (§3.6.1)");

// The array `key` of `doc`, or an empty one.
json array_of(const json& doc, const char* key) {
  const auto it = doc.find(key);
  return it != doc.end() && it->is_array() ? *it : json::array();
}

// The entry `key` of an object, or null.
json member(const json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  const auto it = object.find(key);
  return it == object.end() ? json() : *it;
}

// The new index of `value` through `map` (old index → new index or -1), or -1 when it is not an index.
int remap(const json& value, const std::vector<int>& map) {
  if (!value.is_number_integer()) return -1;
  const int64_t i = value.get<int64_t>();
  return i >= 0 && uint64_t(i) < map.size() ? map[size_t(i)] : -1;
}

bool is_index(const json& value, size_t size) {
  return value.is_number_integer() && value.get<int64_t>() >= 0 && uint64_t(value.get<int64_t>()) < size;
}

// The image format by its signature: what §3.8.2 ("Images") and the image extensions allow.
std::string sniff_mime_type(const std::vector<uint8_t>& b) {
  auto starts = [&](std::initializer_list<unsigned char> magic, size_t at = 0) {
    return b.size() >= at + magic.size() && std::equal(magic.begin(), magic.end(), b.begin() + std::ptrdiff_t(at));
  };
  if (starts({0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A})) return "image/png";
  if (starts({0xFF, 0xD8, 0xFF})) return "image/jpeg";
  if (starts({'R', 'I', 'F', 'F'}) && starts({'W', 'E', 'B', 'P'}, 8)) return "image/webp";  // EXT_texture_webp
  if (starts({0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, 0x0D, 0x0A, 0x1A, 0x0A})) return "image/ktx2";  // KHR_texture_basisu
  return "";
}

// The image's format: its signature, else the mime type the file states; empty when neither says.
std::string image_mime_type(const EncodedImage& image) {
  const std::string sniffed = sniff_mime_type(image.bytes);
  return sniffed.empty() ? image.mime_type : sniffed;
}

// Images: bytes from a bufferView, a data URI or an external file (the loader read them, from inside the
// resource root only, into Asset::images). Embedded, they go into the BIN chunk, as a .glb has no folder
// beside it that it must be moved with, and the validator discourages data URIs in a GLB (DATA_URI_GLB);
// shared, they become files (out.image_files) that the image references by a URI relative to the .glb
// (§3.8.3; mimeType kept, as a reader may use it); with none, every image is left out. An image that
// could not be read, or whose format is unknown, is dropped.
std::vector<int> copy_images(const json& src, const std::vector<EncodedImage>& loaded, GlbImages mode, Appearance& out) {
  const json images = array_of(src, "images");
  std::vector<int> map(images.size(), -1);
  json copied = json::array();
  for (size_t i = 0; i < images.size() && mode != GlbImages::kNone; ++i) {
    json image = images[i].is_object() ? images[i] : json::object();
    const EncodedImage empty;
    const EncodedImage& bytes = i < loaded.size() ? loaded[i] : empty;
    const std::string mime = image_mime_type(bytes);
    if (bytes.bytes.empty() || mime.empty()) continue;
    image.erase("uri");
    image.erase("bufferView");
    if (mode == GlbImages::kShared) {
      image["uri"] = shared_image_name(bytes, i);
      out.image_files.push_back({image["uri"].get<std::string>(), std::string(bytes.bytes.begin(), bytes.bytes.end())});
    } else {
      image["bufferView"] = out.bin.view(bytes.bytes.data(), bytes.bytes.size(), 0);
    }
    image["mimeType"] = mime;  // required with a bufferView (§5.17)
    map[i] = int(copied.size());
    copied.push_back(std::move(image));
  }
  out.doc["images"] = std::move(copied);
  return map;
}

// Textures: the image (`source`, and the `source` of extensions such as EXT_texture_webp) and the
// sampler are checked. A texture that pointed at images of which none is left is dropped.
std::vector<int> copy_textures(const json& src, const std::vector<int>& image_map, size_t samplers, Appearance& out) {
  const json textures = array_of(src, "textures");
  std::vector<int> map(textures.size(), -1);
  json copied = json::array();
  for (size_t t = 0; t < textures.size(); ++t) {
    json texture = textures[t].is_object() ? textures[t] : json::object();
    bool had_image = false, has_image = false;
    auto fix_source = [&](json& object) {  // false when the reference must go
      if (!object.contains("source")) return true;
      had_image = true;
      const int s = remap(object["source"], image_map);
      if (s < 0) return false;
      object["source"] = s;
      has_image = true;
      return true;
    };
    if (!fix_source(texture)) texture.erase("source");
    if (texture.contains("extensions") && texture["extensions"].is_object()) {
      std::vector<std::string> gone;
      for (auto& [name, extension] : texture["extensions"].items())
        if (extension.is_object() && !fix_source(extension)) gone.push_back(name);
      for (const std::string& name : gone) texture["extensions"].erase(name);
      if (texture["extensions"].empty()) texture.erase("extensions");
    }
    if (had_image && !has_image) continue;
    if (texture.contains("sampler") && !is_index(texture["sampler"], samplers)) texture.erase("sampler");
    map[t] = int(copied.size());
    copied.push_back(std::move(texture));
  }
  out.doc["textures"] = std::move(copied);
  return map;
}

// Every textureInfo in a material, core or extension (§5.22 and the KHR_materials_* schemas name them all
// "...Texture": baseColorTexture, normalTexture, clearcoatTexture …), gets its texture's new index; one
// whose texture was dropped is removed. Extras are the application's and left alone.
void remap_texture_infos(json& object, const std::vector<int>& texture_map) {
  std::vector<std::string> gone;
  for (auto& [key, value] : object.items()) {
    if (!value.is_object() || key == "extras") continue;
    if (key.ends_with("Texture") && value.contains("index")) {
      const int t = remap(value["index"], texture_map);
      if (t < 0) gone.push_back(key);
      else value["index"] = t;
    } else {
      remap_texture_infos(value, texture_map);
    }
  }
  for (const std::string& key : gone) object.erase(key);
}

// Node extensions whose properties index data that the frame does not copy (accessors, other nodes).
bool copies_node_extension(const std::string& name) { return name != "EXT_mesh_gpu_instancing" && name != "MSFT_lod"; }

std::vector<FixedPrimitive> fixed_primitives(const Asset& asset, const std::vector<SourcePrimitive>& source,
                                             const json& src_mesh, size_t m, size_t materials, BinWriter& bin) {
  std::vector<FixedPrimitive> out;
  const json src_prims = member(src_mesh, "primitives");
  const std::vector<size_t> owners = vertex_data_owners(asset.meshes[m]);
  for (size_t p = 0; p < asset.meshes[m].primitives.size(); ++p) {
    const Primitive& prim = asset.meshes[m].primitives[p];
    if (!source.at(p).error.empty()) throw InputError(source[p].error);
    FixedPrimitive fixed;
    if (owners[p] != p) {
      fixed.attributes = out[owners[p]].attributes;  // the same accessors in the source: written once
    } else {
      for (const SourceAttribute& a : source[p].attributes)
        fixed.attributes[a.name] =
            bin.floats(a.values, a.count, a.components == 2 ? "VEC2" : a.components == 3 ? "VEC3" : "VEC4");
    }
    if (!prim.indices.empty()) fixed.indices = bin.indices(prim.indices);
    if (prim.material >= 0 && size_t(prim.material) < materials) fixed.material = prim.material;
    const json src_prim = src_prims.is_array() && p < src_prims.size() ? src_prims[p] : json();
    fixed.extras = member(src_prim, "extras");
    if (const json variants = member(member(src_prim, "extensions"), "KHR_materials_variants"); !variants.is_null())
      fixed.extensions = {{"KHR_materials_variants", variants}};
    out.push_back(std::move(fixed));
  }
  return out;
}

}  // namespace

std::string shared_image_name(const EncodedImage& image, size_t index) {
  const std::string mime = image_mime_type(image);
  if (image.bytes.empty() || mime.empty()) return {};
  static const std::pair<const char*, const char*> extensions[] = {
      {"image/png", "png"}, {"image/jpeg", "jpg"}, {"image/webp", "webp"}, {"image/ktx2", "ktx2"}};
  const char* extension = "bin";
  for (const auto& [type, ext] : extensions)
    if (mime == type) extension = ext;
  return "image_" + std::to_string(index) + "." + extension;
}

Appearance read_appearance(const Asset& asset, const std::vector<MeshInstance>& instances, int scene, GlbImages images) {
  if (!asset.source) throw std::invalid_argument("GlbWriter: the asset was loaded without LoadOptions::keep_source");
  // The JSON as the loader checked it: appearance values it refused are gone here too.
  const json& src = asset.source->json;

  Appearance out;
  json asset_info = {{"version", "2.0"}, {"generator", std::string("dqskin ") + kVersion}};
  const json src_asset = member(src, "asset");
  for (const char* key : {"copyright", "extras"})
    if (!member(src_asset, key).is_null()) asset_info[key] = src_asset[key];
  out.doc["asset"] = asset_info;
  for (const char* key : {"extensions", "extras"})  // root extensions: KHR_lights_punctual lights, variants …
    if (!member(src, key).is_null()) out.doc[key] = src[key];
  // Without images no texture is left, nor a use for a sampler.
  out.doc["samplers"] = images == GlbImages::kNone ? json::array() : array_of(src, "samplers");
  out.doc["cameras"] = array_of(src, "cameras");

  const std::vector<int> image_map = copy_images(src, asset.images, images, out);
  const std::vector<int> texture_map = copy_textures(src, image_map, out.doc["samplers"].size(), out);
  json materials = array_of(src, "materials");
  for (json& material : materials) {
    if (!material.is_object()) material = json::object();
    remap_texture_infos(material, texture_map);
  }
  out.doc["materials"] = std::move(materials);
  for (const json& e : array_of(src, "extensionsRequired"))
    if (e.is_string()) out.source_extensions_required.push_back(e.get<std::string>());

  // Nodes: what the frame does not change; transforms, meshes, children are the writer's.
  const json src_nodes = array_of(src, "nodes");
  const size_t cameras = out.doc["cameras"].size();
  out.nodes.resize(asset.nodes.size());
  for (size_t n = 0; n < asset.nodes.size() && n < src_nodes.size(); ++n) {
    json& fields = out.nodes[n].fields;
    for (const char* key : {"name", "extras"})
      if (!member(src_nodes[n], key).is_null()) fields[key] = src_nodes[n][key];
    if (const json camera = member(src_nodes[n], "camera"); is_index(camera, cameras))
      fields["camera"] = camera;
    if (const json extensions = member(src_nodes[n], "extensions"); extensions.is_object()) {
      json kept = json::object();
      for (const auto& [name, value] : extensions.items())
        if (copies_node_extension(name)) kept[name] = value;
      if (!kept.empty()) fields["extensions"] = kept;
    }
  }
  if (scene >= 0) {
    const json src_scene = array_of(src, "scenes").at(size_t(scene));
    for (const char* key : {"name", "extras"})
      if (!member(src_scene, key).is_null()) out.scene_fields[key] = src_scene[key];
  }

  // The fixed attributes of each mesh that an instance draws, in the order instances first draw them.
  const json src_meshes = array_of(src, "meshes");
  out.meshes.resize(asset.meshes.size());
  out.mesh_extras.resize(asset.meshes.size());
  for (const MeshInstance& inst : instances) {
    const size_t m = size_t(inst.mesh);
    if (!out.meshes[m].empty()) continue;
    const json src_mesh = m < src_meshes.size() ? src_meshes[m] : json();
    out.meshes[m] = fixed_primitives(asset, asset.source->meshes.at(m), src_mesh, m, out.doc["materials"].size(), out.bin);
    out.mesh_extras[m] = member(src_mesh, "extras");
  }
  return out;
}

Appearance read_look(const Asset& asset) {
  Appearance all = read_appearance(asset, {}, -1, GlbImages::kEmbed);
  Appearance look;
  for (const char* key : {"materials", "textures", "samplers", "images"}) look.doc[key] = std::move(all.doc[key]);
  look.bin = std::move(all.bin);
  look.source_extensions_required = std::move(all.source_extensions_required);
  return look;
}

glm::vec3 unit_or(const glm::dvec3& n, const glm::vec3& fallback) {
  const double length = glm::length(n);
  if (!(length > 1e-30) || !std::isfinite(length)) return fallback;
  const glm::vec3 u(n / length);
  return std::abs(glm::length(u) - 1.0f) <= 1e-4f ? u : fallback;
}

}  // namespace dqskin::glb
