// The joints `dqskin report` measures and the vertices each one answers for (internal to lib/report): per
// joint of a skin that the scene's instances use, its region (the vertices whose largest weight is that
// joint), its parent joint (the nearest ancestor node that is a joint of the same skin), its bind-space
// position and bone axes, and its blend zone with its parent (docs/commands/report.md).
#pragma once

#include "dqskin/asset.hpp"
#include "dqskin/skinning.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace dqskin::report_detail {

// One vertex of the deformed batch: its primitive there (instances in order, primitives in mesh order,
// as DeformedBatch and deform_frame list them) and its index in it.
struct VertexRef {
  uint32_t primitive = 0;
  uint32_t vertex = 0;
};

// A primitive of the batch and where it comes from.
struct BatchPrimitive {
  size_t instance = 0;
  int mesh = -1;
  size_t primitive = 0;  // in its mesh
  int skin = -1;         // -1: a rigid instance
  size_t vertices = 0;
};

// A blend-zone vertex with its coordinate along the joint's bind-space bone axis.
struct ZoneVertex {
  VertexRef ref;
  glm::dvec3 bind{0.0};  // bind-space position (the primitive's POSITION)
  double axial = 0;      // dot(bind − the joint's bind position, section axis): only its differences count
};

struct JointRegion {
  int skin = -1;
  int joint = -1;         // index into the skin's joints
  int node = -1;
  std::string name;       // the node's name, or "node N" when it has none
  int parent = -1;        // parent joint (index into the skin's joints), or -1
  glm::dvec3 bind_position{0.0};   // inverse(IBM) · origin
  glm::dvec3 section_axis{0.0};    // unit, parent → joint; zero without a parent or when they coincide
  glm::dvec3 twist_axis{0.0};      // unit, joint → first child joint, else parent → joint; may be zero
  std::vector<VertexRef> vertices;  // the region
  std::vector<ZoneVertex> zone;     // weight ≥ kZoneWeight on both the joint and its parent
};

// The weight a vertex needs on both the joint and its parent joint to be in their blend zone.
constexpr double kZoneWeight = 0.2;

struct SkinRegions {
  std::vector<BatchPrimitive> primitives;  // every primitive of the batch, in its order
  std::vector<JointRegion> joints;         // those with a non-empty region, skin then joint order
  size_t vertices = 0, skinned_vertices = 0;
  int max_influences = 0;  // most non-zero weights on one vertex of a skinned primitive
};

// The regions of the skinned instances among `instances`. A vertex's weights are divided by their sum (as
// the deformers do); a vertex without weight belongs to no region; ties go to the influence listed first.
SkinRegions skin_regions(const Asset& asset, const std::vector<MeshInstance>& instances);

// The normalised weight of every influence of vertex `v` of a skinned primitive: (joint, weight) pairs
// with weight > 0, the same joint listed twice summed.
struct Influence {
  int joint = 0;
  double weight = 0;
};
std::vector<Influence> vertex_influences(const Primitive& primitive, size_t v);

}  // namespace dqskin::report_detail
