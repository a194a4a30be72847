#include "cross_section.hpp"

#include <algorithm>
#include <cmath>

namespace dqskin::report_detail {

std::vector<std::vector<size_t>> slice_zone(const std::vector<ZoneVertex>& zone) {
  if (zone.empty()) return {};
  const int count = int(std::clamp(zone.size() / (2 * kSliceVertices), size_t(1), size_t(kSlices)));
  std::vector<std::vector<size_t>> slices(static_cast<size_t>(count));
  double lo = zone[0].axial, hi = zone[0].axial;
  for (const ZoneVertex& z : zone) lo = std::min(lo, z.axial), hi = std::max(hi, z.axial);
  const double extent = hi - lo;
  for (size_t i = 0; i < zone.size(); ++i) {
    const int k = extent > 0 ? std::clamp(int(std::floor((zone[i].axial - lo) / extent * count)), 0, count - 1) : 0;
    slices[size_t(k)].push_back(i);
  }
  std::erase_if(slices, [](const std::vector<size_t>& s) { return s.size() < kSliceVertices; });
  return slices;
}

Spread section_spread(std::span<const glm::dvec3> points, const glm::dvec3& axis) {
  if (points.empty()) return {};
  // An orthonormal basis (u, v) of the plane normal to the axis.
  const glm::dvec3 helper = std::abs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(axis, helper)), v = glm::cross(axis, u);
  glm::dvec3 mean(0.0);
  for (const glm::dvec3& p : points) mean += p;
  mean /= double(points.size());
  double uu = 0, uv = 0, vv = 0;
  for (const glm::dvec3& p : points) {
    const glm::dvec3 d = p - mean;
    const double a = glm::dot(d, u), b = glm::dot(d, v);
    uu += a * a, uv += a * b, vv += b * b;
  }
  const double n = double(points.size());
  uu /= n, uv /= n, vv /= n;
  const double det = std::max(0.0, uu * vv - uv * uv), half_trace = (uu + vv) / 2;
  const double root = std::sqrt(std::max(0.0, half_trace * half_trace - det));
  return {std::sqrt(det), half_trace + root, std::max(0.0, half_trace - root)};
}

glm::dvec3 deformed_axis(const JointRegion& region, const DualQuat<double>& parent, const DualQuat<double>& joint) {
  Quat<double> a = parent.real, b = joint.real;
  if (glm::dot(a, b) < 0) b = -b;
  const Quat<double> mean = glm::normalize(a + b);
  return glm::normalize(mean * region.section_axis);
}

}  // namespace dqskin::report_detail
