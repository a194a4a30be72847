// `dqskin bench` as a library call: vertex-frames per second of every deformation path side by side, on
// synthetic characters of 10k, 100k and 1M vertices: lbs, dqs and dqs with scale (T = 5), on the GPU path
// (1, 64 and 256 frames per batch, readback excluded and included), the fast CPU deformer (1 thread and
// every core), the CPU reference (1 and 2 threads), and a memcpy of the same bytes on every core (the
// bound); then the fast CPU deformer beside the bound, the GPU path and lbs.
#pragma once

#include "dqskin/deformer.hpp"
#include "dqskin/gpu_context.hpp"

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace dqskin {

// Bytes one vertex-frame must move at least: reads position, normal (12 + 12), 4 packed joint indices and
// 4 weights (8 + 16); writes position and normal (12 + 12). Joint data comes from the bone texture, shared
// by all vertices, so it is not counted. GB/s figures are vertex-frames per second times this.
inline constexpr double kBenchBytesPerVertexFrame = 72;

struct BenchOptions {
  Backend backend = Backend::kAuto;        // the GL context of the GPU rows: auto, egl or osmesa
  size_t gpu_memory = size_t(512) << 20;   // GPU output buffer budget per batch, bytes
  bool quick = false;  // a run under a minute: 10k and 100k vertices, 1 and 64 frames per batch, shorter timing
};

// One row: a mode on one path at one size.
struct BenchMeasurement {
  std::string mode;     // lbs, dqs, dqs-scale
  std::string path;     // gpu, fast (the fast CPU deformer), cpu (the double reference), copy (memcpy)
  std::string backend;  // the GL backend, describe(DeformPath::kFastCpu), "cpu-double" or "memcpy"
  size_t vertices = 0;
  size_t frames_requested = 1, frames_per_batch = 0;  // fewer per batch than requested: GPU limits allowed no more
  size_t threads = 0;   // CPU paths; 0 on the GPU
  bool readback = false;
  double vertex_frames_per_second = 0;
};

// The fast CPU deformer on every core at one mode and size, beside the others.
struct BenchRatios {
  std::string mode;
  size_t vertices = 0;
  double fast = 0;      // its vertex-frames per second
  double of_bound = 0;  // share of the memcpy bound
  double over_gpu = 0;  // times the GPU path's best row (readback excluded: the strictest comparison)
  double over_lbs = 0;  // this mode's time per vertex-frame over lbs's
};

struct BenchReport {
  GpuContextInfo gpu;   // the context of the GPU rows
  unsigned cores = 1;   // threads of the "every core" rows
  std::vector<BenchMeasurement> measurements;  // in the order measured: size, mode, then path
  std::vector<BenchRatios> ratios;             // per size and mode
};

// Called as the bench goes, on the calling thread: once the context is made, before the first measurement,
// and after each measurement (a run takes minutes; a caller prints the rows as they come).
struct BenchProgress {
  std::function<void(const GpuContextInfo&)> started;
  std::function<void(const BenchMeasurement&)> measured;
};

// Measures every path. Throws NoGpuContext when no context of options.backend can be made, InputError for
// a backend that is not a GL one (cpu, fast-cpu: the CPU deformers are measured anyway).
BenchReport bench(const BenchOptions& options, const BenchProgress& progress = {});

// The ratios of BenchReport from its measurements: per size and mode, the fast CPU row on `cores` threads
// beside the memcpy row, the best GPU row and the fast CPU lbs row of that size. A figure whose row is
// missing divides by zero (inf or nan), as a bench that could not measure it shows.
std::vector<BenchRatios> bench_ratios(const std::vector<BenchMeasurement>& measurements, unsigned cores);

}  // namespace dqskin
