// What a file `dqskin bake` wrote holds, read back for `dqskin diff` of two bakes (internal to lib/diff):
// the vertices of a PLY, OBJ or glb frame in the order bake wrote them, or the texels of an EXR texture.
#pragma once

#include "dqskin/load.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
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

// What reading a file takes as its header declares it, before any of it is read: an EXR texture's
// texels as positions and a band of rows (`what`: "12000x12000 texels"). {0, ""} for the other files,
// which hold what they declare (a glb frame's loading has its own estimate), and for an EXR whose header
// cannot be read (read_baked_file says why).
struct DeclaredSize {
  uint64_t bytes = 0;
  uint64_t points = 0;  // texels
  std::string what;
};
DeclaredSize declared_size(const std::string& path);

// Reads one file (a glb frame with `load`). Throws InputError naming the problem (not the file) when it is
// not what bake writes, without quoting the file's bytes.
BakedPoints read_baked_file(const std::string& path, const LoadOptions& load);

}  // namespace dqskin::diff_detail
