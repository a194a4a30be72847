// The double-precision CPU reference (lib/skin) as a Deformer: frames sampled and deformed one by one,
// converted to float batches (to_batch), so that every consumer sees one batch type whichever path ran.
#include "reference_deformer.hpp"

#include "dqskin/frame_view.hpp"

#include <algorithm>
#include <chrono>
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
    for (size_t first = 0; first < times.size(); first += kFramesPerBatch) {
      if (options_.before_batch) options_.before_batch();
      std::vector<DeformedFrame> frames;
      for (size_t f = first; f < std::min(times.size(), first + kFramesPerBatch); ++f) {
        Clock::time_point start = Clock::now();
        const Pose pose = sample_pose(asset_, clip, times[f]);
        stats_.sample_seconds += since(start);
        start = Clock::now();
        frames.push_back(deform_frame(asset_, instances_, pose, options_.mode, threads_));
        stats_.deform_seconds += since(start);
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
