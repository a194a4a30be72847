#include "single_mesh_glb.hpp"

#include "dqskin/triangles.hpp"
#include "dqskin/version.hpp"

#include <algorithm>

namespace dqskin::texture {

using glb::json;

void add_topology(const Primitive& source, glb::BinWriter& bin, json& primitive) {
  if (const std::vector<uint32_t> triangles = triangle_list(source); !triangles.empty()) {
    primitive["indices"] = bin.indices(triangles);
    return;
  }
  if (!source.indices.empty()) primitive["indices"] = bin.indices(source.indices);
  primitive["mode"] = int(source.mode);  // glTF's primitive.mode values (§3.7.2.1)
}

int colors_accessor(const std::vector<glm::vec4>& colors, glb::BinWriter& bin) {
  std::vector<float> clamped;
  clamped.reserve(colors.size() * 4);
  for (const glm::vec4& c : colors)
    for (int k = 0; k < 4; ++k) clamped.push_back(std::clamp(c[k], 0.0f, 1.0f));
  return bin.floats(clamped, colors.size(), "VEC4");
}

bool has_materials(const glb::Appearance* look) {
  return look && look->doc.contains("materials") && !look->doc["materials"].empty();
}

void add_material(const Primitive& source, const glb::Appearance* look, json& primitive) {
  if (has_materials(look) && source.material >= 0 && size_t(source.material) < look->doc["materials"].size())
    primitive["material"] = source.material;
}

std::string single_mesh_glb(json primitives, glb::BinWriter bin, const std::string& name, const glb::Appearance* look) {
  json doc = {{"asset", {{"version", "2.0"}, {"generator", std::string("dqskin ") + kVersion}}},
              {"scene", 0},
              {"scenes", json::array({{{"nodes", {0}}}})},
              {"nodes", json::array({{{"name", name}, {"mesh", 0}}})},
              {"meshes", json::array({{{"name", name}, {"primitives", std::move(primitives)}}})}};
  if (has_materials(look)) {
    for (const char* key : {"materials", "textures", "samplers", "images"}) doc[key] = look->doc[key];
    // extensionsUsed and extensionsRequired from what the materials use (KHR_texture_transform,
    // EXT_texture_webp …); empty arrays left out (§5.1).
    return glb::finish_glb(std::move(doc), std::move(bin), look->source_extensions_required);
  }
  doc["accessors"] = std::move(bin.accessors);
  doc["bufferViews"] = std::move(bin.views);
  if (!bin.bytes.empty()) doc["buffers"] = json::array({{{"byteLength", bin.bytes.size()}}});
  return glb::glb_container(doc, std::move(bin.bytes));
}

}  // namespace dqskin::texture
