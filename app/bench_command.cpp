// `dqskin bench`: vertex-frames per second of every deformation path side by side, on synthetic
// characters of 10k, 100k and 1M vertices: lbs, dqs and dqs with scale (T = 5), on the GPU path (1, 64
// and 256 frames per batch, readback excluded and included) and on the CPU reference (1 and 2 threads).
#include "commands.hpp"
#include "console.hpp"
#include "exit_codes.hpp"
#include "synthetic_asset.hpp"

#include "dqskin/gpu_deform.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>

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

  size_t frames = 0;
  const Clock::time_point start = Clock::now();
  double elapsed = 0;
  do {
    gpu.run(&asset.clips[0], times, sink);
    frames += batch;
    elapsed = seconds_since(start);
  } while (elapsed < min_seconds);
  Measurement m;
  m.path = "gpu";
  m.backend = ctx.info().backend;
  m.vertices = vertices;
  m.frames_requested = frames_per_batch;
  m.frames_per_batch = batch;
  m.readback = readback;
  m.vertex_frames_per_second = double(vertices) * double(frames) / elapsed;
  return m;
}

Measurement measure_cpu(const Asset& asset, BlendMode mode, int threads, double min_seconds) {
  const std::vector<MeshInstance> instances = mesh_instances(asset, 0);
  const size_t vertices = asset.meshes[0].primitives[0].vertex_count();
  size_t frames = 0;
  const Clock::time_point start = Clock::now();
  double elapsed = 0;
  do {
    const Pose pose = sample_pose(asset, &asset.clips[0], 0.1 * double(frames % 20));
    const DeformedFrame frame = deform_frame(asset, instances, pose, mode, threads);
    frames += frame.primitives.empty() ? 0u : 1u;
    elapsed = seconds_since(start);
  } while (elapsed < min_seconds);
  Measurement m;
  m.path = "cpu";
  m.backend = "cpu-double";
  m.vertices = vertices;
  m.frames_per_batch = 1;
  m.threads = size_t(threads);
  m.readback = true;
  m.vertex_frames_per_second = double(vertices) * double(frames) / elapsed;
  return m;
}

void print_row(const Measurement& m) {
  // "64" when the batch ran as asked; "256→83" when GPU limits (one SSBO binding, the memory budget)
  // allowed fewer frames per batch.
  const std::string frames = m.frames_requested == m.frames_per_batch
                                 ? std::to_string(m.frames_per_batch)
                                 : std::to_string(m.frames_requested) + "->" + std::to_string(m.frames_per_batch);
  std::printf("%-10s %-4s %-16s %9zu %8s %8s %14.3e %8.2f\n", m.mode.c_str(), m.path.c_str(),
              (m.path == "cpu" ? std::to_string(m.threads) + " thread" + (m.threads > 1 ? "s" : "") : m.backend).c_str(),
              m.vertices, frames.c_str(), m.readback ? "yes" : "no", m.vertex_frames_per_second,
              m.vertex_frames_per_second * kBytesPerVertexFrame / 1e9);
  std::fflush(stdout);
}

// Measures vertex-frames per second of every deformation path. Returns an ExitCode.
int run_bench(const BenchSettings& settings) {
  Backend backend = Backend::kAuto;
  if (!parse_backend(settings.backend, backend) || backend == Backend::kCpu) {  // bench measures the reference anyway
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
  std::vector<Measurement> all;
  for (size_t vertices : sizes) {
    for (const ModeCase& mc : modes) {
      const Asset asset = make_synthetic_asset(vertices, 32, mc.scale);
      std::vector<Measurement> rows;
      for (size_t fpb : batches)
        for (bool readback : {false, true})
          rows.push_back(measure_gpu(*ctx, asset, mc.mode, fpb, readback, budget, min_seconds));
      for (int threads : {1, 2}) rows.push_back(measure_cpu(asset, mc.mode, threads, min_seconds));
      for (Measurement& m : rows) {
        m.mode = mc.name;
        if (!settings.json) print_row(m);
        all.push_back(m);
      }
    }
  }

  if (settings.json) {
    nlohmann::ordered_json out;
    out["backend"] = ctx->info().backend;
    out["gl_version"] = ctx->info().version;
    out["renderer"] = ctx->info().renderer;
    out["bytes_per_vertex_frame"] = kBytesPerVertexFrame;
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
      "bench", "Measure vertex-frames per second of lbs, dqs and dqs with scale on the GPU path and the CPU "
               "reference, for synthetic characters of 10k, 100k and 1M vertices");
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
