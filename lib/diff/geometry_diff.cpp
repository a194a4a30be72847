// `dqskin diff A.glb B.glb`: correspondence at the rest pose, then both files deformed chunk by chunk at
// the same times and every corresponding pair of surface points measured.
#include "dqskin/geometry_diff.hpp"

#include "clip_matching.hpp"
#include "correspondence.hpp"
#include "correspondence_pose.hpp"
#include "diff_numbers.hpp"
#include "diff_side.hpp"
#include "error_heat_map.hpp"
#include "frame_measure.hpp"
#include "normal_comparison.hpp"
#include "largest_errors.hpp"
#include "surface_correspondence.hpp"
#include "../base/parallel_for.hpp"
#include "../base/saturating.hpp"

#include "dqskin/animation.hpp"
#include "../base/byte_size.hpp"
#include "dqskin/error.hpp"
#include "dqskin/image_output.hpp"
#include "dqskin/job.hpp"
#include "../job/job_run.hpp"
#include "dqskin/memory_ceiling.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <limits>
#include <filesystem>
#include <functional>
#include <map>
#include <new>
#include <optional>
#include <thread>

namespace dqskin {

using diff_detail::Correspondence;
using diff_detail::DiffSide;
using diff_detail::FrameResult;
using diff_detail::at;
using diff_detail::measure;
using diff_detail::LargestErrors;
using diff_detail::SideFrame;
using diff_detail::SurfacePoint;

namespace {

constexpr float kInfF = std::numeric_limits<float>::infinity();


// Frames deformed and measured at once, at most.
constexpr uint64_t kMaxFramesAtOnce = 32;

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

struct Thresholds {
  double warn, fail, hard_warn, hard_fail;
};

Thresholds absolute(const DiffThresholds& t, bool relative, double diagonal) {
  const double k = relative ? diagonal : 1.0;
  return {t.warn * k, t.fail * k, t.hard_warn * k, t.hard_fail * k};
}

std::string length(double value) { return diff_detail::number(value); }

// Why a clip failed or warned, in words.
std::string verdict_reason(const ClipGeometryDiff& c, const DiffThresholds& t, const Thresholds& abs, bool relative) {
  const char* unit = relative ? " of the diagonal" : "";
  auto over = [&](uint64_t n, const char* flag, double value) {
    return std::to_string(n) + " samples (" + diff_detail::percent(n, c.samples) + ") over " + flag + " " +
           diff_detail::number(value) + unit;
  };
  if (!std::isfinite(c.max_error)) return "an error is not finite";
  if (c.status == DiffStatus::kFail) {
    if (c.max_error > abs.hard_fail) return "max " + length(c.max_error) + " over --hardfail " + diff_detail::number(t.hard_fail) + unit;
    return over(c.over_fail, "--fail", t.fail);
  }
  if (c.status == DiffStatus::kWarn) {
    if (c.max_error > abs.hard_warn) return "max " + length(c.max_error) + " over --hardwarn " + diff_detail::number(t.hard_warn) + unit;
    return over(c.over_warn, "--warn", t.warn);
  }
  return "";
}

class GeometryDiffer {
public:
  GeometryDiffer(DiffSide& a, DiffSide& b, const GeometryDiffOptions& options, GeometryDiffReport& report)
      : a_(a), b_(b), options_(options), report_(report),
        threads_(options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency())),
        context_(options.backend) {
    for (const std::string& name : a.joint_names) joint_index(name);
    for (const std::string& name : b.joint_names) joint_index(name);
    for (const std::string& name : a.joint_names) joint_a_.push_back(joint_index(name));
    for (const std::string& name : b.joint_names) joint_b_.push_back(joint_index(name));
    DeformerOptions d;
    d.mode = options.mode, d.backend = options.backend, d.threads = options.threads;
    d.before_batch = [cancel = options.cancel] { check_cancelled(cancel); };
    GpuContext* context = context_.for_deforming(options.mode);
    report.deformer = describe(deform_path(options.backend, options.mode, context));
    deform_a_ = make_deformer(context, a.asset, a.instances, d);
    deform_b_ = make_deformer(context, b.asset, b.instances, d);
  }

  // Makes the correspondence at the pose choose_correspondence_pose picks: the rest pose, or when it is
  // degenerate the first pair of clips both files have (of `pairs`) at its first compared time, or the
  // bind pose.
  void correspond(const std::vector<diff_detail::ClipPair>& pairs) {
    const auto start = Clock::now();
    const Clip* clip_a = nullptr;
    const Clip* clip_b = nullptr;
    std::string label;
    double time = 0;
    for (const diff_detail::ClipPair& pair : pairs)
      if (pair.a >= 0 && pair.b >= 0) {
        clip_a = &a_.asset.clips[size_t(pair.a)], clip_b = &b_.asset.clips[size_t(pair.b)];
        label = diff_detail::clip_label(a_.asset, pair.a);
        const std::vector<double> times = clip_times(clip_a, clip_b);
        if (!times.empty()) time = times.front();
        break;
      }
    const diff_detail::CorrespondencePose pose =
        diff_detail::choose_correspondence_pose(a_, b_, clip_a, clip_b, label, time, options_.mode);
    const diff_detail::PosedSurface& pa = pose.of_a(a_);
    const diff_detail::PosedSurface& pb = pose.of_b(b_);
    report_.correspondence_pose = pose.kind == diff_detail::PoseKind::kRest   ? "rest"
                                  : pose.kind == diff_detail::PoseKind::kClip ? "clip"
                                                                               : "bind";
    report_.correspondence_clip = pose.clip, report_.correspondence_time = pose.time;
    report_.rest_distortion_a = pose.rest_a.share(), report_.rest_distortion_b = pose.rest_b.share();

    const diff_detail::Box box_a = diff_detail::bounding_box(a_, pa), box_b = diff_detail::bounding_box(b_, pb);
    const glm::dvec3 la = box_a.low, ua = box_a.high, lb = box_b.low, ub = box_b.high;
    const double diagonal = std::max(glm::length(ua - la), glm::length(ub - lb));
    const double slack = 1e-6 * diagonal;
    if (glm::any(glm::greaterThan(la, ub + slack)) || glm::any(glm::greaterThan(lb, ua + slack)))
      throw InputError("the two files' meshes do not overlap at " + pose_text(report_) +
                       " (their bounding boxes are disjoint)");
    report_.identity = diff_detail::same_vertices(a_, pa, b_, pb, slack);
    if (report_.identity) {
      a_to_b_ = diff_detail::identity(a_), b_to_a_ = diff_detail::identity(b_);
    } else {
      a_to_b_ = diff_detail::closest_points(a_, pa, b_, pb, "B", threads_);
      b_to_a_ = diff_detail::closest_points(b_, pb, a_, pa, "A", threads_);
    }
    for (uint32_t v : a_to_b_.vertices) a_to_b_.joint.push_back(joint_a_[a_.joint[v]]);
    for (uint32_t v : b_to_a_.vertices) b_to_a_.joint.push_back(joint_b_[b_.joint[v]]);
    const std::vector<uint8_t> smooth_a = diff_detail::smooth_vertices(a_, pa), smooth_b = diff_detail::smooth_vertices(b_, pb);
    diff_detail::plan_normal_comparison(a_, smooth_a, smooth_b, a_to_b_);
    diff_detail::plan_normal_comparison(b_, smooth_b, smooth_a, b_to_a_);
    report_.smooth_normals_a = size_t(std::count(a_to_b_.smooth.begin(), a_to_b_.smooth.end(), 1));
    report_.smooth_normals_b = size_t(std::count(b_to_a_.smooth.begin(), b_to_a_.smooth.end(), 1));
    report_.face_normals_a = a_to_b_.faces.size() / 3, report_.face_normals_b = b_to_a_.faces.size() / 3;
    report_.rest_a_to_b = a_to_b_.max_rest_distance;
    report_.rest_b_to_a = b_to_a_.max_rest_distance;
    report_.correspondence_seconds = seconds_since(start);
    frames_at_once_ = frames_at_once();
  }

  ClipGeometryDiff compare(const diff_detail::ClipPair& pair) {
    const Clip* clip_a = pair.a >= 0 ? &a_.asset.clips[size_t(pair.a)] : nullptr;
    const Clip* clip_b = pair.b >= 0 ? &b_.asset.clips[size_t(pair.b)] : nullptr;
    ClipGeometryDiff c;
    c.name = diff_detail::clip_label(a_.asset, pair.a);
    c.name_b = diff_detail::clip_label(b_.asset, pair.b);
    const std::vector<double> times = clip_times(clip_a, clip_b);

    // Relative thresholds need the clip's diagonal before the samples are counted.
    if (options_.relative) c.diagonal = diagonal_of(clip_a, times);
    const Thresholds abs = absolute(options_.thresholds, options_.relative, c.diagonal);

    std::vector<double> joint_max(joint_names_.size(), -1.0), joint_time(joint_names_.size(), 0.0);
    glm::vec3 low(kInfF), high(-kInfF);
    double sum = 0;
    const size_t at_once = frames_at_once_;
    std::vector<SideFrame> frames_a(at_once), frames_b(at_once);
    std::vector<FrameResult> results(at_once);
    for (size_t first = 0; first < times.size(); first += at_once) {
      check_cancelled(options_.cancel);
      const std::span<const double> chunk(times.data() + first, std::min(at_once, times.size() - first));
      deform(*deform_a_, a_, clip_a, chunk, frames_a);
      deform(*deform_b_, b_, clip_b, chunk, frames_b);
      concurrency::parallel_for(chunk.size(), threads_, [&](size_t f) {
        results[f] = measure_frame(frames_a[f], frames_b[f], abs);
        results[f].figures.time = chunk[f];
      });
      for (size_t f = 0; f < chunk.size(); ++f) {
        FrameResult& r = results[f];
        if (c.frames.empty() || (!std::isnan(c.max_error) && !(r.figures.max_error <= c.max_error))) {
          c.max_error = r.figures.max_error;
          c.worst = {r.worst_side, r.worst_vertex, chunk[f], r.figures.worst_joint};
        }
        c.max_a_to_b = std::max(c.max_a_to_b, r.max_a_to_b);
        c.max_b_to_a = std::max(c.max_b_to_a, r.max_b_to_a);
        c.p99_error = std::max(c.p99_error, r.figures.p99_error);
        c.max_normal_degrees = std::max(c.max_normal_degrees, r.figures.max_normal_degrees);
        c.samples += r.samples, c.over_warn += r.over_warn, c.over_fail += r.over_fail;
        sum += r.sum;
        for (size_t j = 0; j < joint_max.size(); ++j)
          if (double(r.joint_max[j]) > joint_max[j]) joint_max[j] = double(r.joint_max[j]), joint_time[j] = chunk[f];
        low = glm::min(low, r.low), high = glm::max(high, r.high);
        c.frames.push_back(std::move(r.figures));
      }
    }
    if (!options_.relative) c.diagonal = glm::length(glm::dvec3(high - low));
    c.mean_error = c.samples ? sum / double(c.samples) : 0;
    for (size_t j = 0; j < joint_max.size(); ++j)
      if (joint_max[j] >= 0) c.joints.push_back({joint_names_[j], joint_max[j], joint_time[j]});
    std::stable_sort(c.joints.begin(), c.joints.end(), [](const JointDiff& x, const JointDiff& y) { return x.max_error > y.max_error; });
    c.status = diff_verdict({abs.fail, options_.thresholds.fail_percent, abs.hard_fail, abs.warn,
                             options_.thresholds.warn_percent, abs.hard_warn},
                            c.max_error, c.over_warn, c.over_fail, std::max<uint64_t>(c.samples, 1));
    c.reason = verdict_reason(c, options_.thresholds, abs, options_.relative);
    // The worst frame deformed once for both pictures that show it.
    const bool out = !options_.out_dir.empty() && c.status == DiffStatus::kFail, page = !options_.page_dir.empty();
    if (out || page) {
      std::vector<SideFrame> fa, fb;
      worst_frame(clip_a, clip_b, c, fa, fb);
      if (out) c.heat_map = heat_map(fa[0], fb[0], c);
      if (page) page_pictures(fa[0], fb[0], c);
    }
    return c;
  }

  std::string contact_sheet() { return sheet_.size() ? write_sheet() : ""; }

private:
  // Frames deformed and measured at once: up to 32, fewer when --max-memory leaves less beside what is
  // held now (both files, their sides, the correspondence, the deformers). Each frame takes both sides'
  // positions and normals as float, once gathered and once in the deformer's batch; each thread measuring
  // a frame its distances, cosines and surface points; one more frame of each side for a heat map. Throws InputError
  // when not even one frame fits.
  size_t frames_at_once() const {
    using saturating::add;
    using saturating::mul;
    constexpr uint64_t kFrameBytesPerVertex = 2 * (12 + 12);
    const uint64_t per_frame = mul(kFrameBytesPerVertex, uint64_t(a_.vertices) + uint64_t(b_.vertices));
    const uint64_t measuring = mul(uint64_t(threads_) * 20, std::max(a_to_b_.vertices.size(), b_to_a_.vertices.size()));
    const uint64_t fixed = add(measuring, per_frame);  // the heat map's frame
    const uint64_t left = diff_detail::memory_left(options_.load.max_memory);
    if (add(fixed, per_frame) > left)
      throw InputError("comparing a frame of their " + std::to_string(a_.vertices + b_.vertices) + " vertices needs about " +
                       byte_size(add(fixed, per_frame)) + ", more than " + diff_detail::left_text(left, options_.load.max_memory));
    return size_t(std::min<uint64_t>(kMaxFramesAtOnce, (left - fixed) / per_frame));
  }

  uint32_t joint_index(const std::string& name) {
    const auto [it, added] = joint_ids_.emplace(name, uint32_t(joint_names_.size()));
    if (added) joint_names_.push_back(name);
    return it->second;
  }

  std::vector<double> clip_times(const Clip* clip_a, const Clip* clip_b) const {
    if (options_.frames && !options_.frames->times.empty()) return options_.frames->times;
    if (options_.frames && clip_a) return frame_times(*clip_a, *options_.frames);
    return diff_detail::comparison_times(clip_a, clip_b);
  }

  double diagonal_of(const Clip* clip, const std::vector<double>& times) {
    glm::vec3 low(kInfF), high(-kInfF);
    deform_a_->run(clip, times, [&](const DeformedBatch& batch) {
      for (size_t k = 0; k < batch.primitives.size(); ++k) {
        const DeformedBatch::Primitive& p = batch.primitives[k];
        for (size_t i = 0; i + 2 < p.positions.size(); i += 3) {
          if (!a_.on_surface[a_.first_vertex[k] + (i / 3) % p.vertices]) continue;  // frame-major: i / 3 counts frames too
          const glm::vec3 v(p.positions[i], p.positions[i + 1], p.positions[i + 2]);
          low = glm::min(low, v), high = glm::max(high, v);
        }
      }
    });
    return glm::length(glm::dvec3(high - low));
  }

  void deform(Deformer& deformer, const DiffSide& side, const Clip* clip, std::span<const double> times,
              std::vector<SideFrame>& out) {
    deformer.run(clip, times, [&](const DeformedBatch& batch) {
      for (size_t f = 0; f < batch.frame_count; ++f) diff_detail::gather_frame(side, batch, f, out[batch.first_frame + f]);
    });
  }

  FrameResult measure_frame(const SideFrame& fa, const SideFrame& fb, const Thresholds& abs) const {
    FrameResult r;
    r.joint_max.assign(joint_names_.size(), -1.0f);
    // The 99th percentile (the value at index ceil(0.99 n) − 1 in increasing order) is the least of the
    // n − that index largest errors.
    const size_t na = a_to_b_.vertices.size(), n = na + b_to_a_.vertices.size();
    const size_t index = std::min(n - 1, size_t(std::ceil(0.99 * double(n))) - 1);
    thread_local LargestErrors largest;
    largest.reset(n - index);
    measure(fa, fb, a_to_b_, abs.warn, abs.fail, 'A', r, largest, r.max_a_to_b);
    measure(fb, fa, b_to_a_, abs.warn, abs.fail, 'B', r, largest, r.max_b_to_a);
    r.samples = n;
    r.figures.mean_error = r.sum / double(n);
    r.figures.p99_error = double(largest.least());
    const DiffSide& side = r.worst_side == 'A' ? a_ : b_;
    r.figures.worst_joint = side.joint_names[side.joint[r.worst_vertex]];
    if (!options_.relative)  // with --relative, diagonal_of measured the box before the samples
      for (size_t v = 0; v < a_.vertices; ++v) {
        if (!a_.on_surface[v]) continue;
        const glm::vec3 p = at(fa.positions, v);
        r.low = glm::min(r.low, p), r.high = glm::max(r.high, p);
      }
    return r;
  }

  // Each vertex's distance to its corresponding point on the other side's surface (0 where it has none).
  static std::vector<float> vertex_errors(const Correspondence& from_to, size_t vertices, const SideFrame& from,
                                          const SideFrame& onto) {
    std::vector<float> error(vertices, 0.0f);
    for (size_t i = 0; i < from_to.vertices.size(); ++i) {
      const SurfacePoint& s = from_to.points[i];
      glm::vec3 p(0.0f);
      for (int k = 0; k < 3; ++k) p += s.weight[k] * at(onto.positions, s.vertex[k]);
      error[from_to.vertices[i]] = glm::length(at(from.positions, from_to.vertices[i]) - p);
    }
    return error;
  }

  // Both sides deformed at the clip's worst frame.
  void worst_frame(const Clip* clip_a, const Clip* clip_b, const ClipGeometryDiff& c, std::vector<SideFrame>& fa,
                   std::vector<SideFrame>& fb) {
    const double time[1] = {c.worst.time};
    fa.resize(1), fb.resize(1);
    deform(*deform_a_, a_, clip_a, time, fa);
    deform(*deform_b_, b_, clip_b, time, fb);
  }

  // The worst frame of a failing clip, A's surface colored by its error against B.
  std::string heat_map(const SideFrame& fa, const SideFrame& fb, const ClipGeometryDiff& c) {
    const std::vector<float> error = vertex_errors(a_to_b_, a_.vertices, fa, fb);
    // Made with the first image, so that a diff that stops before one (an input error) leaves nothing.
    std::filesystem::create_directories(options_.out_dir);
    const std::string file = diff_detail::heat_map_file_name(c.name);
    diff_detail::ErrorHeatMap map{a_, fa, error, c.max_error,
                                  "t = " + diff_detail::number(c.worst.time) + " s", Bounds{}};
    const Image image = diff_detail::render_error_heat_map(context_.get(), map, options_.image_size);
    diff_detail::write_heat_map(options_.out_dir + "/" + file, image);
    sheet_.add(image, int(sheet_.size()));
    return file;
  }

  // The page's two pictures of a clip (GeometryDiffOptions::page_dir): A and B at the worst frame, each
  // shaded by its own distance to the other (A's vertices against B's surface, B's against A's), on the
  // clip's one scale and framed on the box of both, so that the pictures line up pixel for pixel.
  void page_pictures(const SideFrame& fa, const SideFrame& fb, ClipGeometryDiff& c) {
    const std::vector<float> error_a = vertex_errors(a_to_b_, a_.vertices, fa, fb);
    const std::vector<float> error_b = vertex_errors(b_to_a_, b_.vertices, fb, fa);
    Bounds both;
    for (const auto& [side, frame] : {std::pair{&a_, &fa}, std::pair{&b_, &fb}})
      for (size_t v = 0; v < side->vertices; ++v)
        if (side->on_surface[v]) both.add(at(frame->positions, v));
    char stem[32];
    std::snprintf(stem, sizeof stem, "images/clip%04zu", page_pictures_++);  // by the clip's place in the report
    const std::string time = "t = " + diff_detail::number(c.worst.time) + " s";
    std::filesystem::create_directories(std::filesystem::path(options_.page_dir) / "images");
    for (const char side : {'A', 'B'}) {
      const bool is_a = side == 'A';
      const diff_detail::ErrorHeatMap map{is_a ? a_ : b_, is_a ? fa : fb, is_a ? error_a : error_b,
                                          c.max_error, std::string(1, side) + "  " + time, both};
      std::string& file = is_a ? c.page_a : c.page_b;
      file = std::string(stem) + (is_a ? ".a.png" : ".b.png");
      diff_detail::write_heat_map((std::filesystem::path(options_.page_dir) / file).string(),
                                  diff_detail::render_error_heat_map(context_.get(), map, options_.image_size));
    }
  }

  std::string write_sheet() {
    const std::string file = "worst_frames.png";
    sheet_.write(options_.out_dir + "/" + file, {Overwrite::kReplace});
    return file;
  }

  DiffSide& a_;
  DiffSide& b_;
  const GeometryDiffOptions& options_;
  GeometryDiffReport& report_;
  unsigned threads_;
  JobContext context_;
  std::unique_ptr<Deformer> deform_a_, deform_b_;
  Correspondence a_to_b_, b_to_a_;
  std::map<std::string, uint32_t> joint_ids_;
  std::vector<std::string> joint_names_;
  std::vector<uint32_t> joint_a_, joint_b_;  // each side's joint table into joint_names_
  size_t frames_at_once_ = 1;
  size_t page_pictures_ = 0;  // clips with page pictures so far
  ContactSheet sheet_{256};
};

// Runs one step of comparing the pair `pair` ("A vs B"): its InputErrors and the ceiling's refusals name
// both files.
template <class Step>
auto of_pair(const std::string& pair, Step&& step) {
  try {
    return step();
  } catch (const InputError& e) {
    throw InputError(pair + ": " + e.what());
  } catch (const std::bad_alloc&) {
    const MemoryCeilingLifted lifted;
    throw InputError(pair + ": " + out_of_memory_message());
  }
}

}  // namespace

DiffStatus GeometryDiffReport::status() const {
  DiffStatus worst = DiffStatus::kPass;
  auto take = [&](DiffStatus s) { worst = std::max(worst, s); };
  for (const ClipGeometryDiff& c : clips) take(c.status);
  for (const AnimationFinding& f : findings) take(f.severity);
  return worst;
}

GeometryDiffReport diff_geometry(const std::string& a, const std::string& b, const GeometryDiffOptions& options) {
  const auto start = Clock::now();
  GeometryDiffReport report;
  report.a = a, report.b = b;
  report.mode = options.mode;
  report.thresholds = options.thresholds;
  report.relative = options.relative;

  DiffSide side_a = diff_detail::load_diff_side(a, options.load, options.mode);
  DiffSide side_b = diff_detail::load_diff_side(b, options.load, options.mode);
  report.vertices_a = side_a.vertices, report.vertices_b = side_b.vertices;
  report.on_no_triangle_a = size_t(std::count(side_a.on_surface.begin(), side_a.on_surface.end(), 0));
  report.on_no_triangle_b = size_t(std::count(side_b.on_surface.begin(), side_b.on_surface.end(), 0));
  const std::vector<size_t> selected =
      side_a.asset.clips.empty() ? std::vector<size_t>{} : select_clips(side_a.asset, options.clips);
  const std::string both = a + " vs " + b;
  diff_detail::ClipMatch match =
      of_pair(both, [&] { return diff_detail::match_clips(side_a.asset, side_b.asset, selected); });
  report.findings = std::move(match.findings);
  for (const diff_detail::ClipPair& pair : match.pairs)
    if (pair.a >= 0) {
      const std::vector<AnimationFinding> notes =
          diff_detail::compare_animations(side_a.asset, side_a.asset.clips[size_t(pair.a)], side_b.asset,
                                          side_b.asset.clips[size_t(pair.b)], diff_detail::clip_label(side_a.asset, pair.a));
      report.findings.insert(report.findings.end(), notes.begin(), notes.end());
    }

  std::optional<GeometryDiffer> differ;
  of_pair(both, [&] {
    differ.emplace(side_a, side_b, options, report);
    differ->correspond(match.pairs);
  });
  for (const diff_detail::ClipPair& pair : match.pairs)
    report.clips.push_back(of_pair(both, [&] { return differ->compare(pair); }));
  report.contact_sheet = of_pair(both, [&] { return differ->contact_sheet(); });
  report.wall_seconds = seconds_since(start);
  return report;
}

}  // namespace dqskin
