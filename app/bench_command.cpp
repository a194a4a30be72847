// `dqskin bench`: vertex-frames per second of every deformation path side by side, on synthetic
// characters of 10k, 100k and 1M vertices: lbs, dqs and dqs with scale (T = 5), on the GPU path (1, 64
// and 256 frames per batch, readback excluded and included), the fast CPU deformer (1 thread and every
// core), the CPU reference (1 and 2 threads), and a memcpy of the same bytes on every core (the bound).
// A last table puts the fast CPU deformer beside the bound, the GPU path and lbs.
#include "commands.hpp"
#include "console.hpp"
#include "exit_codes.hpp"
#include "synthetic_asset.hpp"

#include "dqskin/deformer.hpp"
#include "dqskin/gpu_deform.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>
#include <memory>
#include <thread>

namespace dqskin::cli {
namespace {

struct BenchSettings {
  bool json = false;
  bool quick = false;
  std::string backend = "auto";
  size_t gpu_memory_mb = 512;
};

using Clock = std::chrono::steady_clock;

// Bytes one vertex-frame must move at least: reads position, normal (12 + 12), 4 packed joint
// indices and 4 weights (8 + 16); writes position and normal (12 + 12). Joint data comes from the
// bone texture, shared by all vertices, so it is not counted.
constexpr double kBytesPerVertexFrame = 72;

struct Measurement {
  std::string mode, path, backend;
  size_t vertices = 0, frames_requested = 1, frames_per_batch = 0, threads = 0;
  bool readback = false;
  double vertex_frames_per_second = 0;
};

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

// GPU: runs whole batches until at least `min_seconds` passed (after one warm-up batch, which also
// compiles the shader variant), and counts vertex-frames.
Measurement measure_gpu(GpuContext& ctx, const Asset& asset, BlendMode mode, size_t frames_per_batch, bool readback,
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
  Measurement m;
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
Measurement measure_fast_cpu(const Asset& asset, BlendMode mode, unsigned threads, double min_seconds) {
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
  Measurement m;
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

// The bound: kBytesPerVertexFrame moved per vertex-frame by memcpy on `threads` threads, each copying its
// own slice. As in the fast CPU deformer, every frame reads the same source (the rest data, warm in cache
// when it fits) and writes a region of its own, in batches of the deformer's `frames_per_batch`, three
// batch buffers in turn: the same memory the deformer's outputs go through.
Measurement measure_memcpy(size_t vertices, unsigned threads, size_t frames_per_batch, double min_seconds) {
  const size_t bytes = vertices * size_t(kBytesPerVertexFrame) / 2;
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
  Measurement m;
  m.path = "copy";
  m.backend = "memcpy";
  m.vertices = vertices;
  m.frames_requested = m.frames_per_batch = frames_per_batch;
  m.threads = threads;
  m.readback = true;
  m.vertex_frames_per_second = double(vertices) * fps;
  return m;
}

Measurement measure_cpu(const Asset& asset, BlendMode mode, int threads, double min_seconds) {
  const std::vector<MeshInstance> instances = mesh_instances(asset, 0);
  const size_t vertices = asset.meshes[0].primitives[0].vertex_count();
  size_t step = 0;
  const double fps = frames_per_second(min_seconds, [&] {
    const Pose pose = sample_pose(asset, &asset.clips[0], 0.1 * double(step++ % 20));
    return deform_frame(asset, instances, pose, mode, threads).primitives.empty() ? 0u : 1u;
  });
  Measurement m;
  m.path = "cpu";
  m.backend = "cpu-double";
  m.vertices = vertices;
  m.frames_per_batch = 1;
  m.threads = size_t(threads);
  m.readback = true;
  m.vertex_frames_per_second = double(vertices) * fps;
  return m;
}

void print_row(const Measurement& m) {
  // "64" when the batch ran as asked; "256→83" when GPU limits (one SSBO binding, the memory budget)
  // allowed fewer frames per batch.
  const std::string frames = m.frames_requested == m.frames_per_batch
                                 ? std::to_string(m.frames_per_batch)
                                 : std::to_string(m.frames_requested) + "->" + std::to_string(m.frames_per_batch);
  const bool threaded = m.path != "gpu";
  std::printf("%-10s %-4s %-16s %9zu %8s %8s %14.3e %8.2f\n", m.mode.c_str(), m.path.c_str(),
              (threaded ? std::to_string(m.threads) + " thread" + (m.threads > 1 ? "s" : "") : m.backend).c_str(),
              m.vertices, frames.c_str(), m.readback ? "yes" : "no", m.vertex_frames_per_second,
              m.vertex_frames_per_second * kBytesPerVertexFrame / 1e9);
  std::fflush(stdout);
}

// Measures vertex-frames per second of every deformation path. Returns an ExitCode.
int run_bench(const BenchSettings& settings) {
  Backend backend = Backend::kAuto;
  // The GL context of the GPU rows; bench measures the CPU deformers anyway.
  if (!parse_backend(settings.backend, backend) || backend == Backend::kCpu || backend == Backend::kFastCpu) {
    print_error("--backend must be auto, egl or osmesa, not '" + settings.backend + "'");
    return kUsageOrInputError;
  }
  std::unique_ptr<GpuContext> ctx;
  try {
    ctx = create_gpu_context(backend);
  } catch (const NoGpuContext& e) {
    print_error(e.what());
    return kNoGlContext;
  }

  const std::vector<size_t> sizes = settings.quick ? std::vector<size_t>{10000, 100000}
                                                   : std::vector<size_t>{10000, 100000, 1000000};
  const std::vector<size_t> batches = settings.quick ? std::vector<size_t>{1, 64} : std::vector<size_t>{1, 64, 256};
  const double min_seconds = settings.quick ? 0.15 : 0.5;
  const size_t budget = settings.gpu_memory_mb << 20;
  struct ModeCase {
    const char* name;
    BlendMode mode;
    bool scale;
  };
  const ModeCase modes[] = {{"lbs", BlendMode::kLbs, false}, {"dqs", BlendMode::kDqs, false}, {"dqs-scale", BlendMode::kDqs, true}};

  if (!settings.json) {
    std::printf("dqskin bench: %s, OpenGL %s, %s\n", ctx->info().backend.c_str(), ctx->info().version.c_str(),
                ctx->info().renderer.c_str());
    std::printf("GB/s counts %.0f bytes per vertex-frame (float inputs and outputs, 4 influences).\n\n",
                kBytesPerVertexFrame);
    std::printf("%-10s %-4s %-16s %9s %8s %8s %14s %8s\n", "mode", "path", "backend", "vertices", "frames", "readback",
                "vertex-frames/s", "GB/s");
  }
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  std::vector<Measurement> all;
  for (size_t vertices : sizes) {
    for (const ModeCase& mc : modes) {
      const Asset asset = make_synthetic_asset(vertices, 32, mc.scale);
      std::vector<Measurement> rows;
      for (size_t fpb : batches)
        for (bool readback : {false, true})
          rows.push_back(measure_gpu(*ctx, asset, mc.mode, fpb, readback, budget, min_seconds));
      for (unsigned threads : {1u, cores}) rows.push_back(measure_fast_cpu(asset, mc.mode, threads, min_seconds));
      const size_t fast_batch = rows.back().frames_per_batch;
      for (int threads : {1, 2}) rows.push_back(measure_cpu(asset, mc.mode, threads, min_seconds));
      rows.push_back(measure_memcpy(vertices, cores, fast_batch, min_seconds));
      for (Measurement& m : rows) {
        m.mode = mc.name;
        if (!settings.json) print_row(m);
        all.push_back(m);
      }
    }
  }

  // The fast CPU deformer on every core beside the bound, the GPU path's best row (readback excluded: the
  // strictest comparison) and lbs at the same size.
  struct Ratios {
    std::string mode;
    size_t vertices;
    double fast, of_bound, over_gpu, over_lbs;  // over_lbs: this mode's time per vertex-frame over lbs's
  };
  std::vector<Ratios> ratios;
  for (size_t vertices : sizes)
    for (const ModeCase& mc : modes) {
      double fast = 0, bound = 0, gpu = 0, fast_lbs = 0;
      for (const Measurement& m : all) {
        if (m.vertices != vertices) continue;
        const bool all_cores = m.threads == cores;
        if (m.path == "fast" && all_cores && m.mode == "lbs") fast_lbs = m.vertex_frames_per_second;
        if (m.mode != mc.name) continue;
        if (m.path == "fast" && all_cores) fast = m.vertex_frames_per_second;
        if (m.path == "copy") bound = m.vertex_frames_per_second;
        if (m.path == "gpu") gpu = std::max(gpu, m.vertex_frames_per_second);
      }
      ratios.push_back({mc.name, vertices, fast, fast / bound, fast / gpu, fast_lbs / fast});
    }
  if (!settings.json) {
    std::printf("\nfast CPU on %u thread%s: share of the memcpy bound, times the GPU path's best (%s), and this mode's "
                "time over lbs's\n",
                cores, cores > 1 ? "s" : "", ctx->info().backend.c_str());
    std::printf("%-10s %9s %14s %9s %9s %9s\n", "mode", "vertices", "vertex-frames/s", "of bound", "x gpu", "time/lbs");
    for (const Ratios& r : ratios)
      std::printf("%-10s %9zu %14.3e %8.0f%% %9.2f %9.2f\n", r.mode.c_str(), r.vertices, r.fast, 100 * r.of_bound,
                  r.over_gpu, r.over_lbs);
  }

  if (settings.json) {
    nlohmann::ordered_json out;
    out["backend"] = ctx->info().backend;
    out["gl_version"] = ctx->info().version;
    out["renderer"] = ctx->info().renderer;
    out["bytes_per_vertex_frame"] = kBytesPerVertexFrame;
    out["fast_cpu_ratios"] = nlohmann::ordered_json::array();
    for (const Ratios& r : ratios)
      out["fast_cpu_ratios"].push_back({{"mode", r.mode}, {"vertices", r.vertices}, {"vertex_frames_per_second", r.fast},
                                        {"share_of_memcpy_bound", r.of_bound}, {"times_gpu_path", r.over_gpu},
                                        {"time_over_lbs", r.over_lbs}});
    out["measurements"] = nlohmann::ordered_json::array();
    for (const Measurement& m : all)
      out["measurements"].push_back({{"mode", m.mode}, {"path", m.path}, {"backend", m.backend},
                                     {"threads", m.threads}, {"vertices", m.vertices},
                                     {"frames_per_batch_requested", m.frames_requested},
                                     {"frames_per_batch", m.frames_per_batch}, {"readback", m.readback},
                                     {"vertex_frames_per_second", m.vertex_frames_per_second},
                                     {"gb_per_second", m.vertex_frames_per_second * kBytesPerVertexFrame / 1e9}});
    std::cout << json_text(out, 2) << '\n';
  }
  return kSuccess;
}

}  // namespace

Command add_bench_command(CLI::App& app) {
  auto settings = std::make_shared<BenchSettings>();
  BenchSettings& bench = *settings;
  CLI::App* bench_cmd = app.add_subcommand(
      "bench", "Measure vertex-frames per second of lbs, dqs and dqs with scale on the GPU path, the fast CPU "
               "deformer, the CPU reference and a memcpy of the same bytes (the bound), for synthetic characters "
               "of 10k, 100k and 1M vertices");
  bench_cmd->add_flag("--json", bench.json, "Print one JSON document: one entry per measurement");
  bench_cmd->add_flag("--quick", bench.quick, "A run under a minute: 10k and 100k vertices, 1 and 64 frames per batch");
  bench_cmd->add_option("--backend", bench.backend, "Headless OpenGL backend: auto (EGL, then OSMesa), egl or osmesa")
      ->capture_default_str();
  bench_cmd->add_option("--gpu-memory", bench.gpu_memory_mb, "GPU output buffer budget per batch, in MiB")
      ->capture_default_str()
      ->check(CLI::Range(size_t(1), size_t(1) << 20));
  return {bench_cmd, [settings] { return run_bench(*settings); }};
}

}  // namespace dqskin::cli
