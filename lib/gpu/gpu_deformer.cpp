// The GPU deformer: the stages of docs/DESIGN.md §1.1 strung batch by batch. sample (Pose per frame) →
// palette and pack (one BoneTexture per instance) on the CPU, then SkinKernel uploads, dispatches and reads
// back, with two batches in flight and the sink on a thread of its own.
#include "dqskin/gpu_deform.hpp"

#include "../base/ordered_worker.hpp"
#include "skin_kernel.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <optional>
#include <utility>

namespace dqskin {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

}  // namespace

struct GpuDeformer::Impl {
  const Asset& asset;
  const std::vector<MeshInstance> instances;
  const bool read_back;
  gpu::SkinKernel kernel;
  std::array<DeformedBatch, 3> buffers;  // read-back batches, reused run after run
  DeformStats stats;

  Impl(GpuContext& context, const Asset& a, std::vector<MeshInstance> inst, const GpuDeformOptions& options)
      : asset(a), instances(std::move(inst)), read_back(options.read_back),
        kernel(context, a, instances, options.mode, options.memory_budget, options.mapped_readback) {}

  // sample → palette → pack → dispatch for frames [first, first + count).
  gpu::SkinKernel::Submitted dispatch(const Clip* clip, std::span<const double> times, int set, gpu::KernelTimes& t) {
    const Clock::time_point start = Clock::now();
    std::vector<Pose> poses(times.size());
    for (size_t f = 0; f < times.size(); ++f) poses[f] = sample_pose(asset, clip, times[f]);
    const std::vector<BoneTexture> bones = pack_instance_textures(asset, instances, poses);
    stats.sample_seconds += since(start);
    return kernel.dispatch(bones, poses, set, t);
  }

  void run(const Clip* clip, std::span<const double> times, const std::function<void(const DeformedBatch&)>& sink) {
    kernel.make_current();
    gpu::KernelTimes t;
    // The sink runs on its own thread: while it writes batch b − 2, batch b − 1 is read back and batch b
    // is computed. Batch b is read into buffer b % 3, whose arrays are reused from batch b − 3 (the worker
    // holds at most b − 1 waiting and b − 2 in the sink): no page faults and zero-filling of fresh arrays.
    concurrency::OrderedWorker<const DeformedBatch*> worker([&](const DeformedBatch* batch) { sink(*batch); });
    struct InFlight {
      gpu::SkinKernel::Submitted submitted;
      size_t first = 0;
    };
    std::optional<InFlight> previous;
    size_t delivered = 0;
    auto deliver = [&] {
      DeformedBatch& out = buffers[delivered++ % buffers.size()];
      kernel.read_back(previous->submitted, previous->first, read_back, t, out);
      worker.push(&out);
      stats.deform_seconds += std::exchange(t.deform, 0.0);
      stats.readback_seconds += std::exchange(t.readback, 0.0);
    };
    const size_t batch = kernel.frames_per_batch();
    int set = 0;
    for (size_t first = 0; first < times.size(); first += batch, set ^= 1) {
      const size_t count = std::min(batch, times.size() - first);
      const gpu::SkinKernel::Submitted submitted = dispatch(clip, times.subspan(first, count), set, t);
      stats.deform_seconds += std::exchange(t.deform, 0.0);
      if (previous) deliver();
      previous = InFlight{submitted, first};
    }
    if (previous) deliver();
    worker.finish();
  }
};

GpuDeformer::GpuDeformer(GpuContext& context, const Asset& asset, std::vector<MeshInstance> instances,
                         const GpuDeformOptions& options)
    : impl_(std::make_unique<Impl>(context, asset, std::move(instances), options)) {}
GpuDeformer::~GpuDeformer() = default;
size_t GpuDeformer::frames_per_batch() const { return impl_->kernel.frames_per_batch(); }
bool GpuDeformer::mapped_readback() const { return impl_->kernel.mapped_readback(); }
const DeformStats& GpuDeformer::stats() const { return impl_->stats; }
void GpuDeformer::run(const Clip* clip, std::span<const double> times,
                      const std::function<void(const DeformedBatch&)>& sink) {
  impl_->run(clip, times, sink);
}

}  // namespace dqskin
