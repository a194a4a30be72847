// Closest points on a triangle surface, for the geometric diff: "which point of B's surface is this vertex
// of A?" at the rest pose, so that the point can be followed through every frame even when an optimizer
// reordered, merged or re-triangulated the vertices (internal to lib/diff).
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace dqskin::diff_detail {

// A point on a surface: a triangle (its three vertex indices) and barycentric weights, w[0] + w[1] + w[2] = 1.
struct SurfacePoint {
  uint32_t vertex[3] = {0, 0, 0};
  float weight[3] = {1, 0, 0};
  float distance = 0;  // from the query at the rest pose
};

// The exact closest point of a triangle to a point (Ericson, Real-Time Collision Detection §5.1.5:
// Voronoi regions of the vertices, then the edges, then the face), as barycentric weights of a, b, c.
glm::dvec3 closest_point_weights(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

// An index of a triangle surface for exact closest-point queries. nanoflann (a Debian package) indexes
// points, not triangles, so each triangle is represented by a grid of sample points no farther than `h`
// from any point of it: the nearest sample gives an upper bound d of the distance to the surface, and
// every triangle that has a point within d has a sample within d + h, so a radius search for d + h finds
// all candidates and the closest of them is exact. The grid's spacing follows the median edge, so a mesh
// of even triangles gets about three samples per triangle and a large triangle as many as it needs.
class SurfaceIndex {
public:
  // `positions` and `triangles` (three vertex indices each, < positions.size()) are copied; so are
  // `normals` (one per position, or empty), which choose between points at the same distance.
  SurfaceIndex(std::span<const glm::dvec3> positions, std::span<const uint32_t> triangles,
               std::span<const glm::dvec3> normals = {});
  ~SurfaceIndex();
  SurfaceIndex(const SurfaceIndex&) = delete;
  SurfaceIndex& operator=(const SurfaceIndex&) = delete;

  bool empty() const;
  // The closest point of the surface to `query`. Points within 1e-4 of the surface's diagonal of the
  // closest are ties (a crease or seam, where split vertices share a position; quantized positions; a
  // thin part): the tie goes to the point whose interpolated normal agrees best with `normal` (when both
  // the index and the query have normals), then to the nearest, then to the triangle listed first. The
  // index must not be empty. Safe to call from several threads.
  SurfacePoint closest(const glm::dvec3& query, const glm::dvec3& normal = glm::dvec3(0)) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dqskin::diff_detail
