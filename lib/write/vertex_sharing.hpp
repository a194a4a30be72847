// Which primitives share their vertices, so that the per-vertex outputs (PLY, OBJ, vertex-animation
// textures, the morph bake) write each distinct vertex once per drawn instance. glTF lets several
// primitives of a mesh name the same accessors (§3.7.2.1: attributes are accessor indices); exporters that
// split a mesh by material, and VRM files, do so with one vertex set and one index list per material.
//
// Two primitives of one mesh share vertex data when they name the same accessor for every attribute and
// every morph target attribute (Primitive::vertex_accessors equal and not empty) and neither has normals
// the loader generated (those are computed from each primitive's own faces, so they differ). Then every
// per-vertex value the deformation and the writers read is the same, and so is the deformed vertex.
//
// The output's vertex order: instances in scene order; within one, the mesh's primitives in order, each
// adding its vertices in accessor order, except a primitive that shares the vertex data of an earlier one
// of its mesh: it adds none, and its faces index the earlier one's vertices.
#pragma once

#include "dqskin/frame_view.hpp"
#include "dqskin/skinning.hpp"

#include <cstddef>
#include <vector>

namespace dqskin {

// Whether `a` and `b`, two primitives of one mesh, have the same vertex data (see above).
bool shares_vertex_data(const Primitive& a, const Primitive& b);

// For each primitive of `mesh`, the index of the first primitive of the mesh whose vertex data it shares:
// itself when none before it does.
std::vector<size_t> vertex_data_owners(const Mesh& mesh);

// Where each primitive of `instances` (in deform_frame's order: instances, then their mesh's primitives)
// finds its vertices in the output.
struct SharedVertexLayout {
  std::vector<size_t> owner;         // flat index of the primitive whose vertices it uses (itself: it writes them)
  std::vector<size_t> first_vertex;  // output index of its owner's first vertex
  size_t vertices = 0;               // distinct vertices written
  bool writes(size_t p) const { return owner[p] == p; }
};
SharedVertexLayout shared_vertex_layout(const Asset& asset, const std::vector<MeshInstance>& instances);

// `frame` with only the primitives that write vertices: its vertices, concatenated, are the output's.
FrameView distinct_vertices(const FrameView& frame, const SharedVertexLayout& layout);

}  // namespace dqskin
