// `dqskin render` as a library call: inputs planned by the job layer, each clip deformed (on the GPU, or
// on the CPU reference for dib and --backend cpu) once for its bounding box (unless a glTF camera needs
// none) and once more, a chunk of frames at a time, to render this shard's frames.
#include "dqskin/render.hpp"

#include "dqskin/error.hpp"
#include "dqskin/deformer.hpp"
#include "../job/job_run.hpp"
#include "../base/output_journal.hpp"
#include "../base/ordered_worker.hpp"
#include "render_manifest.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>

namespace dqskin {

namespace {

using Clock = std::chrono::steady_clock;

// Frames deformed per Deformer::run: the deformer may hand batches to a thread of its own, but GL may
// only be used from this one, so a chunk's batches are kept and rendered after the run.
// Small enough to bound that copy, large enough that the GPU still works in batches.
constexpr size_t kFramesPerChunk = 16;

// The distance between two deformations of the same vertices, per primitive and vertex.
std::vector<std::vector<float>> distances(const FrameView& a, const FrameView& b) {
  std::vector<std::vector<float>> out(a.primitives.size());
  for (size_t p = 0; p < a.primitives.size(); ++p) {
    const std::span<const float> pa = a.primitives[p].positions, pb = b.primitives[p].positions;
    out[p].resize(a.primitives[p].vertices);
    for (size_t v = 0; v < out[p].size(); ++v)
      out[p][v] = glm::length(glm::vec3(pa[3 * v], pa[3 * v + 1], pa[3 * v + 2]) - glm::vec3(pb[3 * v], pb[3 * v + 1], pb[3 * v + 2]));
  }
  return out;
}

// Deforms frames of one input in one blend mode, where deform_path() says: the GPU, the fast CPU deformer,
// or the double-precision CPU reference (dib, which has no GPU path, and --backend cpu).
class FrameSource {
public:
  FrameSource(GpuContext& context, const InputPlan& input, BlendMode mode, Backend backend) {
    DeformerOptions o;
    o.mode = mode;
    o.backend = backend;
    deformer_ = make_deformer(&context, *input.asset, input.instances, o);
  }

  std::vector<DeformedBatch> deform(const Clip* clip, const std::vector<double>& times) {
    std::vector<DeformedBatch> batches;
    deformer_->run(clip, times, [&](const DeformedBatch& batch) { batches.push_back(batch); });
    return batches;
  }

private:
  std::unique_ptr<Deformer> deformer_;
};

// The renderer options of one input: with a glTF camera that has an aspect ratio, and no size given by
// the user, the width follows that ratio.
RendererOptions renderer_options(const InputPlan& input, const RenderOptions& options, int camera_node) {
  RendererOptions r = options.renderer;
  if (camera_node < 0) return r;
  const SceneCamera& camera = camera_of_node(*input.asset, camera_node);
  if (!camera.problem.empty()) throw InputError(camera.problem);  // before any frame is deformed
  if (!options.size_from_camera) return r;
  const double ratio = camera.orthographic ? std::abs(camera.xmag / camera.ymag) : camera.aspect_ratio;
  if (ratio > 0 && std::isfinite(ratio)) r.width = int(std::lround(std::clamp(double(r.height) * ratio, 1.0, 16384.0)));
  return r;
}

class InputRenderer {
public:
  InputRenderer(const InputPlan& input, const RenderOptions& options, GpuContext& context, RenderReport& report,
                ProgressCounter& progress, OutputJournal& journal)
      : input_(input), options_(options), report_(report), progress_(progress), journal_(journal),
        camera_node_(options.camera_node.empty() ? -1 : find_camera_node(*input.asset, options.camera_node)),
        renderer_options_(renderer_options(input, options, camera_node_)),
        source_(context, input, options.mode, options.backend),
        renderer_(context, *input.asset, input.instances, renderer_options_) {
    if (options.renderer.shade == Shade::kWeights) {
      if (options.joint.empty()) throw InputError("--shade weights needs --joint NAME");
      scalars_ = joint_weights(*input.asset, input.instances, options.joint);
    }
    if (options.renderer.shade == Shade::kModeDiff)  // against lbs, or dqs when lbs is drawn
      other_ = std::make_unique<FrameSource>(context, input, options.mode == BlendMode::kLbs ? BlendMode::kDqs : BlendMode::kLbs,
                                             deform_path(options.backend, options.mode, &context) == DeformPath::kReference
                                                 ? Backend::kCpu
                                                 : options.backend);
  }

  void render_clip(const ClipPlan& clip) {
    check_cancel();
    const std::vector<size_t> mine = clip.my_frames();
    if (mine.empty()) return;
    journal_.make_folders(options_.out_dir + "/" + clip.folder);

    // The box (and the largest mode difference) over every frame, not only this shard's, so that every
    // shard frames the same camera and colors with the same scale. A glTF camera needs no box.
    const double aspect = double(renderer_options_.width) / double(renderer_options_.height);
    Bounds box;
    double max_distance = 0;
    if (camera_node_ < 0 || other_) {
      std::vector<size_t> all(clip.times.size());
      for (size_t f = 0; f < all.size(); ++f) all[f] = f;
      for_each_frame(clip, all, [&](size_t, const FrameView& frame, const FrameView* other) {
        box.add(frame);
        if (other)
          for (const std::vector<float>& d : distances(frame, *other))
            for (float x : d) max_distance = std::max(max_distance, double(x));
      });
      if (box.empty()) throw InputError("the scene has no vertices to frame");
    }
    // The automatic camera is fixed for the clip; a glTF camera follows its node's animation.
    const Camera automatic = camera_node_ < 0 ? frame_camera(box, options_.camera, aspect) : Camera{};
    auto camera_at = [&](size_t f) {
      if (camera_node_ < 0) return automatic;
      const Asset& asset = *input_.asset;
      const Mat4<double> world = sample_pose(asset, clip.clip, clip.times[f]).world[size_t(camera_node_)];
      return scene_camera(camera_of_node(asset, camera_node_), world, aspect);
    };
    if (other_) report_.mode_diff.push_back({input_.path, clip.name, max_distance});

    // Whole-animation review images of this shard's frames, built as the frames arrive: the sheet keeps
    // only its resized cells, the GIF writes each frame at once.
    std::optional<ContactSheet> sheet;
    if (options_.sheet) sheet.emplace(options_.sheet_cell);
    std::unique_ptr<GifWriter> gif;
    // Shards write into one folder, each with its own frames: their sheets and GIFs get the shard's name.
    const std::string suffix = options_.shard.whole()
                                   ? ""
                                   : "_shard" + std::to_string(options_.shard.index) + "of" + std::to_string(options_.shard.count);
    const std::string gif_file = clip.folder + "/animation" + suffix + ".gif";
    if (options_.gif) gif = std::make_unique<GifWriter>(options_.out_dir + "/" + gif_file, clip.fps > 0 ? clip.fps : options_.frames.fps);

    // Encoding and writing a frame (PNG compression, the sheet's resize, the GIF's palette) runs on a
    // thread of its own, in frame order, while this one renders the next frame: GL stays on this thread.
    {
      concurrency::OrderedWorker<std::pair<size_t, Image>> writer([&](const std::pair<size_t, Image>& item) {
        const auto& [f, image] = item;
        const std::string relative = clip.frame_file(f, extension(options_.format));
        write_image(options_.out_dir + "/" + relative, image, options_.format, {options_.overwrite, &journal_});
        report_.outputs.push_back(relative);
        if (sheet) sheet->add(image, clip.numbers[f]);
        if (gif) gif->add(image);
        ++frames_done_;
        progress_.add(1, input_.path, clip.name);
      });
      for_each_frame(clip, mine, [&](size_t f, const FrameView& frame, const FrameView* other) {
        check_cancel();
        if (other) {
          scalars_ = distances(frame, *other);
          // Scaled by the animation's largest difference; an animation where both modes agree stays cold.
          for (std::vector<float>& d : scalars_)
            for (float& x : d) x = max_distance > 0 ? float(double(x) / max_distance) : 0.0f;
        }
        writer.push({f, renderer_.render(frame, camera_at(f), scalars_)});
      });
      writer.finish();
    }
    if (sheet) {
      const std::string relative = clip.folder + "/sheet" + suffix + ".png";
      sheet->write(options_.out_dir + "/" + relative, {options_.overwrite, &journal_});
      report_.outputs.push_back(relative);
    }
    if (gif) {
      gif->commit({options_.overwrite, &journal_});
      report_.outputs.push_back(gif_file);
    }
  }

  size_t frames_done() const { return frames_done_; }

private:
  void check_cancel() const { check_cancelled(options_.cancel); }

  // Calls visit(frame index, frame, the other mode's frame or null) for `frames` of the clip, in order,
  // a chunk at a time on this thread.
  template <typename Visit>
  void for_each_frame(const ClipPlan& clip, const std::vector<size_t>& frames, Visit visit) {
    for (size_t first = 0; first < frames.size(); first += kFramesPerChunk) {
      const size_t count = std::min(kFramesPerChunk, frames.size() - first);
      std::vector<double> times;
      for (size_t i = first; i < first + count; ++i) times.push_back(clip.times[frames[i]]);
      const std::vector<DeformedBatch> batches = source_.deform(clip.clip, times);
      const std::vector<DeformedBatch> others = other_ ? other_->deform(clip.clip, times) : std::vector<DeformedBatch>{};
      size_t other_batch = 0, other_k = 0;  // the two deformers may batch differently
      for (const DeformedBatch& batch : batches)
        for (size_t k = 0; k < batch.frame_count; ++k) {
          std::optional<FrameView> other;
          if (other_) {
            if (other_k == others.at(other_batch).frame_count) ++other_batch, other_k = 0;
            other = frame_view(others.at(other_batch), other_k++);
          }
          visit(frames[first + batch.first_frame + k], frame_view(batch, k), other ? &*other : nullptr);
        }
    }
  }

  const InputPlan& input_;
  const RenderOptions& options_;
  RenderReport& report_;
  ProgressCounter& progress_;
  OutputJournal& journal_;
  const int camera_node_;  // --camera: the node, or -1 for the automatic camera
  const RendererOptions renderer_options_;
  FrameSource source_;
  std::unique_ptr<FrameSource> other_;  // mode-diff: the other blend mode
  Renderer renderer_;
  std::vector<std::vector<float>> scalars_;
  size_t frames_done_ = 0;
};

}  // namespace

bool RenderReport::any_failed() const {
  return std::any_of(inputs.begin(), inputs.end(), [](const InputResult& r) { return !r.error.empty(); });
}

RenderReport render(const std::vector<std::string>& inputs, const RenderOptions& options,
                    const std::function<void(const JobProgress&)>& progress) {
  const Clock::time_point start = Clock::now();
  if (options.shard.count == 0 || options.shard.index >= options.shard.count) throw InputError("bad shard");
  // The backend's context draws; where the deformation runs is deform_path()'s decision.
  if (options.sheet && (options.sheet_cell < 1 || options.sheet_cell > 4096))
    throw InputError("--sheet-cell must be 1 to 4096 pixels");

  PlanOptions plan_options{options.out_dir, options.load, options.clips, options.frames, options.scene, options.shard};
  plan_options.load.decoded_images = true;  // the renderer decodes the textures
  double load_seconds = 0;
  const std::vector<InputPlan> plans = plan_inputs(inputs, plan_options, load_seconds);

  RenderReport report;
  for (const InputPlan& plan : plans)
    for (const ClipPlan& clip : plan.clips) report.frames_total += clip.my_frames().size();

  JobContext context(options.backend);
  ProgressCounter counter(report.frames_total, progress);
  size_t outputs_before = 0, mode_diff_before = 0;
  report.inputs = for_each_input(
      plans,
      [&](const InputPlan& plan, OutputJournal& journal, InputResult& result) {
        outputs_before = report.outputs.size(), mode_diff_before = report.mode_diff.size();
        InputRenderer renderer(plan, options, context.get(), report, counter, journal);
        for (const ClipPlan& clip : plan.clips) renderer.render_clip(clip);
        result.frames = renderer.frames_done();
      },
      [&](const InputPlan&) {
        report.outputs.resize(outputs_before);
        report.mode_diff.resize(mode_diff_before);
      });
  if (context.info()) {
    report.gpu = *context.info();
    report.deformer = describe(deform_path(options.backend, options.mode, &context.get()));
  }
  std::sort(report.outputs.begin(), report.outputs.end());
  // As bake: a render that drew something records it (render-manifest.json, which also clears what a
  // killed run of this shard left), after one sync, so that the record only lists files on disk.
  if (std::any_of(report.inputs.begin(), report.inputs.end(), [](const InputResult& r) { return r.error.empty(); })) {
    std::filesystem::create_directories(options.out_dir);
    sync_folder(options.out_dir);
    report.manifest = render_detail::write_render_manifest(plans, options, report);
  }
  report.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return report;
}

}  // namespace dqskin
