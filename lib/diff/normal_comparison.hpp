// How the geometric diff compares normals (internal to lib/diff). A file's normal at a point means one thing
// only where its surface is smooth there: at a crease, and everywhere on a flat-shaded mesh, the vertices at
// one position carry the normals of different faces (split normals), and a primitive without NORMAL is drawn
// with flat normals (glTF 2.0 §3.7.2.1: "client implementations MUST calculate flat normals"). So vertex
// normals are compared where both files define one smooth normal at corresponding points, and elsewhere the
// faces are: each triangle's normal against that of the triangle its corners' corresponding points make on
// the other surface (on the same surface, whatever its triangulation, that triangle lies in the same plane).
#pragma once

#include "correspondence.hpp"
#include "diff_side.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace dqskin::diff_detail {

// Normals that differ by less than this at one position are one smooth normal (exporters write a seam's
// two vertices with normals that round differently).
constexpr double kSmoothDegrees = 1.0;

// Per vertex of `side`: its primitive has normals from the file, and every vertex at exactly the same
// position of `surface` (of any primitive) has one within kSmoothDegrees of its own.
std::vector<uint8_t> smooth_vertices(const DiffSide& side, const PosedSurface& surface);

// Fills c.smooth (a compared vertex of `from` smooth, and every vertex that weighs in its surface point
// smooth) and c.faces (the triangles of `from` with a corner not compared smoothly).
void plan_normal_comparison(const DiffSide& from, std::span<const uint8_t> from_smooth,
                            std::span<const uint8_t> onto_smooth, Correspondence& c);

}  // namespace dqskin::diff_detail
