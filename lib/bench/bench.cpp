// The bench's plan: every size × mode × path, measured one after the other on one GL context (the CPU rows
// too, so that a run with no context measures nothing rather than half the table).
#include "dqskin/bench.hpp"

#include "dqskin/error.hpp"
#include "measure.hpp"
#include "synthetic_asset.hpp"

#include <algorithm>
#include <thread>
#include <utility>

namespace dqskin {

using namespace bench_detail;

std::vector<BenchRatios> bench_ratios(const std::vector<BenchMeasurement>& measurements, unsigned cores) {
  // Sizes and modes in the order they were measured.
  std::vector<std::pair<size_t, std::string>> cases;
  for (const BenchMeasurement& m : measurements)
    if (std::find(cases.begin(), cases.end(), std::pair(m.vertices, m.mode)) == cases.end())
      cases.emplace_back(m.vertices, m.mode);
  std::vector<BenchRatios> ratios;
  for (const auto& [vertices, mode] : cases) {
    double fast = 0, bound = 0, gpu = 0, fast_lbs = 0;
    for (const BenchMeasurement& m : measurements) {
      if (m.vertices != vertices) continue;
      const bool all_cores = m.threads == cores;
      if (m.path == "fast" && all_cores && m.mode == "lbs") fast_lbs = m.vertex_frames_per_second;
      if (m.mode != mode) continue;
      if (m.path == "fast" && all_cores) fast = m.vertex_frames_per_second;
      if (m.path == "copy") bound = m.vertex_frames_per_second;
      if (m.path == "gpu") gpu = std::max(gpu, m.vertex_frames_per_second);
    }
    ratios.push_back({mode, vertices, fast, fast / bound, fast / gpu, fast_lbs / fast});
  }
  return ratios;
}

BenchReport bench(const BenchOptions& options, const BenchProgress& progress) {
  if (options.backend == Backend::kCpu || options.backend == Backend::kFastCpu)
    throw InputError("bench measures the CPU deformers anyway; its backend is the GL context of the GPU rows: auto, egl or osmesa");
  const std::unique_ptr<GpuContext> ctx = create_gpu_context(options.backend);
  BenchReport report;
  report.gpu = ctx->info();
  report.cores = std::max(1u, std::thread::hardware_concurrency());
  if (progress.started) progress.started(report.gpu);

  const std::vector<size_t> sizes = options.quick ? std::vector<size_t>{10000, 100000}
                                                  : std::vector<size_t>{10000, 100000, 1000000};
  const std::vector<size_t> batches = options.quick ? std::vector<size_t>{1, 64} : std::vector<size_t>{1, 64, 256};
  const double min_seconds = options.quick ? 0.15 : 0.5;
  struct ModeCase {
    const char* name;
    BlendMode mode;
    bool scale;
  };
  const ModeCase modes[] = {{"lbs", BlendMode::kLbs, false}, {"dqs", BlendMode::kDqs, false}, {"dqs-scale", BlendMode::kDqs, true}};
  const unsigned cores = report.cores;
  for (size_t vertices : sizes) {
    for (const ModeCase& mc : modes) {
      const Asset asset = make_synthetic_asset(vertices, 32, mc.scale);
      auto add = [&](BenchMeasurement m) {
        m.mode = mc.name;
        report.measurements.push_back(m);
        if (progress.measured) progress.measured(report.measurements.back());
        return m;
      };
      for (size_t fpb : batches)
        for (bool readback : {false, true})
          add(measure_gpu(*ctx, asset, mc.mode, fpb, readback, options.gpu_memory, min_seconds));
      size_t fast_batch = 0;
      for (unsigned threads : {1u, cores}) fast_batch = add(measure_fast_cpu(asset, mc.mode, threads, min_seconds)).frames_per_batch;
      for (int threads : {1, 2}) add(measure_cpu(asset, mc.mode, threads, min_seconds));
      add(measure_memcpy(vertices, cores, fast_batch, min_seconds));
    }
  }
  report.ratios = bench_ratios(report.measurements, cores);
  return report;
}

}  // namespace dqskin
