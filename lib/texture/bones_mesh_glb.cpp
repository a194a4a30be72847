#include "bones_mesh_glb.hpp"

#include "single_mesh_glb.hpp"

namespace dqskin::texture {

using glb::json;

namespace {

// An UNSIGNED_SHORT VEC4 accessor over `values` (four per vertex).
int joints_accessor(glb::BinWriter& bin, const std::vector<uint16_t>& values) {
  const int view = bin.view(values.data(), values.size() * sizeof(uint16_t), glb::kArrayBuffer);
  bin.accessors.push_back(
      {{"bufferView", view}, {"componentType", glb::kUnsignedShort}, {"count", values.size() / 4}, {"type", "VEC4"}});
  return int(bin.accessors.size()) - 1;
}

// glm vectors are tightly packed floats (asserted by glm's own layout tests); an empty vector gives an
// empty span.
template <class Vec>
std::span<const float> flat(const std::vector<Vec>& values) {
  return {reinterpret_cast<const float*>(values.data()), values.size() * Vec::length()};
}

}  // namespace

std::string encode_bones_mesh_glb(const Asset& asset, const std::vector<MeshInstance>& instances,
                                  const std::string& name, const glb::Appearance* look) {
  glb::BinWriter bin = has_materials(look) ? look->bin : glb::BinWriter{};
  json primitives = json::array();
  for (const MeshInstance& instance : instances) {
    if (instance.skin < 0) continue;
    for (const Primitive& source : asset.meshes[size_t(instance.mesh)].primitives) {
      const size_t n = source.vertex_count();
      json attributes;
      attributes["POSITION"] = bin.positions(flat(source.positions));
      if (source.normals.size() == n) attributes["NORMAL"] = bin.floats(flat(source.normals), n, "VEC3");
      if (source.uv0.size() == n) attributes["TEXCOORD_0"] = bin.floats(flat(source.uv0), n, "VEC2");
      if (has_materials(look) && source.uv1.size() == n) attributes["TEXCOORD_1"] = bin.floats(flat(source.uv1), n, "VEC2");
      // COLOR_0 multiplies the base color (§3.9.2), so it is part of the look.
      if (has_materials(look) && source.colors.size() == n) attributes["COLOR_0"] = colors_accessor(source.colors, bin);
      // The loader's influences are vertex-major, `influences` (4 per set) per vertex; glTF sets hold 4.
      const size_t per = size_t(source.influences);
      for (size_t set = 0; set * 4 < per; ++set) {
        std::vector<uint16_t> joints(4 * n);
        std::vector<float> weights(4 * n);
        for (size_t v = 0; v < n; ++v)
          for (size_t i = 0; i < 4; ++i) {
            joints[4 * v + i] = source.joints[v * per + 4 * set + i];
            weights[4 * v + i] = source.weights[v * per + 4 * set + i];
          }
        attributes["_JOINTS_" + std::to_string(set)] = joints_accessor(bin, joints);
        attributes["_WEIGHTS_" + std::to_string(set)] = bin.floats(weights, n, "VEC4");
      }
      json primitive = {{"attributes", std::move(attributes)},
                        {"extras", {{"skin", instance.skin}, {"bones", "bones_skin" + std::to_string(instance.skin)}}}};
      add_material(source, look, primitive);
      add_topology(source, bin, primitive);
      primitives.push_back(std::move(primitive));
    }
  }
  return single_mesh_glb(std::move(primitives), std::move(bin), name, look);
}

}  // namespace dqskin::texture
