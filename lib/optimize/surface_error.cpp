#include "surface_error.hpp"

#include "channel_reduction.hpp"

#include "dqskin/deformed_batch.hpp"

#include <algorithm>
#include <cmath>
#include <set>

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
                           unsigned threads) {
  DeformerOptions options;
  options.mode = mode;
  options.backend = backend;
  options.threads = threads;
  const std::unique_ptr<Deformer> a = make_deformer(nullptr, asset, instances, options);
  const std::unique_ptr<Deformer> b = make_deformer(nullptr, candidate_asset, instances, options);
  const auto owners = primitive_owners(asset, instances);

  SurfaceError e;
  e.samples = times.size();
  // The p99 from a histogram of [0, 2 × scale) in kBins bins and one bin above: to 1/2048 of the scale,
  // or the max when more than 1 % of the vertex-times are past twice the scale.
  const double range = scale > 0 ? 2 * scale : 1;
  std::vector<uint64_t> histogram(kBins + 1, 0);
  std::vector<std::vector<float>> held;  // per primitive: the chunk's reference frames, frame-major
  for (size_t first = 0; first < times.size(); first += kTimesPerChunk) {
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
      for (size_t k = 0; k < batch.primitives.size(); ++k) {
        const DeformedBatch::Primitive& p = batch.primitives[k];
        const float* r = held[k].data() + batch.first_frame * p.vertices * 3;
        for (size_t i = 0; i < batch.frame_count * p.vertices; ++i) {
          const double dx = double(p.positions[3 * i]) - double(r[3 * i]);
          const double dy = double(p.positions[3 * i + 1]) - double(r[3 * i + 1]);
          const double dz = double(p.positions[3 * i + 2]) - double(r[3 * i + 2]);
          const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
          ++histogram[std::min(kBins, size_t(d / range * double(kBins)))];
          if (d > e.max) {
            e.max = d;
            e.max_time = chunk[batch.first_frame + i / p.vertices];
            e.max_instance = owners[k].first;
            e.max_primitive = owners[k].second;
            e.max_vertex = i % p.vertices;
          }
        }
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
