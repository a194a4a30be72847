#include "vertex_sharing.hpp"

#include <cassert>

namespace dqskin {

bool shares_vertex_data(const Primitive& a, const Primitive& b) {
  return !a.vertex_accessors.empty() && a.vertex_accessors == b.vertex_accessors && !a.normals_generated &&
         !b.normals_generated && a.vertex_count() == b.vertex_count();
}

std::vector<size_t> vertex_data_owners(const Mesh& mesh) {
  std::vector<size_t> owners(mesh.primitives.size());
  for (size_t p = 0; p < owners.size(); ++p) {
    owners[p] = p;
    // Quadratic in the primitives of one mesh, which are few (one per material).
    for (size_t q = 0; q < p; ++q)
      if (owners[q] == q && shares_vertex_data(mesh.primitives[q], mesh.primitives[p])) {
        owners[p] = q;
        break;
      }
  }
  return owners;
}

SharedVertexLayout shared_vertex_layout(const Asset& asset, const std::vector<MeshInstance>& instances) {
  SharedVertexLayout layout;
  for (const MeshInstance& inst : instances) {
    const Mesh& mesh = asset.meshes[size_t(inst.mesh)];
    const size_t base = layout.owner.size();
    const std::vector<size_t> owners = vertex_data_owners(mesh);
    for (size_t p = 0; p < owners.size(); ++p) {
      layout.owner.push_back(base + owners[p]);
      if (owners[p] == p) {
        layout.first_vertex.push_back(layout.vertices);
        layout.vertices += mesh.primitives[p].vertex_count();
      } else {
        layout.first_vertex.push_back(layout.first_vertex[base + owners[p]]);
      }
    }
  }
  return layout;
}

FrameView distinct_vertices(const FrameView& frame, const SharedVertexLayout& layout) {
  assert(frame.primitives.size() == layout.owner.size());
  FrameView out;
  for (size_t p = 0; p < frame.primitives.size(); ++p)
    if (layout.writes(p)) out.primitives.push_back(frame.primitives[p]);
  return out;
}

}  // namespace dqskin
