// The fast CPU deformer: docs/DESIGN.md §1.1's stages on the CPU in float. Once per deformer, every primitive's rest
// data goes into structure-of-arrays blocks (fast_rest_data.hpp); per batch, sample → palette runs in
// parallel over frames, then the kernel over (frame, primitive, run of blocks), and the finished batch
// goes to the sink on a thread of its own while the next one is computed. Every vertex of every frame is
// computed by the same instructions whatever the thread count, so the bytes do not depend on it.
#include "fast_cpu_deformer.hpp"

#include "dqskin/error.hpp"

#include "../base/ordered_worker.hpp"
#include "../base/parallel_for.hpp"
#include "fast_rest_data.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <thread>

namespace dqskin::deform {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Output bytes of one batch: enough frames for every core to encode one (consumers encode a batch's frames
// in parallel), few enough that the three batch buffers (one computed, one waiting, one in the sink) stay
// small beside the asset.
constexpr size_t kBatchBytes = size_t(64) << 20;
constexpr size_t kMaxFramesPerBatch = 64;
// Blocks of kLanes vertices per work item: large enough to amortize a task, small enough to balance.
constexpr size_t kBlocksPerItem = 256;

// One frame's palettes and morph weights, indexed by mesh instance. Instances of one skin share the palette
// of the first of them (palette_owner_), so only owners' entries are filled.
struct FramePalettes {
  std::vector<std::vector<float>> palette;   // (joints + 1) · kPaletteStride floats
  std::vector<KernelMode> mode;
  std::vector<std::vector<float>> morph;     // morph weights as float, one per target
};

class FastCpuDeformer final : public Deformer {
public:
  FastCpuDeformer(const Asset& asset, std::vector<MeshInstance> instances, const DeformerOptions& options, KernelIsa isa)
      : asset_(asset), instances_(std::move(instances)), options_(options),
        threads_(options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency())), isa_(isa),
        rest_(make_rest_data(asset, instances_)) {
    if (!has_gpu_path(options.mode))
      throw InputError(std::string("mode ") + to_string(options.mode) + " runs on the CPU reference only");
    // The first instance of each skin owns the palette that its later instances read.
    palette_owner_.resize(instances_.size());
    for (size_t i = 0; i < instances_.size(); ++i) {
      palette_owner_[i] = i;
      for (size_t j = 0; j < i && instances_[i].skin >= 0; ++j)
        if (instances_[j].skin == instances_[i].skin) {
          palette_owner_[i] = j;
          break;
        }
    }
    size_t frame_bytes = 0;
    targets_.assign(instances_.size(), 0);
    for (const RestPrimitive& r : rest_) {
      frame_bytes += r.output_bytes_per_frame();
      targets_[r.instance] = std::max(targets_[r.instance], r.view.targets);
    }
    frames_per_batch_ = std::clamp<size_t>(kBatchBytes / std::max<size_t>(1, frame_bytes), 1, kMaxFramesPerBatch);
  }

  void run(const Clip* clip, std::span<const double> times, const std::function<void(const DeformedBatch&)>& sink) override {
    // Batch b is computed into buffer b % 3 while the worker may still hold b − 1 (waiting) and b − 2 (in
    // the sink): reusing the buffers spares the page faults and zero-filling of fresh output arrays.
    concurrency::OrderedWorker<const DeformedBatch*> worker([&](const DeformedBatch* batch) { sink(*batch); });
    for (size_t first = 0, b = 0; first < times.size(); first += frames_per_batch_, ++b) {
      if (options_.before_batch) options_.before_batch();
      const std::span<const double> batch_times = times.subspan(first, std::min(frames_per_batch_, times.size() - first));
      Clock::time_point start = Clock::now();
      const std::vector<FramePalettes> palettes = make_palettes(clip, batch_times);
      stats_.sample_seconds += since(start);
      start = Clock::now();
      DeformedBatch& batch = buffers_[b % buffers_.size()];
      deform(palettes, first, batch);
      stats_.deform_seconds += since(start);
      worker.push(&batch);
    }
    worker.finish();
  }

  const DeformStats& stats() const override { return stats_; }
  size_t frames_per_batch() const override { return frames_per_batch_; }

private:
  // sample → palette for every frame of a batch, frames in parallel.
  std::vector<FramePalettes> make_palettes(const Clip* clip, std::span<const double> times) const {
    std::vector<FramePalettes> out(times.size());
    concurrency::parallel_for(times.size(), threads_, [&](size_t f) {
      const Pose pose = sample_pose(asset_, clip, times[f]);
      FramePalettes& frame = out[f];
      frame.palette.resize(instances_.size());
      frame.mode.resize(instances_.size());
      frame.morph.resize(instances_.size());
      for (size_t i = 0; i < instances_.size(); ++i) {
        const MeshInstance& inst = instances_[i];
        if (palette_owner_[i] == i)  // a rigid instance's one joint is its node's world matrix: lbs, as the reference
          frame.mode[i] = pack_palette(instance_joint_transforms(asset_, inst, pose),
                                       inst.skin < 0 ? BlendMode::kLbs : options_.mode, frame.palette[i]);
        // One weight per target of the instance's primitives; a target beyond the node's weights has none.
        const std::vector<double>& weights = pose.weights[size_t(inst.node)];
        frame.morph[i].assign(weights.begin(), weights.end());
        frame.morph[i].resize(std::max(frame.morph[i].size(), targets_[i]), 0.0f);
      }
    });
    return out;
  }

  // The kernel over every (frame, primitive, run of blocks) of the batch, into `batch` (every value written).
  void deform(const std::vector<FramePalettes>& palettes, size_t first, DeformedBatch& batch) const {
    batch.first_frame = first;
    batch.frame_count = palettes.size();
    batch.primitives.resize(rest_.size());
    struct Item {
      size_t frame, primitive, first_block, last_block;
    };
    std::vector<Item> items;
    for (size_t p = 0; p < rest_.size(); ++p) {
      const RestPrimitive& r = rest_[p];
      DeformedBatch::Primitive& out = batch.primitives[p];
      out.vertices = r.vertices;
      out.positions.resize(r.vertices * 3 * palettes.size());
      if (r.has_normals()) out.normals.resize(r.vertices * 3 * palettes.size());
      if (r.has_tangents()) out.tangents.resize(r.vertices * 4 * palettes.size());
      for (size_t f = 0; f < palettes.size(); ++f)
        for (size_t b = 0; b < r.view.blocks; b += kBlocksPerItem)
          items.push_back({f, p, b, std::min(r.view.blocks, b + kBlocksPerItem)});
    }
    concurrency::parallel_for(items.size(), threads_, [&](size_t i) {
      const Item& item = items[i];
      const RestPrimitive& r = rest_[item.primitive];
      const FramePalettes& frame = palettes[item.frame];
      DeformedBatch::Primitive& out = batch.primitives[item.primitive];
      KernelFrame k;
      const size_t owner = palette_owner_[r.instance];
      k.palette = frame.palette[owner].data();
      k.morph_weights = frame.morph[r.instance].data();
      k.vertices = r.vertices;
      k.positions = out.positions.data() + item.frame * r.vertices * 3;
      if (r.has_normals()) k.normals = out.normals.data() + item.frame * r.vertices * 3;
      if (r.has_tangents()) k.tangents = out.tangents.data() + item.frame * r.vertices * 4;
      kernel_function(frame.mode[owner], isa_)(r.view, k, item.first_block, item.last_block);
    });
  }

  const Asset& asset_;
  const std::vector<MeshInstance> instances_;
  const DeformerOptions options_;
  const unsigned threads_;
  const KernelIsa isa_;
  const std::vector<RestPrimitive> rest_;
  std::vector<size_t> palette_owner_;  // per instance: the instance whose palette it reads
  std::vector<size_t> targets_;  // per instance: the most morph targets of its primitives
  size_t frames_per_batch_ = 1;
  std::array<DeformedBatch, 3> buffers_;
  DeformStats stats_;
};

}  // namespace

std::unique_ptr<Deformer> make_fast_cpu_deformer(const Asset& asset, std::vector<MeshInstance> instances,
                                                 const DeformerOptions& options, KernelIsa isa) {
  return std::make_unique<FastCpuDeformer>(asset, std::move(instances), options, isa);
}

}  // namespace dqskin::deform
