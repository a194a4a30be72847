#include "correspondence_pose.hpp"

#include "dqskin/dual_quat.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace dqskin::diff_detail {

namespace {

// Which side of a triangle its vertices' normals are on: +1, −1, or 0 when they cancel or are missing.
template <class Vec, class Normals>
int orientation(const Vec& a, const Vec& b, const Vec& c, const Normals& n, size_t u, size_t v, size_t w) {
  if (n.empty()) return 0;
  const glm::dvec3 face = glm::cross(glm::dvec3(b) - glm::dvec3(a), glm::dvec3(c) - glm::dvec3(a));
  const double side = glm::dot(face, glm::dvec3(n[u]) + glm::dvec3(n[v]) + glm::dvec3(n[w]));
  return side > 0 ? 1 : side < 0 ? -1 : 0;
}

}  // namespace

PoseDistortion primitive_distortion(std::span<const glm::dvec3> posed_positions,
                                    std::span<const glm::dvec3> posed_normals,
                                    std::span<const glm::vec3> bind_positions, std::span<const glm::vec3> bind_normals,
                                    std::span<const uint32_t> triangles, size_t first) {
  const size_t count = triangles.size() / 3;
  auto corner = [&](size_t t, size_t k) { return size_t(triangles[3 * t + k]) - first; };
  auto bind_area = [&](size_t t) {
    const glm::dvec3 a(bind_positions[corner(t, 0)]), b(bind_positions[corner(t, 1)]), c(bind_positions[corner(t, 2)]);
    return glm::length(glm::cross(b - a, c - a));
  };
  auto ratio = [&](size_t t, size_t k) {
    const size_t u = corner(t, k), v = corner(t, (k + 1) % 3);
    return glm::length(posed_positions[u] - posed_positions[v]) /
           glm::length(glm::dvec3(bind_positions[u]) - glm::dvec3(bind_positions[v]));
  };
  // The median ratio, over evenly spread triangles.
  std::vector<double> sample;
  const size_t stride = std::max<size_t>(1, count / kMedianTriangles);
  for (size_t t = 0; t < count; t += stride)
    if (bind_area(t) > 0)
      for (size_t k = 0; k < 3; ++k) sample.push_back(ratio(t, k));
  double median = 0;
  if (!sample.empty()) {
    std::nth_element(sample.begin(), sample.begin() + std::ptrdiff_t(sample.size() / 2), sample.end());
    median = sample[sample.size() / 2];
  }
  PoseDistortion d;
  for (size_t t = 0; t < count; ++t) {
    if (!(bind_area(t) > 0)) continue;  // no face at the bind pose: nothing to compare with
    ++d.triangles;
    bool distorted = !(median > 0) || !std::isfinite(median);
    for (size_t k = 0; k < 3 && !distorted; ++k) {
      const double relative = ratio(t, k) / median;
      distorted = !(relative <= kStretch && relative >= 1 / kStretch);  // NaN counts as distorted
    }
    const size_t u = corner(t, 0), v = corner(t, 1), w = corner(t, 2);
    const int before = orientation(bind_positions[u], bind_positions[v], bind_positions[w], bind_normals, u, v, w);
    const int after = orientation(posed_positions[u], posed_positions[v], posed_positions[w], posed_normals, u, v, w);
    d.distorted += distorted || (before != 0 && after == -before);
  }
  return d;
}

PoseDistortion side_distortion(const DiffSide& side, const PosedSurface& posed) {
  PoseDistortion d;
  size_t primitive = 0, cursor = 0;  // side.triangles lists each primitive's triangles in turn
  for (const MeshInstance& instance : side.instances)
    for (const Primitive& p : side.asset.meshes[size_t(instance.mesh)].primitives) {
      const size_t first = side.first_vertex[primitive], end = first + side.primitive_size[primitive];
      const size_t begin = cursor;
      while (cursor < side.triangles.size() && side.triangles[cursor] >= first && side.triangles[cursor] < end) cursor += 3;
      ++primitive;
      if (instance.skin < 0) continue;
      const std::span<const glm::dvec3> positions(posed.positions.data() + first, p.vertex_count());
      const std::span<const glm::dvec3> normals(posed.normals.data() + first, p.vertex_count());
      d += primitive_distortion(positions, normals, p.positions, p.normals,
                                std::span<const uint32_t>(side.triangles).subspan(begin, cursor - begin), first);
    }
  return d;
}

PosedSurface bind_surface(const DiffSide& side, BlendMode mode) {
  const Pose rest = sample_pose(side.asset, nullptr, 0);
  PosedSurface surface;
  size_t primitive = 0;
  for (const MeshInstance& instance : side.instances) {
    JointTransforms identity;
    if (instance.skin >= 0) {
      const size_t joints = side.asset.skins[size_t(instance.skin)].joints.size();
      const JointSplit<double> split = split_joint_matrix(Mat4<double>(1.0));
      identity.matrices.assign(joints, Mat4<double>(1.0));
      identity.rigid.assign(joints, split.rigid);
      identity.scale.assign(joints, split.scale);
    }
    const size_t count = side.asset.meshes[size_t(instance.mesh)].primitives.size();
    for (size_t p = 0; p < count; ++p, ++primitive) {
      const DeformedPrimitive d =
          deform_primitive(side.asset, instance, p, rest, instance.skin >= 0 ? &identity : nullptr, mode);
      surface.positions.insert(surface.positions.end(), d.positions.begin(), d.positions.end());
      if (side.file_normals[primitive])
        surface.normals.insert(surface.normals.end(), d.normals.begin(), d.normals.end());
      else
        surface.normals.resize(surface.positions.size(), glm::dvec3(0));
    }
  }
  return surface;
}

CorrespondencePose choose_correspondence_pose(const DiffSide& a, const DiffSide& b, const Clip* clip_a,
                                              const Clip* clip_b, const std::string& clip_label, double time,
                                              BlendMode mode) {
  CorrespondencePose pose;
  pose.rest_a = side_distortion(a, a.rest);
  pose.rest_b = side_distortion(b, b.rest);
  if (!pose.rest_a.degenerate() && !pose.rest_b.degenerate()) return pose;
  if (clip_a && clip_b) {
    PosedSurface at_a = pose_surface(a, sample_pose(a.asset, clip_a, time), mode);
    PosedSurface at_b = pose_surface(b, sample_pose(b.asset, clip_b, time), mode);
    pose.clip_a = side_distortion(a, at_a);
    pose.clip_b = side_distortion(b, at_b);
    if (!pose.clip_a.degenerate() && !pose.clip_b.degenerate()) {
      pose.kind = PoseKind::kClip, pose.clip = clip_label, pose.time = time;
      pose.a = std::move(at_a), pose.b = std::move(at_b);
      return pose;
    }
  }
  pose.kind = PoseKind::kBind;
  pose.a = bind_surface(a, mode), pose.b = bind_surface(b, mode);
  return pose;
}

}  // namespace dqskin::diff_detail
