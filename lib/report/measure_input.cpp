#include "measure_input.hpp"

#include "closed_volume.hpp"
#include "joint_metrics.hpp"
#include "verdict.hpp"
#include "../base/parallel_for.hpp"

#include "dqskin/deformer.hpp"
#include "dqskin/error.hpp"
#include "../base/sha256.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <thread>

namespace dqskin::report_detail {
namespace {

// Frames deformed per Deformer::run: the three blends of a chunk are kept while it is measured, so the
// memory a clip needs does not grow with its length. At most 32 frames, and fewer for large meshes, so that
// a chunk's deformed frames (positions and normals in double, three blends) take at most 256 MiB: 32
// frames of a million vertices took 4.4 GiB and the report of a 1M-vertex character passed the 2 GiB
// default of --max-memory. The figures do not depend on the chunk.
constexpr size_t kMaxFramesPerChunk = 32;
constexpr size_t kChunkBytes = size_t(256) << 20;

size_t frames_per_chunk(size_t vertices) {
  const size_t frame_bytes = 3 * std::max<size_t>(vertices, 1) * 6 * sizeof(double);
  return std::clamp<size_t>(kChunkBytes / frame_bytes, 1, kMaxFramesPerChunk);
}

// The blends the report compares, each on the double-precision CPU reference: dib has no other path,
// and lbs and dqs run there too so that every difference measured is the blends', not float rounding's
// (docs/commands/report.md); with options.fast_cpu lbs and dqs run on the fast float deformer.
constexpr BlendMode kModes[3] = {BlendMode::kLbs, BlendMode::kDqs, BlendMode::kDib};

class Blends {
public:
  Blends(const InputPlan& input, bool fast_cpu, const std::atomic<bool>* cancel) {
    for (size_t m = 0; m < 3; ++m) {
      DeformerOptions o;
      o.mode = kModes[m];
      o.backend = fast_cpu && kModes[m] != BlendMode::kDib ? Backend::kFastCpu : Backend::kCpu;
      o.before_batch = [cancel] { check_cancelled(cancel); };
      deformers_[m] = make_deformer(nullptr, *input.asset, input.instances, o);
    }
  }
  // The three blends' batches of `times`.
  std::array<std::vector<DeformedBatch>, 3> deform(const Clip* clip, std::span<const double> times) {
    std::array<std::vector<DeformedBatch>, 3> out;
    for (size_t m = 0; m < 3; ++m)
      deformers_[m]->run(clip, times, [&out, m](const DeformedBatch& b) { out[m].push_back(b); });
    return out;
  }

private:
  std::array<std::unique_ptr<Deformer>, 3> deformers_;
};

FrameView view_at(const std::vector<DeformedBatch>& batches, size_t frame) {
  for (const DeformedBatch& b : batches)
    if (frame >= b.first_frame && frame < b.first_frame + b.frame_count) return frame_view(b, frame - b.first_frame);
  throw std::logic_error("a deformer skipped a frame");
}

double diagonal_of(const FrameView& frame) {
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const PrimitiveView& p : frame.primitives)
    for (size_t v = 0; v < p.vertices; ++v) {
      const glm::dvec3 x(p.positions[3 * v], p.positions[3 * v + 1], p.positions[3 * v + 2]);
      lo = glm::min(lo, x), hi = glm::max(hi, x);
    }
  return lo.x <= hi.x ? glm::distance(lo, hi) : 0.0;
}

std::string node_name(const Asset& asset, int node) {
  std::string name = asset.nodes[size_t(node)].name;
  if (name.empty()) {
    name = "node ";
    name += std::to_string(node);
  }
  return name;
}

}  // namespace

InputData measure_input(const InputPlan& input, const ReportOptions& options, ProgressCounter& progress) {
  const Asset& asset = *input.asset;
  InputData data;
  data.regions = std::make_unique<const SkinRegions>(skin_regions(asset, input.instances));
  const SkinRegions& regions = *data.regions;
  data.file = std::filesystem::path(input.path).filename().string();
  data.sha256 = sha256_file(input.path);
  data.vertices = regions.vertices;
  data.skinned_vertices = regions.skinned_vertices;
  data.skins = input.skins.size();
  data.max_influences = regions.max_influences;
  if (regions.joints.empty()) throw InputError("no skinned mesh in the scene: nothing to report");
  Blends blends(input, options.fast_cpu, options.cancel);

  // The rest pose: the reference of the area and volume ratios, and the diagonal.
  const double rest_time[1] = {0.0};
  const auto rest = blends.deform(nullptr, rest_time);
  const FrameView rest_view = view_at(rest[2], 0);
  data.diagonal = diagonal_of(rest_view);
  const std::vector<JointTransforms> rest_joints = JointMetrics::skin_transforms(asset, regions, sample_pose(asset, nullptr, 0));
  const JointMetrics metrics(asset, regions, rest_view, rest_joints);
  const std::vector<BatchTriangle> closed = closed_triangles(asset, input.instances, regions);
  const double rest_volume = closed.empty() ? 0.0 : signed_volume(closed, rest_view);
  const bool has_volume = std::abs(rest_volume) > 1e-12 * std::pow(data.diagonal, 3);

  data.joints.resize(regions.joints.size());
  for (size_t r = 0; r < regions.joints.size(); ++r) {
    JointData& j = data.joints[r];
    j.region = &regions.joints[r];
    if (j.region->parent >= 0) j.parent_name = node_name(asset, asset.skins[size_t(j.region->skin)].joints[size_t(j.region->parent)]);
  }

  for (const ClipPlan& plan : input.clips) {
    ClipData& clip = data.clips.emplace_back();
    clip.name = plan.name;
    clip.fps = plan.fps;
    clip.times = plan.times;
    if (has_volume) clip.volume = ClipVolume{rest_volume, {}, {}, {}};
    for (JointData& j : data.joints) j.clips.emplace_back().reserve(plan.times.size());
    const size_t chunk = frames_per_chunk(data.vertices);
    for (size_t first = 0; first < plan.times.size(); first += chunk) {
      check_cancelled(options.cancel);
      const size_t count = std::min(chunk, plan.times.size() - first);
      const std::span<const double> times(plan.times.data() + first, count);
      const auto batches = blends.deform(plan.clip, times);
      std::vector<std::vector<JointFrame>> measured(count);
      std::vector<std::array<double, 3>> volumes(count);
      concurrency::parallel_for(count, std::max(1u, std::thread::hardware_concurrency()), [&](size_t k) {
        const FrameView lbs = view_at(batches[0], k), dqs = view_at(batches[1], k), dib = view_at(batches[2], k);
        const std::vector<JointTransforms> joints = JointMetrics::skin_transforms(asset, regions, sample_pose(asset, plan.clip, times[k]));
        measured[k] = metrics.measure({&lbs, &dqs, &dib, &joints});
        if (has_volume)
          volumes[k] = {signed_volume(closed, lbs) / rest_volume, signed_volume(closed, dqs) / rest_volume,
                        signed_volume(closed, dib) / rest_volume};
      });
      for (size_t k = 0; k < count; ++k) {
        double worst = 0;
        for (size_t r = 0; r < measured[k].size(); ++r) {
          data.joints[r].clips.back().push_back(measured[k][r]);
          worst = std::max(worst, measured[k][r].lbs_dib_max);
          clip.lbs_dqs_max = std::max(clip.lbs_dqs_max, measured[k][r].lbs_dqs_max);
        }
        clip.worst_lbs_dib.push_back(worst);
        if (has_volume) {
          clip.volume->lbs.push_back(volumes[k][0]);
          clip.volume->dqs.push_back(volumes[k][1]);
          clip.volume->dib.push_back(volumes[k][2]);
        }
      }
      progress.add(count, input.path, plan.name);
    }
  }

  for (JointData& j : data.joints) {
    j.summary = summarize(j.clips);
    j.verdict = joint_verdict(j, data.clips, options.thresholds, data.diagonal);
  }
  data.verdict = asset_verdict(data.joints);
  return data;
}

}  // namespace dqskin::report_detail
