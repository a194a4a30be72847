// The cross-section measure of `dqskin report` (internal to lib/report; docs/commands/report.md,
// "Cross-section"): how much a slice of a joint's blend zone spreads around the joint's axis, so that a ring
// collapsing onto the bone (lbs's candy wrapper) or swelling (a bulge) shows on open meshes as well.
#pragma once

#include "skin_regions.hpp"

#include <span>
#include <vector>

namespace dqskin::report_detail {

// Slices across the bone: equal intervals of the zone's axial coordinate, each a list of indices into
// `zone`; as many as give each about 2·kSliceVertices vertices, at most kSlices (low-polygon limbs have
// zones of a few dozen vertices). Slices with fewer than kSliceVertices vertices are dropped: the spread
// of a handful of points swings with every small move, so its ratio says nothing.
constexpr int kSlices = 8;
constexpr size_t kSliceVertices = 6;
std::vector<std::vector<size_t>> slice_zone(const std::vector<ZoneVertex>& zone);

// The spread of `points` across `axis` (unit): the 2×2 covariance C of the points projected onto the
// plane normal to the axis, and its area measure sqrt(det C), with its eigenvalues. A ring of radius r
// gives r²/2 (whatever its position), a ring collapsed onto a point or a segment 0. Unit-free as a ratio:
// report divides it by the same slice's value at the rest pose.
struct Spread {
  double area = 0;                    // sqrt(det C)
  double major = 0, minor = 0;        // C's eigenvalues, major ≥ minor ≥ 0
};
Spread section_spread(std::span<const glm::dvec3> points, const glm::dvec3& axis);

// A slice is measured only when its rest spread is not flat: minor ≥ kFlatness · major (a sheet-like
// slice, a fin or an ear, has an area near zero at rest, and any ratio to it is noise).
constexpr double kFlatness = 0.01;

// The joint's axis at a frame: the bind-space section axis turned by the normalized average of the
// parent's and the joint's rigid rotations (their real parts brought into one hemisphere first).
glm::dvec3 deformed_axis(const JointRegion& region, const DualQuat<double>& parent, const DualQuat<double>& joint);

}  // namespace dqskin::report_detail
