// Rendering deformed frames into images (docs/DESIGN.md §1.1, draw) as one job:
// `dqskin render` as a library call, which walks inputs × clips × frames, deforms each clip and draws its
// frames with the camera (dqskin/camera.hpp), the renderer (dqskin/renderer.hpp) and the image files
// (dqskin/image_output.hpp). Those layers have their own headers so that a part used alone (framing a
// view, drawing one frame, writing one image) does not depend on the job; this one includes all three.
// No GL or OpenImageIO type appears here.
#pragma once

#include "dqskin/animation.hpp"
#include "dqskin/atomic_file.hpp"
#include "dqskin/camera.hpp"
#include "dqskin/deformer.hpp"
#include "dqskin/gpu_context.hpp"
#include "dqskin/image_output.hpp"
#include "dqskin/job.hpp"
#include "dqskin/load.hpp"
#include "dqskin/renderer.hpp"
#include "dqskin/skinning.hpp"

#include <atomic>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace dqskin {

// `dqskin render` as a library call: the inputs' animations planned by the job layer (job_plan.hpp), so
// with the frames, clips, shards and names a bake has (OUT/<stem>/<anim>/frame_NNNN.png), each clip
// deformed twice: once for its bounding box over every frame (so that all frames, and all shards, share
// one camera), once to render this shard's frames.
struct RenderOptions {
  std::string out_dir;
  LoadOptions load;  // resource roots and limits for reading the inputs
  std::string clips = "all";
  FrameSpec frames;
  BlendMode mode = BlendMode::kDqs;  // lbs or dqs: the geometry drawn (mode-diff deforms with both)
  Backend backend = Backend::kAuto;  // draws on its context; cpu: deformed on the CPU reference
  int scene = -1;
  Shard shard;  // this process renders the shard's frames of the plan (lib/job/job_plan.hpp)
  RendererOptions renderer;
  CameraOptions camera;
  // --camera: the node (by name) whose glTF camera the frames are seen through, following its animation;
  // empty for the automatic camera. With size_from_camera (the user gave no size), a camera with an
  // aspect ratio sets the image width to height × aspectRatio.
  std::string camera_node;
  bool size_from_camera = false;
  std::string joint;  // Shade::kWeights: the joint node whose influence is shown
  ImageFormat format = ImageFormat::kPng;
  Overwrite overwrite = Overwrite::kRefuseDifferent;
  // Per clip, after its frames: OUT/<stem>/<anim>/sheet.png and OUT/<stem>/<anim>/animation.gif, of the
  // frames this shard renders (all of them when not sharded); with --shard I/N they are named
  // sheet_shardIofN.png and animation_shardIofN.gif, so that the shards' files do not collide.
  bool sheet = false;
  int sheet_cell = 256;  // cell width in pixels
  bool gif = false;
  const std::atomic<bool>* cancel = nullptr;  // set from a signal handler: stop between frames
};

// Shade::kModeDiff: the distance that the heat map's top color stands for in one clip.
struct ModeDiffScale {
  std::string input, clip;
  double max_distance = 0;  // largest |p_lbs − p_dqs| over every vertex and frame, world units
};

struct RenderReport {
  std::vector<InputResult> inputs;  // error empty when the input rendered
  std::vector<ModeDiffScale> mode_diff;  // one per rendered clip with Shade::kModeDiff
  std::vector<std::string> outputs;     // files written or found equal, relative to out_dir, sorted
  std::string manifest;  // render-manifest.json (render-manifest.shard-I-of-N.json); empty when nothing rendered
  GpuContextInfo gpu;       // the context that drew
  std::string deformer;     // what deformed: describe(DeformPath), empty when nothing was rendered
  size_t frames_total = 0;  // frames this shard renders over all inputs
  double wall_seconds = 0;
  bool any_failed() const;
};

// Renders every input (a failing input is reported and the rest go on). Throws NoGpuContext when no
// context can be made, JobCancelled when options.cancel was set, InputError for options that cannot
// work. `progress` is called after each frame's image is written, from the thread that writes images
// (one call at a time).
RenderReport render(const std::vector<std::string>& inputs, const RenderOptions& options,
                    const std::function<void(const JobProgress&)>& progress = {});

}  // namespace dqskin
