// One file of a geometric diff as the comparison needs it (internal to lib/diff): its mesh instances with
// every vertex numbered in FrameView order, its triangles, the joint each vertex mostly follows, and its
// surface at the rest pose.
#pragma once

#include "dqskin/asset.hpp"
#include "dqskin/deformed_batch.hpp"
#include "dqskin/load.hpp"
#include "dqskin/skinning.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace dqskin::diff_detail {

// A side's surface at one pose: world positions and normals per vertex, in vertex numbers (normals zero
// where a primitive has none from the file).
struct PosedSurface {
  std::vector<glm::dvec3> positions, normals;
};

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
  std::vector<uint8_t> on_surface;     // per vertex: used by a triangle of its primitive, so compared
  std::vector<uint32_t> joint;         // per vertex: index into joint_names of the joint it mostly follows
  std::vector<std::string> joint_names;
  PosedSurface rest;                   // at the rest pose (the CPU reference, double)
};

// What make_diff_side takes for `asset`, from its vertex and triangle counts: what the side holds (the rest
// pose and its normals in double, the triangles, the per-vertex tables) and, while it is made, the rest
// pose as deform_frame returns it. An estimate, checked before the side is made: a file of a few hundred
// bytes may declare millions of vertices (an accessor without a buffer).
struct SideSize {
  uint64_t vertices = 0;
  uint64_t bytes = 0;
};
SideSize diff_side_size(const Asset& asset);

// What --max-memory (`max`) leaves beside the memory held now (all of it when this binary does not count
// its allocations: dqskin/memory_ceiling.hpp).
uint64_t memory_left(uint64_t max);

// "--max-memory 2.00 GiB", or when less is left, "the 1.20 GiB that --max-memory 2.00 GiB leaves".
std::string left_text(uint64_t left, uint64_t max);

// Throws InputError (without the file's name) when `asset`'s side needs more memory than `max` (--max-memory)
// leaves beside what is held now.
void check_side_fits(const Asset& asset, uint64_t max);

// Loads `path` with `load` and makes its side (make_diff_side); refuses a file whose side needs more
// memory than load.max_memory leaves after loading it (diff_side_size). Throws InputError naming the file,
// also for the memory ceiling's refusal (std::bad_alloc).
DiffSide load_diff_side(const std::string& path, const LoadOptions& load, BlendMode mode);

// Prepares a loaded asset's `scene` (-1: the default) for a diff. Throws InputError when the scene has no
// triangles.
DiffSide make_diff_side(Asset asset, BlendMode mode);

// `side`'s surface at `pose` (sample_pose's), deformed by the CPU reference in double.
PosedSurface pose_surface(const DiffSide& side, const Pose& pose, BlendMode mode);

// Positions and normals of every vertex at one frame, in vertex numbers: 3 floats each; normals are zero
// where a primitive has none from the file.
struct SideFrame {
  std::vector<float> positions, normals;
};

// Frame `frame` of a batch, gathered into `out` (resized as needed).
void gather_frame(const DiffSide& side, const DeformedBatch& batch, size_t frame, SideFrame& out);

}  // namespace dqskin::diff_detail
