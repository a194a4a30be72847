// GPU deformation (docs/DESIGN.md §2.4): the compute shader glsl/skin.comp reads a BoneTexture
// (bone_texture.hpp) and deforms every vertex of every frame of a batch in one dispatch, handing out
// DeformedBatches (deformed_batch.hpp). Library users never touch GL.
#pragma once

#include "dqskin/bone_texture.hpp"
#include "dqskin/deformed_batch.hpp"
#include "dqskin/deformer.hpp"
#include "dqskin/gpu_context.hpp"
#include "dqskin/skinning.hpp"

#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace dqskin {

struct GpuDeformOptions {
  BlendMode mode = BlendMode::kDqs;          // lbs or dqs; a mode without has_gpu_path() is an InputError
  size_t memory_budget = size_t(512) << 20;  // bytes of GPU output buffers (--gpu-memory); two batches are
                                             // in flight, one computed while the other is read back
  bool read_back = true;  // false: wait for the GPU (glFinish) but leave the results there; batches
                          // reach the sink with empty arrays (for benchmarks of the deformation alone)
  // Read results through output buffers mapped once for the deformer's life (glBufferStorage with
  // MAP_PERSISTENT, a fence per batch) where the context has OpenGL 4.4 or ARB_buffer_storage; false, or a
  // context with neither: glGetBufferSubData. The bytes are the same either way.
  bool mapped_readback = true;
};

// Deforms an asset's mesh instances on the GPU. Uploads the rest data once; each run() samples the clip,
// packs the bone textures and dispatches batch after batch into two alternating sets of output buffers,
// reading batch b − 1 back (and handing it to the sink) while batch b is being computed. Not thread-safe.
class GpuDeformer final : public Deformer {
public:
  // `context` and `asset` must outlive the deformer. Throws InputError for mode dib, NoGpuContext when
  // the context lacks an entry point, std::runtime_error (naming glsl/skin.comp and the line) when a
  // shader variant does not compile.
  GpuDeformer(GpuContext& context, const Asset& asset, std::vector<MeshInstance> instances,
              const GpuDeformOptions& options);
  ~GpuDeformer() override;
  GpuDeformer(const GpuDeformer&) = delete;
  GpuDeformer& operator=(const GpuDeformer&) = delete;

  // Frames per batch under the memory budget (at least 1).
  size_t frames_per_batch() const override;
  // Whether results are read through persistently mapped buffers (GpuDeformOptions::mapped_readback).
  bool mapped_readback() const;
  const DeformStats& stats() const override;

  // Calls `sink` once per batch, in frame order, on a thread of its own, so that the sink's work (encoding,
  // writing) overlaps the next batches' readback and dispatch; returns when the sink has seen every batch.
  // An exception from the sink stops the run and is rethrown here. `clip` may be null (rest pose).
  void run(const Clip* clip, std::span<const double> times,
           const std::function<void(const DeformedBatch&)>& sink) override;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dqskin
