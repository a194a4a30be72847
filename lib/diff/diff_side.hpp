// One file of a geometric diff as the comparison needs it (internal to lib/diff): its mesh instances with
// every vertex numbered in FrameView order, its triangles, the joint each vertex mostly follows, and its
// surface at the rest pose.
#pragma once

#include "dqskin/asset.hpp"
#include "dqskin/deformed_batch.hpp"
#include "dqskin/skinning.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace dqskin::diff_detail {

struct DiffSide {
  Asset asset;
  std::vector<MeshInstance> instances;
  std::vector<size_t> first_vertex;    // per primitive (FrameView order): its first vertex's number
  std::vector<size_t> primitive_size;  // per primitive: its vertex count
  // Per primitive: the file has normals. The loader's generated ones are not compared: the
  // specification leaves such normals to the viewer, and an optimizer that merges split vertices changes
  // what smoothing makes of them without changing the file's meaning.
  std::vector<uint8_t> file_normals;
  size_t vertices = 0;
  std::vector<uint32_t> triangles;     // of triangle primitives, three vertex numbers each
  std::vector<uint8_t> on_surface;     // per vertex: on a triangle primitive, so compared
  std::vector<uint32_t> joint;         // per vertex: index into joint_names of the joint it mostly follows
  std::vector<std::string> joint_names;
  std::vector<glm::dvec3> rest;        // world positions at the rest pose (the CPU reference, double)
  std::vector<glm::dvec3> rest_normals;  // and normals (zero where a primitive has none)
};

// Prepares a loaded asset's `scene` (-1: the default) for a diff. Throws InputError when the scene has no
// triangles.
DiffSide make_diff_side(Asset asset, BlendMode mode);

// Positions and normals of every vertex at one frame, in vertex numbers: 3 floats each; normals are zero
// where a primitive has none from the file.
struct SideFrame {
  std::vector<float> positions, normals;
};

// Frame `frame` of a batch, gathered into `out` (resized as needed).
void gather_frame(const DiffSide& side, const DeformedBatch& batch, size_t frame, SideFrame& out);

}  // namespace dqskin::diff_detail
