// `dqskin bench`: the flags of dqskin/bench.hpp's bench() and its tables (or one JSON document) on standard
// output, each row printed as it is measured.
#include "commands.hpp"
#include "console.hpp"
#include "exit_codes.hpp"

#include "dqskin/bench.hpp"

#include <nlohmann/json.hpp>

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

void print_row(const BenchMeasurement& m) {
  // "64" when the batch ran as asked; "256→83" when GPU limits (one SSBO binding, the memory budget)
  // allowed fewer frames per batch.
  const std::string frames = m.frames_requested == m.frames_per_batch
                                 ? std::to_string(m.frames_per_batch)
                                 : std::to_string(m.frames_requested) + "->" + std::to_string(m.frames_per_batch);
  const bool threaded = m.path != "gpu";
  std::printf("%-10s %-4s %-16s %9zu %8s %8s %14.3e %8.2f\n", m.mode.c_str(), m.path.c_str(),
              (threaded ? std::to_string(m.threads) + " thread" + (m.threads > 1 ? "s" : "") : m.backend).c_str(),
              m.vertices, frames.c_str(), m.readback ? "yes" : "no", m.vertex_frames_per_second,
              m.vertex_frames_per_second * kBenchBytesPerVertexFrame / 1e9);
  std::fflush(stdout);
}

void print_header(const GpuContextInfo& gpu) {
  std::printf("dqskin bench: %s, OpenGL %s, %s\n", gpu.backend.c_str(), gpu.version.c_str(), gpu.renderer.c_str());
  std::printf("GB/s counts %.0f bytes per vertex-frame (float inputs and outputs, 4 influences).\n\n",
              kBenchBytesPerVertexFrame);
  std::printf("%-10s %-4s %-16s %9s %8s %8s %14s %8s\n", "mode", "path", "backend", "vertices", "frames", "readback",
              "vertex-frames/s", "GB/s");
}

void print_ratios(const BenchReport& r) {
  std::printf("\nfast CPU on %u thread%s: share of the memcpy bound, times the GPU path's best (%s), and this mode's "
              "time over lbs's\n",
              r.cores, r.cores > 1 ? "s" : "", r.gpu.backend.c_str());
  std::printf("%-10s %9s %14s %9s %9s %9s\n", "mode", "vertices", "vertex-frames/s", "of bound", "x gpu", "time/lbs");
  for (const BenchRatios& x : r.ratios)
    std::printf("%-10s %9zu %14.3e %8.0f%% %9.2f %9.2f\n", x.mode.c_str(), x.vertices, x.fast, 100 * x.of_bound,
                x.over_gpu, x.over_lbs);
}

void print_json(const BenchReport& r) {
  nlohmann::ordered_json out;
  out["backend"] = r.gpu.backend;
  out["gl_version"] = r.gpu.version;
  out["renderer"] = r.gpu.renderer;
  out["bytes_per_vertex_frame"] = kBenchBytesPerVertexFrame;
  out["fast_cpu_ratios"] = nlohmann::ordered_json::array();
  for (const BenchRatios& x : r.ratios)
    out["fast_cpu_ratios"].push_back({{"mode", x.mode}, {"vertices", x.vertices}, {"vertex_frames_per_second", x.fast},
                                      {"share_of_memcpy_bound", x.of_bound}, {"times_gpu_path", x.over_gpu},
                                      {"time_over_lbs", x.over_lbs}});
  out["measurements"] = nlohmann::ordered_json::array();
  for (const BenchMeasurement& m : r.measurements)
    out["measurements"].push_back({{"mode", m.mode}, {"path", m.path}, {"backend", m.backend},
                                   {"threads", m.threads}, {"vertices", m.vertices},
                                   {"frames_per_batch_requested", m.frames_requested},
                                   {"frames_per_batch", m.frames_per_batch}, {"readback", m.readback},
                                   {"vertex_frames_per_second", m.vertex_frames_per_second},
                                   {"gb_per_second", m.vertex_frames_per_second * kBenchBytesPerVertexFrame / 1e9}});
  std::cout << json_text(out, 2) << '\n';
}

// Measures vertex-frames per second of every deformation path. Returns an ExitCode.
int run_bench(const BenchSettings& settings) {
  BenchOptions options;
  // The GL context of the GPU rows; bench measures the CPU deformers anyway.
  if (!parse_backend(settings.backend, options.backend) || options.backend == Backend::kCpu ||
      options.backend == Backend::kFastCpu) {
    print_error("--backend must be auto, egl or osmesa, not '" + settings.backend + "'");
    return kUsageOrInputError;
  }
  options.gpu_memory = settings.gpu_memory_mb << 20;
  options.quick = settings.quick;
  BenchProgress progress;
  if (!settings.json) progress.started = print_header, progress.measured = print_row;
  // No context: NoGpuContext reaches main's guarded_run, which prints it and returns kNoGlContext.
  const BenchReport report = bench(options, progress);
  if (settings.json) print_json(report);
  else print_ratios(report);
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
