#include "surface_error.hpp"

#include "channel_reduction.hpp"

#include "dqskin/deformed_batch.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <thread>

namespace dqskin::optimize_detail {
namespace {

constexpr size_t kTimesPerChunk = 32;  // the reference's frames held at once
constexpr size_t kBins = 4096;         // the p99's histogram

// Which instance and primitive each of a batch's primitives is (instances in order, primitives in mesh order).
std::vector<std::pair<size_t, size_t>> primitive_owners(const Asset& asset, const std::vector<MeshInstance>& instances) {
  std::vector<std::pair<size_t, size_t>> owners;
  for (size_t i = 0; i < instances.size(); ++i)
    for (size_t p = 0; p < asset.meshes[size_t(instances[i].mesh)].primitives.size(); ++p) owners.emplace_back(i, p);
  return owners;
}

// The distances of one batch's vertices to the held reference, split over threads: each takes a
// contiguous share of the batch's (primitive, vertex-time) pairs with its own histogram and max; the shares
// merge in order, a later one winning only with a strictly larger distance, so the max found (and where)
// is the one a single pass in order finds.
struct Worst {
  double d = 0;
  size_t primitive = 0, index = 0;  // index: frame-major vertex-time within the primitive
};

void compare_batch(const DeformedBatch& batch, const std::vector<std::vector<float>>& held, double range,
                   unsigned threads, std::vector<uint64_t>& histogram, Worst& worst) {
  std::vector<size_t> begin(batch.primitives.size() + 1, 0);  // flat index of each primitive's first pair
  for (size_t k = 0; k < batch.primitives.size(); ++k)
    begin[k + 1] = begin[k] + batch.frame_count * batch.primitives[k].vertices;
  const size_t total = begin.back();
  const size_t workers = std::clamp<size_t>(threads, 1, std::max<size_t>(1, total / 65536));
  std::vector<std::vector<uint64_t>> histograms(workers, std::vector<uint64_t>(histogram.size(), 0));
  std::vector<Worst> worsts(workers);
  auto work = [&](size_t w) {
    const size_t from = total * w / workers, to = total * (w + 1) / workers;
    Worst& m = worsts[w];
    std::vector<uint64_t>& h = histograms[w];
    const size_t bins = h.size() - 1;
    for (size_t k = size_t(std::upper_bound(begin.begin(), begin.end(), from) - begin.begin()) - 1;
         k < batch.primitives.size() && begin[k] < to; ++k) {
      const DeformedBatch::Primitive& p = batch.primitives[k];
      const float* r = held[k].data() + batch.first_frame * p.vertices * 3;
      const size_t first = std::max(from, begin[k]) - begin[k], last = std::min(to, begin[k + 1]) - begin[k];
      for (size_t i = first; i < last; ++i) {
        const double dx = double(p.positions[3 * i]) - double(r[3 * i]);
        const double dy = double(p.positions[3 * i + 1]) - double(r[3 * i + 1]);
        const double dz = double(p.positions[3 * i + 2]) - double(r[3 * i + 2]);
        const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
        ++h[std::min(bins, size_t(d / range * double(bins)))];
        if (d > m.d) m = {d, k, i};
      }
    }
  };
  std::vector<std::thread> pool;
  for (size_t w = 1; w < workers; ++w) pool.emplace_back(work, w);
  work(0);
  for (std::thread& t : pool) t.join();
  for (size_t w = 0; w < workers; ++w) {
    for (size_t b = 0; b < histogram.size(); ++b) histogram[b] += histograms[w][b];
    if (worsts[w].d > worst.d) worst = worsts[w];
  }
}

}  // namespace

std::vector<double> judged_times(const Clip& clip) {
  std::set<float> keys;
  for (const Channel& c : clip.channels) {
    keys.insert(c.times.begin(), c.times.end());
    if (c.interpolation != Interpolation::kCubicSpline) continue;
    const std::vector<float> samples = cubic_sample_times(c);  // where a linear equivalent may put its keys
    keys.insert(samples.begin(), samples.end());
  }
  std::vector<double> times;
  double previous = 0;
  bool first = true;
  for (float t : keys) {
    if (!first) times.push_back((previous + double(t)) / 2);
    times.push_back(double(t));
    previous = double(t);
    first = false;
  }
  if (times.empty()) times.push_back(0.0);
  return times;
}

SurfaceError surface_error(const Asset& asset, const Clip& reference, const Asset& candidate_asset,
                           const Clip& candidate, const std::vector<MeshInstance>& instances,
                           const std::vector<double>& times, double scale, BlendMode mode, Backend backend,
                           unsigned threads, double stop_above, double look_first) {
  DeformerOptions options;
  options.mode = mode;
  options.backend = backend;
  options.threads = threads;
  options.positions_only = true;  // the reference's normals and tangents would be a third of its time
  const std::unique_ptr<Deformer> a = make_deformer(nullptr, asset, instances, options);
  const std::unique_ptr<Deformer> b = make_deformer(nullptr, candidate_asset, instances, options);
  const auto owners = primitive_owners(asset, instances);
  const unsigned workers = threads ? threads : std::max(1u, std::thread::hardware_concurrency());

  SurfaceError e;
  e.samples = times.size();
  // The p99 from a histogram of [0, 2 × scale) in kBins bins and one bin above: to 1/2048 of the scale,
  // or the max when more than 1 % of the vertex-times are past twice the scale.
  const double range = scale > 0 ? 2 * scale : 1;
  std::vector<uint64_t> histogram(kBins + 1, 0);
  std::vector<std::vector<float>> held;  // per primitive: the chunk's reference frames, frame-major
  // Chunks in time order, the one holding look_first first.
  std::vector<size_t> order;
  for (size_t first = 0; first < times.size(); first += kTimesPerChunk) order.push_back(first);
  if (look_first >= 0) {
    const size_t at = size_t(std::lower_bound(times.begin(), times.end(), look_first) - times.begin());
    const auto chunk = std::find(order.begin(), order.end(), std::min(at, times.size() - 1) / kTimesPerChunk * kTimesPerChunk);
    if (chunk != order.end()) std::rotate(order.begin(), chunk, chunk + 1);
  }
  for (const size_t first : order) {
    if (e.max > stop_above) break;
    const size_t count = std::min(kTimesPerChunk, times.size() - first);
    const std::span<const double> chunk(times.data() + first, count);
    held.assign(owners.size(), {});
    a->run(&reference, chunk, [&](const DeformedBatch& batch) {
      for (size_t k = 0; k < batch.primitives.size(); ++k) {
        const DeformedBatch::Primitive& p = batch.primitives[k];
        std::vector<float>& h = held[k];
        h.resize(count * p.vertices * 3);
        std::copy(p.positions.begin(), p.positions.end(), h.begin() + std::ptrdiff_t(batch.first_frame * p.vertices * 3));
      }
    });
    b->run(&candidate, chunk, [&](const DeformedBatch& batch) {
      Worst worst{e.max, 0, 0};
      compare_batch(batch, held, range, workers, histogram, worst);
      if (worst.d > e.max) {
        const size_t vertices = batch.primitives[worst.primitive].vertices;
        e.max = worst.d;
        e.max_time = chunk[batch.first_frame + worst.index / vertices];
        e.max_instance = owners[worst.primitive].first;
        e.max_primitive = owners[worst.primitive].second;
        e.max_vertex = worst.index % vertices;
      }
    });
  }
  uint64_t total = 0;
  for (uint64_t n : histogram) total += n;
  const uint64_t wanted = total - total / 100;  // 99 % of the vertex-times are at or below the p99
  uint64_t seen = 0;
  e.p99 = e.max;
  for (size_t bin = 0; bin < kBins; ++bin) {
    seen += histogram[bin];
    if (seen >= wanted) {
      e.p99 = std::min(e.max, range * double(bin + 1) / double(kBins));
      break;
    }
  }
  return e;
}

std::string vertex_joint(const Asset& asset, const std::vector<MeshInstance>& instances, size_t instance,
                         size_t primitive, size_t vertex) {
  if (instance >= instances.size()) return "";
  const MeshInstance& in = instances[instance];
  const Primitive& p = asset.meshes[size_t(in.mesh)].primitives[primitive];
  int node = in.node;
  if (in.skin >= 0 && p.influences > 0) {
    const size_t n = size_t(p.influences);
    size_t best = 0;
    for (size_t k = 1; k < n; ++k)
      if (p.weights[vertex * n + k] > p.weights[vertex * n + best]) best = k;
    node = asset.skins[size_t(in.skin)].joints[p.joints[vertex * n + best]];
  }
  const std::string& name = asset.nodes[size_t(node)].name;
  return name.empty() ? "node " + std::to_string(node) : name;
}

}  // namespace dqskin::optimize_detail
