#include "single_mesh_glb.hpp"

#include "dqskin/triangles.hpp"
#include "dqskin/version.hpp"

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

std::string single_mesh_glb(json primitives, glb::BinWriter bin, const std::string& name) {
  json doc = {{"asset", {{"version", "2.0"}, {"generator", std::string("dqskin ") + kVersion}}},
              {"scene", 0},
              {"scenes", json::array({{{"nodes", {0}}}})},
              {"nodes", json::array({{{"name", name}, {"mesh", 0}}})},
              {"meshes", json::array({{{"name", name}, {"primitives", std::move(primitives)}}})},
              {"accessors", std::move(bin.accessors)},
              {"bufferViews", std::move(bin.views)}};
  if (!bin.bytes.empty()) doc["buffers"] = json::array({{{"byteLength", bin.bytes.size()}}});
  return glb::glb_container(doc, std::move(bin.bytes));
}

}  // namespace dqskin::texture
