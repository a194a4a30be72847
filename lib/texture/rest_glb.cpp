#include "rest_glb.hpp"

#include "single_mesh_glb.hpp"

#include "../write/vertex_sharing.hpp"

#include <cassert>
#include <optional>

namespace dqskin::texture {

using glb::json;

namespace {

// Every textureInfo of a material that reads TEXCOORD_1 (by its texCoord, or its KHR_texture_transform's,
// which overrides it) reads TEXCOORD_2 instead: the rest mesh's TEXCOORD_1 is the texel lookup, and the
// source's second set moves to 2. Extras are the application's and left alone.
void move_second_uv_set(json& object) {
  if (object.is_array()) {
    for (json& value : object) move_second_uv_set(value);
    return;
  }
  if (!object.is_object()) return;
  for (auto& [key, value] : object.items()) {
    if (key == "extras") continue;
    if (key == "texCoord" && value == 1) value = 2;
    else move_second_uv_set(value);
  }
}

}  // namespace

std::string encode_rest_glb(const Asset& asset, const std::vector<MeshInstance>& instances, const FrameView& rest,
                            const VatLayout& layout, const std::string& name, const glb::Appearance* look) {
  std::optional<glb::Appearance> moved;
  if (has_materials(look)) {
    moved = *look;
    move_second_uv_set(moved->doc["materials"]);
    look = &*moved;
  }
  glb::BinWriter bin = has_materials(look) ? look->bin : glb::BinWriter{};
  json primitives = json::array();
  const SharedVertexLayout sharing = shared_vertex_layout(asset, instances);
  std::vector<json> written(sharing.owner.size());  // each primitive's attributes, for those that share them
  size_t p = 0;
  for (const MeshInstance& instance : instances) {
    for (const Primitive& source : asset.meshes[size_t(instance.mesh)].primitives) {
      assert(p < rest.primitives.size());
      const size_t me = p++;
      if (!sharing.writes(me)) {
        // The vertices of an earlier primitive (vertex_sharing.hpp): its accessors, as the source shares them.
        json primitive = {{"attributes", written[sharing.owner[me]]}};
        add_material(source, look, primitive);  // the vertices are shared, the material is the primitive's own
        add_topology(source, bin, primitive);
        primitives.push_back(std::move(primitive));
        continue;
      }
      const PrimitiveView& view = rest.primitives[me];
      const size_t n = view.vertices, first = sharing.first_vertex[me];
      json attributes;
      attributes["POSITION"] = bin.positions(view.positions.first(3 * n));
      if (!view.normals.empty()) attributes["NORMAL"] = bin.floats(view.normals, n, "VEC3");
      std::vector<float> lookup(2 * n);
      for (size_t v = 0; v < n; ++v) {
        const glm::dvec2 uv = layout.lookup_uv(first + v);
        lookup[2 * v] = float(uv.x);
        lookup[2 * v + 1] = float(uv.y);
      }
      if (source.uv0.size() == n) {
        attributes["TEXCOORD_0"] = bin.floats(std::span(&source.uv0[0].x, 2 * n), n, "VEC2");
        attributes["TEXCOORD_1"] = bin.floats(lookup, n, "VEC2");
      } else {
        attributes["TEXCOORD_0"] = bin.floats(lookup, n, "VEC2");
        attributes["TEXCOORD_1"] = attributes["TEXCOORD_0"];
      }
      if (has_materials(look) && source.uv1.size() == n)
        attributes["TEXCOORD_2"] = bin.floats(std::span(&source.uv1[0].x, 2 * n), n, "VEC2");
      // COLOR_0 multiplies the base color (§3.9.2), so it is part of the look.
      if (has_materials(look) && source.colors.size() == n)
        attributes["COLOR_0"] = colors_accessor(source.colors, bin);
      written[me] = attributes;
      json primitive = {{"attributes", std::move(attributes)}};
      add_material(source, look, primitive);
      add_topology(source, bin, primitive);
      primitives.push_back(std::move(primitive));
    }
  }
  return single_mesh_glb(std::move(primitives), std::move(bin), name, look);
}

}  // namespace dqskin::texture
