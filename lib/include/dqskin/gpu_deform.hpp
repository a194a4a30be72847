// GPU deformation (shared/DESIGN.md "pack" and "deform"): joint dual quaternions of every frame packed
// into a BoneTexture, and the compute shader glsl/skin.comp deforming every vertex of every frame of a
// batch in one dispatch. Library users never touch GL.
#pragma once

#include "dqskin/gpu_context.hpp"
#include "dqskin/skinning.hpp"

#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace dqskin {

// The BoneTexture of DESIGN.md: RGBA32F, one row per frame, T texels per joint (T = 2: real, dual;
// T = 5 when any joint of any frame is non-rigid: real, dual, then the three rows of S with w = 0).
// Texel (T·j + k, f) is component k of joint j at frame f, joints in the skin's order.
struct BoneTexture {
  int texels_per_joint = 2;
  size_t joints = 0;
  size_t frames = 0;
  std::vector<float> rgba;  // frames × joints × T × 4, row-major

  size_t width() const { return joints * size_t(texels_per_joint); }
};

// Packs one skin's JointTransforms, one per frame.
BoneTexture pack_bone_texture(std::span<const JointTransforms> frames);

// The deformed vertices of several consecutive frames, for every primitive of every instance (in the
// order of deform_frame). Arrays are frame-major: positions[(f · vertices + v) · 3 + c].
struct DeformedBatch {
  size_t first_frame = 0;
  size_t frame_count = 0;
  struct Primitive {
    size_t vertices = 0;
    std::vector<float> positions;  // 3 per vertex
    std::vector<float> normals;    // 3 per vertex, or empty
    std::vector<float> tangents;   // 4 per vertex (w handedness), or empty
  };
  std::vector<Primitive> primitives;
};

struct GpuDeformOptions {
  BlendMode mode = BlendMode::kDqs;                // lbs or dqs; dib is CPU-only (InputError)
  size_t memory_budget = size_t(512) << 20;  // bytes of GPU output buffers (--gpu-memory); two batches are
                                             // in flight, one computed while the other is read back
  bool read_back = true;  // false: wait for the GPU (glFinish) but leave the results there; batches
                          // reach the sink with empty arrays (for benchmarks of the deformation alone)
};

// Where a run's time went, accumulated over runs, in seconds of the calling thread.
struct GpuDeformStats {
  double sample_seconds = 0;    // sampling poses, joint transforms and packing bone textures
  double deform_seconds = 0;    // uploading, dispatching, and waiting for the GPU to finish
  double readback_seconds = 0;  // copying results to host memory
};

// Deforms an asset's mesh instances on the GPU. Uploads the rest data once; each run() samples the clip,
// packs the bone textures and dispatches batch after batch into two alternating sets of output buffers,
// reading batch b − 1 back (and handing it to the sink) while batch b is being computed. Not thread-safe.
class GpuDeformer {
public:
  // `context` and `asset` must outlive the deformer. Throws InputError for mode dib, NoGpuContext when
  // the context lacks an entry point, std::runtime_error (naming glsl/skin.comp and the line) when a
  // shader variant does not compile.
  GpuDeformer(GpuContext& context, const Asset& asset, std::vector<MeshInstance> instances,
              const GpuDeformOptions& options);
  ~GpuDeformer();
  GpuDeformer(const GpuDeformer&) = delete;
  GpuDeformer& operator=(const GpuDeformer&) = delete;

  // Frames per batch under the memory budget (at least 1).
  size_t frames_per_batch() const;
  const GpuDeformStats& stats() const;

  // Calls `sink` once per batch, in frame order, on a thread of its own, so that the sink's work (encoding,
  // writing) overlaps the next batches' readback and dispatch; returns when the sink has seen every batch.
  // An exception from the sink stops the run and is rethrown here. `clip` may be null (rest pose).
  void run(const Clip* clip, std::span<const double> times, const std::function<void(const DeformedBatch&)>& sink);

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dqskin
