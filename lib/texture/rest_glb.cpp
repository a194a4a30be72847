#include "rest_glb.hpp"

#include "../io/glb_appearance.hpp"
#include "dqskin/triangles.hpp"
#include "dqskin/version.hpp"

#include <cassert>

namespace dqskin::texture {

using glb::json;

namespace {

// glTF primitive.mode values (§3.7.2.1).
int gltf_mode(PrimitiveMode mode) { return int(mode); }

}  // namespace

std::string encode_rest_glb(const Asset& asset, const std::vector<MeshInstance>& instances, const FrameView& rest,
                            const VatLayout& layout, const std::string& name) {
  glb::BinWriter bin;
  json primitives = json::array();
  size_t first = 0, p = 0;
  for (const MeshInstance& instance : instances) {
    for (const Primitive& source : asset.meshes[size_t(instance.mesh)].primitives) {
      assert(p < rest.primitives.size());
      const PrimitiveView& view = rest.primitives[p++];
      const size_t n = view.vertices;
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
      json primitive = {{"attributes", std::move(attributes)}};
      if (const std::vector<uint32_t> triangles = triangle_list(source); !triangles.empty()) {
        primitive["indices"] = bin.indices(triangles);
      } else {
        if (!source.indices.empty()) primitive["indices"] = bin.indices(source.indices);
        primitive["mode"] = gltf_mode(source.mode);
      }
      primitives.push_back(std::move(primitive));
      first += n;
    }
  }
  json doc = {{"asset", {{"version", "2.0"}, {"generator", std::string("dqskin ") + kVersion}}},
              {"scene", 0},
              {"scenes", json::array({{{"nodes", {0}}}})},
              {"nodes", json::array({{{"name", name}, {"mesh", 0}}})},
              {"meshes", json::array({{{"name", name}, {"primitives", std::move(primitives)}}})},
              {"accessors", std::move(bin.accessors)},
              {"bufferViews", std::move(bin.views)}};
  if (!bin.bytes.empty()) doc["buffers"] = json::array({{{"byteLength", bin.bytes.size()}}});
  // A buffer's byteLength is the data's; the container pads the chunk itself (§4.4.3.3).
  return glb::glb_container(doc, std::move(bin.bytes));
}

}  // namespace dqskin::texture
