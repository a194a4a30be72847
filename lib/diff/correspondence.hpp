// Where each compared vertex of one side of a geometric diff lies on the other side's surface (internal to
// lib/diff): found once, at a pose where both files are well posed, and followed through every frame.
#pragma once

#include "diff_side.hpp"
#include "surface_correspondence.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace dqskin::diff_detail {

struct Correspondence {
  std::vector<uint32_t> vertices;  // the compared vertices (those on triangles)
  std::vector<SurfacePoint> points;
  std::vector<uint32_t> joint;  // per compared vertex: the joint it mostly follows (the diff's joint table)
  double max_rest_distance = 0;  // the largest distance to the other surface where the correspondence was made
  // How normals are compared (normal_comparison.hpp): per compared vertex, whether its normal is compared
  // with the surface point's; and the triangles compared by face normal, three indices into `vertices`
  // (and `points`) each.
  std::vector<uint8_t> smooth;
  std::vector<uint32_t> faces;
};

struct Box {
  glm::dvec3 low, high;
};
// The bounding box of `side`'s compared vertices (on_surface) at a pose.
Box bounding_box(const DiffSide& side, const PosedSurface& surface);

// True when the files have the same primitives with the same vertex counts and every vertex of one is
// within `tolerance` of the other's at the pose: a re-export that kept the order is then compared vertex by
// vertex.
bool same_vertices(const DiffSide& a, const PosedSurface& pa, const DiffSide& b, const PosedSurface& pb, double tolerance);

// Every compared vertex of `side` against itself.
Correspondence identity(const DiffSide& side);

// Every compared vertex of `from` against the closest point of `onto`'s surface, both at the same pose.
// `onto_name`: "A" or "B", for the message when its triangles have no area. Throws InputError then.
Correspondence closest_points(const DiffSide& from, const PosedSurface& from_pose, const DiffSide& onto,
                              const PosedSurface& onto_pose, const char* onto_name, unsigned threads);

}  // namespace dqskin::diff_detail
