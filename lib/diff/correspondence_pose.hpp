// Where the geometric diff makes its correspondence (internal to lib/diff). The closest-point search needs
// a pose in which both surfaces are laid out as the files mean them; the rest pose (the nodes' transforms
// without animation) usually is one, but some real exports keep the pose only in their clips, and their
// nodes alone fold the mesh onto itself, where a vertex lies near parts it does not belong to.
#pragma once

#include "diff_side.hpp"

#include "dqskin/animation.hpp"
#include "dqskin/asset.hpp"
#include "dqskin/skinning.hpp"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace dqskin::diff_detail {

// A triangle is distorted at a pose when one of its edges is more than kStretch times, or less than
// 1 / kStretch times, its length at the bind pose, measured against its primitive's median ratio (so that a
// uniform scale, an armature at 0.01 or a quantized POSITION, is no distortion), or when it is turned over
// against the bind pose (its face normal on the other side of its vertices' normals; where the file has
// normals). Skinning an animated pose keeps triangles so almost everywhere (blending around a bent joint
// shortens some edges by tens of per cent, folds a few), while a crumpled pose moves whole parts onto or
// through each other and crushes or turns over the triangles that join them. Only skinned primitives are
// measured: a rigid instance's rest pose is an affine map of its mesh, which cannot crumple it.
constexpr double kStretch = 2.0;
// A pose is degenerate when more than this share of its triangles are distorted.
constexpr double kDegenerateShare = 0.05;
// A primitive's median ratio is taken over the edges of at most this many of its triangles, evenly spread,
// so that the measure needs no memory in proportion to the mesh.
constexpr size_t kMedianTriangles = 16384;

struct PoseDistortion {
  uint64_t triangles = 0;  // triangles with an area at the bind pose
  uint64_t distorted = 0;  // of them, those distorted
  double share() const { return triangles ? double(distorted) / double(triangles) : 0.0; }
  bool degenerate() const { return share() > kDegenerateShare; }
  PoseDistortion& operator+=(const PoseDistortion& o) {
    triangles += o.triangles, distorted += o.distorted;
    return *this;
  }
};

// One primitive's distortion. `posed_positions` and `posed_normals`: its vertices at the pose (normals zero
// where unknown); `bind_positions` and `bind_normals`: as POSITION and NORMAL store them (normals may be
// empty); `triangles`: three vertex numbers each, vertex v at index v − `first` of those spans. A primitive
// whose median ratio is zero (everything collapsed onto a point) or not finite has all its triangles
// distorted.
PoseDistortion primitive_distortion(std::span<const glm::dvec3> posed_positions,
                                    std::span<const glm::dvec3> posed_normals,
                                    std::span<const glm::vec3> bind_positions, std::span<const glm::vec3> bind_normals,
                                    std::span<const uint32_t> triangles, size_t first = 0);

// The distortion of every skinned primitive of `side` at `posed` against what its POSITION stores.
PoseDistortion side_distortion(const DiffSide& side, const PosedSurface& posed);

// `side`'s bind pose: what POSITION stores (morphed by the mesh's default weights), every joint matrix the
// identity (glTF 2.0 §3.7.3.2: joint matrices are the identity when the joints are where the inverse bind
// matrices put them); a rigid instance at its node's rest transform. Normals as PosedSurface has them.
PosedSurface bind_surface(const DiffSide& side, BlendMode mode);

enum class PoseKind { kRest, kClip, kBind };

// The pose both sides are compared at to make the correspondence, and why.
struct CorrespondencePose {
  PoseKind kind = PoseKind::kRest;
  std::string clip;   // kClip: A's clip label
  double time = 0;    // kClip: the time in seconds
  PoseDistortion rest_a, rest_b;  // of the rest pose, against the bind pose
  PoseDistortion clip_a, clip_b;  // of the clip's pose, when it was tried
  PosedSurface a, b;  // both surfaces at the pose, unless it is the rest pose (the sides hold that)

  const PosedSurface& of_a(const DiffSide& side) const { return kind == PoseKind::kRest ? side.rest : a; }
  const PosedSurface& of_b(const DiffSide& side) const { return kind == PoseKind::kRest ? side.rest : b; }
};

// The rest pose when neither side's is degenerate; else the pose of the clips `clip_a` and `clip_b` at
// `time` (the first time they are compared) when neither side's is degenerate there (the clips pose both
// files the same way whatever an optimizer did to their stored positions); else the bind pose. The clips
// may be null (neither file animates): the bind pose then. `clip_label`: A's clip, for the report.
CorrespondencePose choose_correspondence_pose(const DiffSide& a, const DiffSide& b, const Clip* clip_a,
                                              const Clip* clip_b, const std::string& clip_label, double time,
                                              BlendMode mode);

}  // namespace dqskin::diff_detail
