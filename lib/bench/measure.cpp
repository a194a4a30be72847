#include "measure.hpp"

#include "dqskin/deformer.hpp"
#include "dqskin/gpu_deform.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <memory>
#include <thread>
#include <vector>

namespace dqskin::bench_detail {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Calls `step` (which returns how many frames it did) until at least `min_seconds` have passed; returns
// frames per second.
template <class Step>
double frames_per_second(double min_seconds, const Step& step) {
  size_t frames = 0;
  const Clock::time_point start = Clock::now();
  double elapsed = 0;
  do {
    frames += step();
    elapsed = seconds_since(start);
  } while (elapsed < min_seconds);
  return double(frames) / elapsed;
}

}  // namespace

// GPU: runs whole batches until at least `min_seconds` passed (after one warm-up batch, which also
// compiles the shader variant), and counts vertex-frames.
BenchMeasurement measure_gpu(GpuContext& ctx, const Asset& asset, BlendMode mode, size_t frames_per_batch, bool readback,
                        size_t memory_budget, double min_seconds) {
  const std::vector<MeshInstance> instances = mesh_instances(asset, 0);
  const size_t vertices = asset.meshes[0].primitives[0].vertex_count();
  const size_t frame_bytes = vertices * 24;
  // Two batches are in flight (GpuDeformOptions::memory_budget), so ask for room for two.
  GpuDeformOptions options{mode, std::min(memory_budget, 2 * frames_per_batch * frame_bytes), readback};
  GpuDeformer gpu(ctx, asset, instances, options);
  const size_t batch = gpu.frames_per_batch();
  std::vector<double> times(batch);
  // Times inside the clip, away from t = 0 where the synthetic joints are still rigid (so that a
  // one-frame dqs-scale batch really has T = 5).
  for (size_t f = 0; f < batch; ++f) times[f] = 0.25 + 1.5 * double(f) / double(batch);
  size_t sink_bytes = 0;
  auto sink = [&](const DeformedBatch& b) { sink_bytes += b.primitives[0].positions.size(); };
  gpu.run(&asset.clips[0], times, sink);  // warm-up

  const double fps = frames_per_second(min_seconds, [&] {
    gpu.run(&asset.clips[0], times, sink);
    return batch;
  });
  BenchMeasurement m;
  m.path = "gpu";
  m.backend = ctx.info().backend;
  m.vertices = vertices;
  m.frames_requested = frames_per_batch;
  m.frames_per_batch = batch;
  m.readback = readback;
  m.vertex_frames_per_second = double(vertices) * fps;
  return m;
}

// The fast CPU deformer through the Deformer interface, 64 frames a run, every output handed to a sink
// that keeps nothing (so the outputs are written to memory, as readback included on the GPU).
BenchMeasurement measure_fast_cpu(const Asset& asset, BlendMode mode, unsigned threads, double min_seconds) {
  DeformerOptions options;
  options.mode = mode;
  options.backend = Backend::kFastCpu;
  options.threads = threads;
  const std::unique_ptr<Deformer> fast = make_deformer(nullptr, asset, mesh_instances(asset, 0), options);
  const size_t vertices = asset.meshes[0].primitives[0].vertex_count();
  std::vector<double> times(64);
  for (size_t f = 0; f < times.size(); ++f) times[f] = 0.25 + 1.5 * double(f) / double(times.size());
  size_t sink_bytes = 0;
  auto sink = [&](const DeformedBatch& b) { sink_bytes += b.primitives[0].positions.size(); };
  fast->run(&asset.clips[0], times, sink);  // warm-up: first touch of the output pages
  const double fps = frames_per_second(min_seconds, [&] {
    fast->run(&asset.clips[0], times, sink);
    return times.size();
  });
  BenchMeasurement m;
  m.path = "fast";
  m.backend = describe(DeformPath::kFastCpu);
  m.vertices = vertices;
  m.frames_requested = times.size();
  m.frames_per_batch = fast->frames_per_batch();
  m.threads = threads;
  m.readback = true;
  m.vertex_frames_per_second = double(vertices) * fps;
  return m;
}

// The bound: kBenchBytesPerVertexFrame moved per vertex-frame by memcpy on `threads` threads, each copying its
// own slice. As in the fast CPU deformer, every frame reads the same source (the rest data, warm in cache
// when it fits) and writes a region of its own, in batches of the deformer's `frames_per_batch`, three
// batch buffers in turn: the same memory the deformer's outputs go through.
BenchMeasurement measure_memcpy(size_t vertices, unsigned threads, size_t frames_per_batch, double min_seconds) {
  const size_t bytes = vertices * size_t(kBenchBytesPerVertexFrame) / 2;
  std::vector<unsigned char> from(bytes, 1), to(3 * frames_per_batch * bytes, 0);
  const size_t slice = (bytes + threads - 1) / threads;
  size_t batch = 0;
  auto copy_batch = [&] {
    unsigned char* buffer = to.data() + (batch++ % 3) * frames_per_batch * bytes;
    auto copy_slice = [&](unsigned t) {
      const size_t begin = std::min(bytes, t * slice), end = std::min(bytes, begin + slice);
      for (size_t f = 0; f < frames_per_batch; ++f) std::memcpy(buffer + f * bytes + begin, from.data() + begin, end - begin);
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(copy_slice, t);
    copy_slice(0);
    for (std::thread& t : pool) t.join();
  };
  for (int i = 0; i < 3; ++i) copy_batch();  // warm-up: first touch of every buffer's pages
  const double fps = frames_per_second(min_seconds, [&] {
    copy_batch();
    return frames_per_batch;
  });
  BenchMeasurement m;
  m.path = "copy";
  m.backend = "memcpy";
  m.vertices = vertices;
  m.frames_requested = m.frames_per_batch = frames_per_batch;
  m.threads = threads;
  m.readback = true;
  m.vertex_frames_per_second = double(vertices) * fps;
  return m;
}

BenchMeasurement measure_cpu(const Asset& asset, BlendMode mode, int threads, double min_seconds) {
  const std::vector<MeshInstance> instances = mesh_instances(asset, 0);
  const size_t vertices = asset.meshes[0].primitives[0].vertex_count();
  size_t step = 0;
  const double fps = frames_per_second(min_seconds, [&] {
    const Pose pose = sample_pose(asset, &asset.clips[0], 0.1 * double(step++ % 20));
    return deform_frame(asset, instances, pose, mode, threads).primitives.empty() ? 0u : 1u;
  });
  BenchMeasurement m;
  m.path = "cpu";
  m.backend = "cpu-double";
  m.vertices = vertices;
  m.frames_per_batch = 1;
  m.threads = size_t(threads);
  m.readback = true;
  m.vertex_frames_per_second = double(vertices) * fps;
  return m;
}

}  // namespace dqskin::bench_detail
