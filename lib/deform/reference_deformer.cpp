// The double-precision CPU reference (lib/skin) as a Deformer: frames sampled and deformed one by one,
// converted to float batches (to_batch), so that every consumer sees one batch type whichever path ran.
#include "reference_deformer.hpp"

#include "dqskin/frame_view.hpp"

#include <algorithm>
#include <chrono>
#include <exception>
#include <thread>

namespace dqskin::deform {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Frames per batch: consumers encode a batch's frames in parallel, as they do the GPU path's batches.
constexpr size_t kFramesPerBatch = 8;

class ReferenceDeformer final : public Deformer {
public:
  ReferenceDeformer(const Asset& asset, std::vector<MeshInstance> instances, const DeformerOptions& options)
      : asset_(asset), instances_(std::move(instances)), options_(options),
        threads_(int(options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency()))) {}

  void run(const Clip* clip, std::span<const double> times, const std::function<void(const DeformedBatch&)>& sink) override {
    const DeformedOutputs outputs = options_.positions_only ? DeformedOutputs::kPositions : DeformedOutputs::kAll;
    for (size_t first = 0; first < times.size(); first += kFramesPerBatch) {
      if (options_.before_batch) options_.before_batch();
      const size_t count = std::min(times.size() - first, kFramesPerBatch);
      std::vector<DeformedFrame> frames(count);
      std::vector<double> sample_seconds(count, 0), deform_seconds(count, 0);
      // Frames are independent, so threads share a batch's frames; a batch of fewer frames than threads
      // splits each frame's vertices instead (a mesh of many small primitives splits badly: each primitive
      // under 2048 vertices stays on one thread). Either way every frame's bits are the same.
      const size_t workers = std::min<size_t>(size_t(threads_), count);
      const int vertex_threads = workers > 1 ? 1 : threads_;
      std::vector<std::exception_ptr> failures(std::max<size_t>(workers, 1));  // a memory ceiling may throw
      auto deform = [&](size_t w) {
        try {
          for (size_t i = w; i < count; i += std::max<size_t>(workers, 1)) {
            Clock::time_point start = Clock::now();
            const Pose pose = sample_pose(asset_, clip, times[first + i]);
            sample_seconds[i] = since(start);
            start = Clock::now();
            frames[i] = deform_frame(asset_, instances_, pose, options_.mode, vertex_threads, outputs);
            deform_seconds[i] = since(start);
          }
        } catch (...) {
          failures[w] = std::current_exception();
        }
      };
      std::vector<std::thread> pool;
      for (size_t w = 1; w < workers; ++w) pool.emplace_back(deform, w);
      deform(0);
      for (std::thread& t : pool) t.join();
      for (const std::exception_ptr& failure : failures)
        if (failure) std::rethrow_exception(failure);
      for (size_t i = 0; i < count; ++i) {
        stats_.sample_seconds += sample_seconds[i];
        stats_.deform_seconds += deform_seconds[i];
      }
      sink(to_batch(frames, first));
    }
  }

  const DeformStats& stats() const override { return stats_; }
  size_t frames_per_batch() const override { return kFramesPerBatch; }

private:
  const Asset& asset_;
  const std::vector<MeshInstance> instances_;
  const DeformerOptions options_;
  const int threads_;
  DeformStats stats_;
};

}  // namespace

std::unique_ptr<Deformer> make_reference_deformer(const Asset& asset, std::vector<MeshInstance> instances,
                                                  const DeformerOptions& options) {
  return std::make_unique<ReferenceDeformer>(asset, std::move(instances), options);
}

}  // namespace dqskin::deform
