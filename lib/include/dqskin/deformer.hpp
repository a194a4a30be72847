// The "deform" stage of shared/DESIGN.md as one interface: callers ask for a clip at some times in one
// blend mode and receive DeformedBatches in frame order, whichever implementation runs (the compute shader
// on a headless GL context, or the double-precision CPU reference). Which one runs is decided here, once,
// from the backend and the mode.
#pragma once

#include "dqskin/deformed_batch.hpp"
#include "dqskin/gpu_context.hpp"
#include "dqskin/skinning.hpp"

#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace dqskin {

// Whether a blend mode has a GPU path: dib exists only on the CPU reference.
bool has_gpu_path(BlendMode mode);
// Where a deformation runs: on the CPU reference for --backend cpu and for a mode without a GPU path.
bool deforms_on_cpu(Backend backend, BlendMode mode);

// Where a deformer's time went, accumulated over runs, in seconds of the calling thread.
struct DeformStats {
  double sample_seconds = 0;    // sampling poses, joint transforms and packing bone textures
  double deform_seconds = 0;    // deforming (on the GPU: uploading, dispatching, waiting for it to finish)
  double readback_seconds = 0;  // copying results to host memory (GPU only)
};

class Deformer {
public:
  virtual ~Deformer() = default;
  // Calls `sink` once per batch, in frame order (batch.first_frame counts from times[0]), possibly on
  // another thread; returns when the sink has seen every batch. An exception from the sink stops the run
  // and is rethrown here. `clip` may be null (rest pose).
  virtual void run(const Clip* clip, std::span<const double> times,
                   const std::function<void(const DeformedBatch&)>& sink) = 0;
  virtual const DeformStats& stats() const = 0;
};

struct DeformerOptions {
  BlendMode mode = BlendMode::kDqs;
  Backend backend = Backend::kAuto;
  size_t gpu_memory = size_t(512) << 20;  // GPU: bytes of output buffers (--gpu-memory)
  unsigned threads = 0;                   // CPU reference: threads per frame, 0 for every core
  std::function<void()> before_batch;     // CPU reference: called before each batch (a cancellation point)
};

// The deformer of an asset's mesh instances for `options`: the CPU reference where deforms_on_cpu(),
// otherwise the GPU path on `context` (then not null). `context` and `asset` must outlive it.
std::unique_ptr<Deformer> make_deformer(GpuContext* context, const Asset& asset, std::vector<MeshInstance> instances,
                                        const DeformerOptions& options);

}  // namespace dqskin
