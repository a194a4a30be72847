// The "deform" stage of docs/DESIGN.md §2.4 as one interface: callers ask for a clip at some times in one
// blend mode and receive DeformedBatches in frame order, whichever implementation runs (the compute shader
// on a headless GL context, the vectorized float CPU deformer, or the double-precision CPU reference).
// Which one runs is decided here, once, from the backend, the mode and the context.
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

// Whether a blend mode has a GPU path (and the fast CPU deformer's): dib exists only on the CPU reference.
bool has_gpu_path(BlendMode mode);

// Where a deformation runs.
enum class DeformPath { kGpu, kFastCpu, kReference };
// The CPU reference for --backend cpu and for a mode without a GPU path; fast-cpu for fast-cpu; the GPU
// path for egl and osmesa; for auto, the GPU path when `context` is a hardware GPU's, else fast-cpu.
DeformPath deform_path(Backend backend, BlendMode mode, const GpuContext* context);
// What runs, in words for --verbose, summaries and manifests: "gpu", "fast-cpu (avx2-fma)", "cpu-reference".
std::string describe(DeformPath path);
// The GpuContextInfo a report gives for a deformation on the CPU (backend "fast-cpu" or "cpu").
GpuContextInfo cpu_deformer_info(DeformPath path);

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
  // Frames a batch holds at most (fewer in the last one of a run).
  virtual size_t frames_per_batch() const = 0;
};

struct DeformerOptions {
  BlendMode mode = BlendMode::kDqs;
  Backend backend = Backend::kAuto;
  size_t gpu_memory = size_t(512) << 20;  // GPU: bytes of output buffers (--gpu-memory)
  unsigned threads = 0;                   // CPU deformers: threads, 0 for every core (results do not depend on it)
  bool positions_only = false;            // the CPU reference: no normals or tangents (a measurement of positions)
  std::function<void()> before_batch;     // CPU deformers: called before each batch (a cancellation point)
};

// The deformer of an asset's mesh instances for `options` on deform_path(options.backend, options.mode,
// context); the GPU path needs `context`. `context` and `asset` must outlive it.
std::unique_ptr<Deformer> make_deformer(GpuContext* context, const Asset& asset, std::vector<MeshInstance> instances,
                                        const DeformerOptions& options);

}  // namespace dqskin
