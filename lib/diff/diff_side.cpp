#include "diff_side.hpp"
#include "clip_matching.hpp"
#include "../base/saturating.hpp"

#include "dqskin/animation.hpp"
#include "../base/byte_size.hpp"
#include "dqskin/error.hpp"
#include "dqskin/memory_ceiling.hpp"
#include "dqskin/triangles.hpp"

#include <algorithm>
#include <map>
#include <new>

namespace dqskin::diff_detail {
namespace {

// The joint a vertex mostly follows: its largest weight's (the first of equal ones), or the instance's
// own node for rigid instances and weightless vertices, which move with it.
uint32_t joint_of_vertex(const DiffSide& side, const MeshInstance& instance, const Primitive& primitive, size_t v,
                         std::map<std::string, uint32_t>& names, std::vector<std::string>& table) {
  int node = instance.node;
  if (instance.skin >= 0 && primitive.influences > 0) {
    const size_t n = size_t(primitive.influences);
    float best = 0;
    for (size_t k = 0; k < n; ++k)
      if (primitive.weights[v * n + k] > best) {
        best = primitive.weights[v * n + k];
        node = side.asset.skins[size_t(instance.skin)].joints[primitive.joints[v * n + k]];
      }
  }
  const std::string label = node_label(side.asset, node);
  const auto [it, added] = names.emplace(label, uint32_t(table.size()));
  if (added) table.push_back(label);
  return it->second;
}

// Corners of the triangles triangle_list makes of a primitive (without making them).
uint64_t triangle_corners(const Primitive& p) {
  const uint64_t n = p.indices.empty() ? p.vertex_count() : p.indices.size();
  switch (p.mode) {
    case PrimitiveMode::kTriangles: return n / 3 * 3;
    case PrimitiveMode::kTriangleStrip:
    case PrimitiveMode::kTriangleFan: return n < 3 ? 0 : (n - 2) * 3;
    default: return 0;
  }
}

// Bytes per vertex a DiffSide holds (rest position and normal in double, joint, on_surface), and what
// deform_frame's rest pose takes while it is made (position and normal in double, a tangent in double
// and its handedness); bytes per triangle corner held (the triangle list) and, for the primitive being
// listed, copied.
constexpr uint64_t kSideBytesPerVertex = 24 + 24 + 4 + 1;
constexpr uint64_t kRestBytesPerVertex = 24 + 24 + 32;
constexpr uint64_t kBytesPerCorner = 4 + 4;

}  // namespace

SideSize diff_side_size(const Asset& asset) {
  using saturating::add;
  using saturating::mul;
  SideSize size;
  uint64_t corners = 0;
  for (const MeshInstance& instance : mesh_instances(asset, choose_scene(asset, -1)))
    for (const Primitive& primitive : asset.meshes[size_t(instance.mesh)].primitives) {
      size.vertices = add(size.vertices, primitive.vertex_count());
      corners = add(corners, triangle_corners(primitive));
    }
  size.bytes = add(mul(size.vertices, kSideBytesPerVertex + kRestBytesPerVertex), mul(corners, kBytesPerCorner));
  return size;
}

uint64_t memory_left(uint64_t max) {
  const uint64_t used = memory_in_use();
  return used >= max ? 0 : max - used;
}

std::string left_text(uint64_t left, uint64_t max) {
  return left >= max ? "--max-memory " + byte_size(max)
                     : "the " + byte_size(left) + " that --max-memory " + byte_size(max) + " leaves";
}

void check_side_fits(const Asset& asset, uint64_t max) {
  const SideSize size = diff_side_size(asset);
  const uint64_t left = memory_left(max);
  if (size.bytes > left)
    throw InputError("comparing its " + std::to_string(size.vertices) + " vertices needs about " + byte_size(size.bytes) +
                     ", more than " + left_text(left, max));
}

DiffSide load_diff_side(const std::string& path, const LoadOptions& load, BlendMode mode) {
  try {
    Asset asset = load_asset(path, load);
    check_side_fits(asset, load.max_memory);
    return make_diff_side(std::move(asset), mode);
  } catch (const InputError& e) {
    throw InputError(path + ": " + e.what());
  } catch (const std::bad_alloc&) {  // the ceiling's refusal; what the file took is freed by now
    const MemoryCeilingLifted lifted;
    throw InputError(path + ": " + out_of_memory_message());
  }
}

DiffSide make_diff_side(Asset asset, BlendMode mode) {
  DiffSide side;
  side.asset = std::move(asset);
  side.instances = mesh_instances(side.asset, choose_scene(side.asset, -1));
  std::map<std::string, uint32_t> names;
  for (const MeshInstance& instance : side.instances)
    for (const Primitive& primitive : side.asset.meshes[size_t(instance.mesh)].primitives) {
      const size_t first = side.vertices;
      side.first_vertex.push_back(first);
      side.primitive_size.push_back(primitive.vertex_count());
      side.file_normals.push_back(!primitive.normals.empty() && !primitive.normals_generated);
      side.vertices += primitive.vertex_count();
      const std::vector<uint32_t> triangles = triangle_list(primitive);
      // Only the vertices a triangle uses are compared: an optimizer drops the others (gltfpack does), and
      // a primitive that shares its vertex buffer with others uses only its part of it.
      side.on_surface.resize(side.vertices, 0);
      for (uint32_t i : triangles) {
        side.triangles.push_back(uint32_t(first + i));
        side.on_surface[first + i] = 1;
      }
      for (size_t v = 0; v < primitive.vertex_count(); ++v)
        side.joint.push_back(joint_of_vertex(side, instance, primitive, v, names, side.joint_names));
    }
  if (side.triangles.empty()) throw InputError("the scene has no triangles to compare");
  if (side.vertices > UINT32_MAX) throw InputError("the scene has more than 2^32 vertices");

  side.rest = pose_surface(side, sample_pose(side.asset, nullptr, 0), mode);
  return side;
}

PosedSurface pose_surface(const DiffSide& side, const Pose& pose, BlendMode mode) {
  const DeformedFrame frame = deform_frame(side.asset, side.instances, pose, mode);
  PosedSurface surface;
  surface.positions.reserve(side.vertices);
  surface.normals.reserve(side.vertices);
  for (size_t i = 0; i < frame.primitives.size(); ++i) {
    const DeformedPrimitive& p = frame.primitives[i];
    surface.positions.insert(surface.positions.end(), p.positions.begin(), p.positions.end());
    if (!side.file_normals[i])
      surface.normals.resize(surface.positions.size(), glm::dvec3(0));
    else
      surface.normals.insert(surface.normals.end(), p.normals.begin(), p.normals.end());
  }
  return surface;
}

void gather_frame(const DiffSide& side, const DeformedBatch& batch, size_t frame, SideFrame& out) {
  out.positions.resize(3 * side.vertices);
  out.normals.resize(3 * side.vertices);
  for (size_t p = 0; p < batch.primitives.size(); ++p) {
    const DeformedBatch::Primitive& prim = batch.primitives[p];
    const size_t n = 3 * prim.vertices, at = 3 * side.first_vertex[p];
    std::copy_n(prim.positions.begin() + std::ptrdiff_t(frame * n), n, out.positions.begin() + std::ptrdiff_t(at));
    if (side.file_normals[p])
      std::copy_n(prim.normals.begin() + std::ptrdiff_t(frame * n), n, out.normals.begin() + std::ptrdiff_t(at));
    else
      std::fill_n(out.normals.begin() + std::ptrdiff_t(at), n, 0.0f);
  }
}

}  // namespace dqskin::diff_detail
