// A clip as a morph-target animation in one glTF 2.0 binary (internal to lib/write and lib/bake): every baked
// primitive in world space under one node, the clip's first frame as the mesh, one morph target per further
// key holding that key's displacements from the mesh (§3.7.2.2), and an animation of the node's weights that
// is one-hot at each key (all zeros at the first), so that a viewer interpolating the weights linearly
// (§3.11) interpolates the two neighbouring keys' vertices linearly: no skinning, in any glTF 2.0 viewer.
// Optionally KHR_mesh_quantization: positions on an integer grid that the node's transform decodes.
#pragma once

#include "glb_appearance.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace dqskin::glb {

// KHR_mesh_quantization's grid for positions: position = origin + step · q with q ∈ [0, kMax] on each axis,
// the node's translation and (uniform: a non-uniform scale would turn the normals) scale. kMax = 2^15 − 1,
// so that the difference of two grid points, a target's displacement, fits a SHORT.
struct MorphGrid {
  static constexpr int kMax = 32767;
  glm::dvec3 origin{0.0};  // float values, as the node's translation holds them
  double step = 0;         // a float value, as the node's scale holds it; 0: no grid (float positions)

  // The grid over the box lo..hi: the coarsest whose kMax + 1 points per axis cover the box's largest side.
  static MorphGrid over(const glm::dvec3& lo, const glm::dvec3& hi);
  bool on() const { return step > 0; }
  // The grid point nearest to p (3 floats), clamped to the grid.
  glm::ivec3 quantize(const float* p) const;
  glm::dvec3 decode(const glm::ivec3& q) const { return origin + step * glm::dvec3(q); }
  // How far a point of the box is from its grid point at most: half a step on every axis, step · √3 / 2.
  double bound() const;
};

// What a viewer decodes (in exact arithmetic) for a key's position `p` (3 floats) stored against the base
// position `base`: with the grid, p's grid point; else base plus the float displacement written.
glm::dvec3 stored_position(const MorphGrid& grid, const float* base, const float* p);

// Whether a target's normal displacements from `base` to `key` (3 per vertex, unit) are written as
// normalized SHORTs (with the grid: KHR_mesh_quantization allows them when every component fits [-1, 1]);
// else they are floats.
bool short_normal_target(const MorphGrid& grid, std::span<const float> base, std::span<const float> key);
// What a viewer decodes (before normalizing) for a key's normal `n` stored against `base`: with the grid the
// base is a normalized SHORT (c / 32767), and a SHORT target (short_target) adds the difference of the two
// quantized normals; a float target adds the float difference.
glm::dvec3 stored_normal(const MorphGrid& grid, bool short_target, const float* base, const float* n);

// One clip's keys, as encode_morph_glb writes them.
struct MorphAnimation {
  std::string name;  // the node's and the mesh's
  std::string clip;  // the animation's
  MorphGrid grid;
  std::vector<double> times;                      // per key, strictly increasing as floats
  std::vector<std::string> target_names;          // per key but the first (mesh.extras.targetNames)
  // per key: 3 per vertex, world space, in shared_vertex_layout's order (each distinct vertex once)
  std::vector<std::span<const float>> positions;
  std::vector<std::span<const float>> normals;    // per key, the same layout, unit
  std::vector<bool> with_normals;                 // per primitive that writes vertices: whether it has NORMAL
};

// What the file holds, for reports and tests.
struct MorphGlbStats {
  size_t targets = 0;
  size_t sparse_accessors = 0;        // morph-target and weight accessors written sparse (§3.6.2.3)
  size_t float_normal_targets = 0;    // with the grid: target normals that did not fit SHORT
};

// The .glb bytes of `animation` over the primitives that `instances` draw (in their order), each with its
// source's fixed attributes, indices and material from `appearance` (read_appearance over the same
// instances). A single key writes the mesh without targets or animation. A target accessor is written
// sparse where that takes fewer bytes. Deterministic. In two parts (glb_appearance.hpp), so that the file's
// bytes are never copied whole.
// `spill`: where the BIN chunk's bytes go as they are made instead of memory (BinWriter::spill); the parts
// then count them in `spilled`.
GlbParts encode_morph_glb(const Asset& asset, const std::vector<MeshInstance>& instances,
                             const Appearance& appearance, const MorphAnimation& animation,
                             MorphGlbStats* stats = nullptr, std::function<void(std::span<const char>)> spill = {});

}  // namespace dqskin::glb
