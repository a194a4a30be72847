// One frame's deformed meshes as one mesh, and its PLY file (shared/DESIGN.md "write"): every primitive
// of every instance merged in scene order, vertices in glTF accessor order, faces from the triangle-mode
// primitives.
#pragma once

#include "dqskin/skinning.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace dqskin {

struct MergedMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // zero for vertices of primitives that have none
  std::vector<glm::vec2> uv0;      // zero for vertices of primitives that have none
  std::vector<uint32_t> triangles; // three indices per face, into the merged vertices
};

// Merges a CPU-reference frame (deform_frame with the same instances) into one mesh, in float.
MergedMesh merge_frame(const Asset& asset, const std::vector<MeshInstance>& instances, const DeformedFrame& frame);

// Writes binary little-endian PLY: x y z nx ny nz s t per vertex, faces as uchar-counted uint lists.
// Atomic (AtomicFile); throws OutputError naming `path`.
void write_ply(const std::string& path, const MergedMesh& mesh);

}  // namespace dqskin
