#include "joint_metrics.hpp"
#include "cross_section.hpp"
#include "swing_twist.hpp"

#include <algorithm>
#include <cmath>

namespace dqskin::report_detail {
namespace {

glm::dvec3 position(const FrameView& frame, const VertexRef& ref) {
  const std::span<const float> p = frame.primitives[ref.primitive].positions;
  return {p[3 * ref.vertex], p[3 * ref.vertex + 1], p[3 * ref.vertex + 2]};
}

}  // namespace

std::vector<JointTransforms> JointMetrics::skin_transforms(const Asset& asset, const SkinRegions& regions, const Pose& pose) {
  std::vector<JointTransforms> out(asset.skins.size());
  for (const BatchPrimitive& p : regions.primitives)
    if (p.skin >= 0 && out[size_t(p.skin)].matrices.empty())
      out[size_t(p.skin)] = joint_transforms(asset.skins[size_t(p.skin)], pose);
  return out;
}

JointMetrics::JointMetrics(const Asset& asset, const SkinRegions& regions, const FrameView& rest,
                           const std::vector<JointTransforms>& rest_joints)
    : regions_(regions) {
  sections_.resize(regions.joints.size());
  influences_.resize(regions.joints.size());
  influence_start_.resize(regions.joints.size());
  for (size_t r = 0; r < regions.joints.size(); ++r) {
    const JointRegion& region = regions.joints[r];
    Section& section = sections_[r];
    section.slices = slice_zone(region.zone);
    // A slice flat at rest (cross_section.hpp, kFlatness) or with no spread at all has no ratio: dropped.
    const std::vector<Spread> rest_spreads = spreads(r, rest, rest_joints[size_t(region.skin)]);
    std::vector<std::vector<size_t>> kept;
    for (size_t s = 0; s < rest_spreads.size(); ++s)
      if (rest_spreads[s].area > 0 && rest_spreads[s].minor >= kFlatness * rest_spreads[s].major) {
        kept.push_back(std::move(section.slices[s]));
        section.rest.push_back(rest_spreads[s].area);
      }
    section.slices = std::move(kept);
    for (const VertexRef& ref : region.vertices) {
      const BatchPrimitive& bp = regions.primitives[ref.primitive];
      const Primitive& primitive = asset.meshes[size_t(bp.mesh)].primitives[bp.primitive];
      influence_start_[r].push_back(uint32_t(influences_[r].size()));
      for (const Influence& i : vertex_influences(primitive, ref.vertex))
        if (i.joint != region.joint) influences_[r].push_back(i.joint);
    }
    influence_start_[r].push_back(uint32_t(influences_[r].size()));
  }
}

std::vector<Spread> JointMetrics::spreads(size_t r, const FrameView& positions, const JointTransforms& joints) const {
  const JointRegion& region = regions_.joints[r];
  const Section& section = sections_[r];
  if (section.slices.empty()) return {};
  const glm::dvec3 axis = deformed_axis(region, joints.rigid[size_t(region.parent)], joints.rigid[size_t(region.joint)]);
  std::vector<Spread> out;
  std::vector<glm::dvec3> points;
  for (const std::vector<size_t>& slice : section.slices) {
    points.clear();
    for (size_t i : slice) points.push_back(position(positions, region.zone[i].ref));
    out.push_back(section_spread(points, axis));
  }
  return out;
}

std::vector<JointFrame> JointMetrics::measure(const FrameInput& frame) const {
  std::vector<JointFrame> out(regions_.joints.size());
  for (size_t r = 0; r < regions_.joints.size(); ++r) {
    const JointRegion& region = regions_.joints[r];
    const JointTransforms& joints = (*frame.joints)[size_t(region.skin)];
    JointFrame& m = out[r];
    for (const VertexRef& ref : region.vertices) {
      const glm::dvec3 l = position(*frame.lbs, ref), d = position(*frame.dqs, ref), i = position(*frame.dib, ref);
      const double ld = glm::distance(l, i), dd = glm::distance(d, i);
      m.lbs_dib_max = std::max(m.lbs_dib_max, ld), m.lbs_dib_mean += ld;
      m.dqs_dib_max = std::max(m.dqs_dib_max, dd), m.dqs_dib_mean += dd;
      m.lbs_dqs_max = std::max(m.lbs_dqs_max, glm::distance(l, d));
    }
    m.lbs_dib_mean /= double(region.vertices.size());
    m.dqs_dib_mean /= double(region.vertices.size());

    // Antipodal flips: DLB brings every influence into the hemisphere of the heaviest one, which is this
    // region's joint (docs/DESIGN.md §3.5; Kavan et al. §3, "antipodal property").
    const Quat<double> heaviest = joints.rigid[size_t(region.joint)].real;
    for (size_t v = 0; v < region.vertices.size(); ++v) {
      const uint32_t begin = influence_start_[r][v], end = influence_start_[r][v + 1];
      for (uint32_t k = begin; k < end; ++k)
        if (glm::dot(joints.rigid[size_t(influences_[r][k])].real, heaviest) < 0) {
          ++m.flips;
          break;
        }
    }

    if (region.parent >= 0) {
      // R_rel = R_parent⁻¹ · R_joint, both rigid parts of world · IBM: the identity at the bind pose.
      const Quat<double> relative = glm::conjugate(joints.rigid[size_t(region.parent)].real) * joints.rigid[size_t(region.joint)].real;
      if (region.twist_axis != glm::dvec3(0.0)) {
        const SwingTwist st = swing_twist(glm::normalize(relative), region.twist_axis);
        m.twist = st.twist_degrees, m.bend = st.swing_degrees;
      }
    }

    const Section& section = sections_[r];
    if (section.slices.empty()) continue;
    const std::vector<Spread> lbs = spreads(r, *frame.lbs, joints), dqs = spreads(r, *frame.dqs, joints),
                              dib = spreads(r, *frame.dib, joints);
    m.area_lbs = m.area_dqs = m.area_dib = m.lbs_over_dib = std::numeric_limits<double>::infinity();
    m.dqs_over_dib = -std::numeric_limits<double>::infinity();
    bool compared = false;
    for (size_t s = 0; s < lbs.size(); ++s) {
      m.area_lbs = std::min(m.area_lbs, lbs[s].area / section.rest[s]);
      m.area_dqs = std::min(m.area_dqs, dqs[s].area / section.rest[s]);
      m.area_dib = std::min(m.area_dib, dib[s].area / section.rest[s]);
      if (dib[s].area > 1e-12 * section.rest[s]) {  // against a dib slice that has not collapsed itself
        m.lbs_over_dib = std::min(m.lbs_over_dib, lbs[s].area / dib[s].area);
        m.dqs_over_dib = std::max(m.dqs_over_dib, dqs[s].area / dib[s].area);
        compared = true;
      }
    }
    if (!compared) m.lbs_over_dib = m.dqs_over_dib = kUndefined;
  }
  return out;
}

}  // namespace dqskin::report_detail
