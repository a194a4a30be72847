// What a file `dqskin bake` wrote holds, read back for `dqskin diff` of two bakes (internal to lib/diff):
// the vertices of a PLY, OBJ or glb frame in the order bake wrote them, or the texels of an EXR texture.
#pragma once

#include <glm/vec3.hpp>

#include <string>
#include <vector>

namespace dqskin::diff_detail {

struct BakedPoints {
  std::vector<glm::vec3> positions;  // vertices, or texels' RGB (a VAT's positions)
  std::vector<glm::vec3> normals;    // one per vertex, or empty (textures, frames without normals)
  std::vector<uint32_t> joint;       // unused for bakes (no skin is left in a frame)
};

// True for the extensions read: .ply, .obj, .glb, .exr (lowercase, as bake writes them).
bool is_baked_file(const std::string& path);

// Reads one file. Throws InputError naming the problem (not the file) when it is not what bake writes.
BakedPoints read_baked_file(const std::string& path);

}  // namespace dqskin::diff_detail
