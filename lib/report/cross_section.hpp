// The cross-section measure of `dqskin report` (internal to lib/report; README "dqskin report", "Cross-
// section"): how much a slice of a joint's blend zone spreads around the joint's axis, so that a ring
// collapsing onto the bone (lbs's candy wrapper) or swelling (a bulge) shows on open meshes as well.
#pragma once

#include "skin_regions.hpp"

#include <span>
#include <vector>

namespace dqskin::report_detail {

// Slices across the bone: kSlices equal intervals of the zone's axial coordinate, each a list of indices
// into `zone`; slices with fewer than 3 vertices are dropped (no spread to measure).
constexpr int kSlices = 8;
std::vector<std::vector<size_t>> slice_zone(const std::vector<ZoneVertex>& zone);

// The spread of `points` around the line through `axis_point` along `axis` (unit): sqrt(det M), M the
// 2×2 second moment of the points' offsets from the line, projected onto the plane normal to `axis`.
// A ring of radius r around the line gives r²/2; a ring collapsed onto the line 0. Unit-free as a
// ratio: report divides it by the same slice's value at the rest pose.
double section_spread(std::span<const glm::dvec3> points, const glm::dvec3& axis_point, const glm::dvec3& axis);

// The joint's axis at a frame: the bind-space section axis turned by the normalized average of the
// parent's and the joint's rigid rotations (their real parts brought into one hemisphere first), and the
// joint's deformed position (its joint matrix world · IBM applied to its bind position).
struct DeformedAxis {
  glm::dvec3 point{0.0}, direction{0.0};
};
DeformedAxis deformed_axis(const JointRegion& region, const DualQuat<double>& parent, const DualQuat<double>& joint,
                           const Mat4<double>& joint_matrix);

}  // namespace dqskin::report_detail
