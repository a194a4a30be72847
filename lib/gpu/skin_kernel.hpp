// The "deform" stage on the GPU (internal to lib/gpu): glsl/skin.comp over the rest data of an asset's mesh
// instances. It only uploads (rest data once, each batch's bone textures and morph weights), dispatches and
// reads back; sampling, the palette and packing happen before it (GpuDeformer strings the stages).
#pragma once

#include "dqskin/animation.hpp"
#include "dqskin/bone_texture.hpp"
#include "dqskin/deformer.hpp"
#include "dqskin/deformed_batch.hpp"
#include "dqskin/gpu_context.hpp"
#include "dqskin/skinning.hpp"

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

namespace dqskin::gpu {

// Seconds of the calling thread: submitting and waiting for the GPU (deform), copying results back.
struct KernelTimes {
  double deform = 0, readback = 0;
};

// Two batches may be in flight: batch b is dispatched into output set b % 2 while batch b − 1 is read from
// the other. Not thread-safe; GL calls happen on the calling thread.
class SkinKernel {
public:
  // Uploads the rest data and sizes the output buffers for frames_per_batch() frames under
  // `memory_budget` bytes (two sets). Throws InputError for a mode without a GPU path or a skin too wide
  // for the GPU's textures, NoGpuContext when the context lacks an entry point.
  SkinKernel(GpuContext& context, const Asset& asset, std::vector<MeshInstance> instances, BlendMode mode,
             size_t memory_budget, bool mapped_readback);
  ~SkinKernel();
  SkinKernel(const SkinKernel&) = delete;
  SkinKernel& operator=(const SkinKernel&) = delete;

  size_t frames_per_batch() const;
  // Whether results are read through persistently mapped buffers (else glGetBufferSubData).
  bool mapped_readback() const;
  // Makes the context current on this thread; call before the first dispatch of a run.
  void make_current();

  // A dispatched batch: its fence, frames and output set.
  struct Submitted {
    void* fence = nullptr;  // a GLsync
    size_t frames = 0;
    int set = 0;
  };
  // Uploads `bones` (one per instance, a row per frame) and the poses' morph weights, then dispatches every
  // primitive into output `set` and starts the GPU. Shader variants compile on first use (a failure throws
  // std::runtime_error naming glsl/skin.comp and the line).
  Submitted dispatch(std::span<const BoneTexture> bones, std::span<const Pose> poses, int set, KernelTimes& times);
  // Waits for `batch` and, with `copy`, reads its outputs back into `out`, reusing its arrays (without,
  // they are left empty: for benchmarks of the deformation alone).
  void read_back(const Submitted& batch, size_t first_frame, bool copy, KernelTimes& times, DeformedBatch& out);

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dqskin::gpu
