// The volume of closed skinned meshes (internal to lib/report; docs/commands/report.md, "Volume"):
// which triangles enclose a volume, and the signed volume they enclose at a frame.
#pragma once

#include "skin_regions.hpp"

#include "dqskin/frame_view.hpp"

#include <array>
#include <span>
#include <vector>

namespace dqskin::report_detail {

// A triangle of the batch: three vertices of one primitive.
struct BatchTriangle {
  uint32_t primitive = 0;
  std::array<uint32_t, 3> vertex{};
};

// The triangles of every skinned instance that is closed: after welding the instance's vertices at
// identical bind positions (primitives of one instance weld together), every edge is shared by exactly
// two triangles that run it in opposite directions (consistent winding, without which a signed volume
// means nothing). Instances are judged one by one; an open one adds nothing. Empty when none is closed.
std::vector<BatchTriangle> closed_triangles(const Asset& asset, const std::vector<MeshInstance>& instances,
                                            const SkinRegions& regions);

// Whether a triangle soup, its corners given as welded vertex ids, is closed in the sense above.
bool is_closed(std::span<const std::array<uint32_t, 3>> triangles);

// Σ p0 · (p1 × p2) / 6 over the triangles (the divergence theorem), in double.
double signed_volume(std::span<const BatchTriangle> triangles, const FrameView& frame);

}  // namespace dqskin::report_detail
