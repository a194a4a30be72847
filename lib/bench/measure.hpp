// One measurement of dqskin bench per path: each runs its deformer (or memcpy) until at least
// `min_seconds` have passed, after a warm-up, and returns vertex-frames per second (mode left for the caller).
#pragma once

#include "dqskin/asset.hpp"
#include "dqskin/bench.hpp"
#include "dqskin/gpu_context.hpp"
#include "dqskin/skinning.hpp"

#include <cstddef>

namespace dqskin::bench_detail {

// The GPU path: whole batches of `frames_per_batch` frames (fewer when GPU limits or `memory_budget` allow
// no more), with or without reading the outputs back.
BenchMeasurement measure_gpu(GpuContext& ctx, const Asset& asset, BlendMode mode, size_t frames_per_batch,
                             bool readback, size_t memory_budget, double min_seconds);

// The fast CPU deformer through the Deformer interface, 64 frames a run on `threads` threads.
BenchMeasurement measure_fast_cpu(const Asset& asset, BlendMode mode, unsigned threads, double min_seconds);

// The double-precision CPU reference, one frame at a time on `threads` threads.
BenchMeasurement measure_cpu(const Asset& asset, BlendMode mode, int threads, double min_seconds);

// The bound: kBenchBytesPerVertexFrame moved per vertex-frame by memcpy on `threads` threads, in batches of
// `frames_per_batch` frames.
BenchMeasurement measure_memcpy(size_t vertices, unsigned threads, size_t frames_per_batch, double min_seconds);

}  // namespace dqskin::bench_detail
