// Rendering deformed frames into images (shared/DESIGN.md "DeformedFrames ──render──▶ images"): a camera
// framed on the animation's bounding box, an offscreen multisampled framebuffer in the borrowed headless
// context, and PNG (8-bit sRGB) or EXR (linear float) files. No GL or OpenImageIO type appears here.
#pragma once

#include "dqskin/animation.hpp"
#include "dqskin/atomic_file.hpp"
#include "dqskin/deformer.hpp"
#include "dqskin/job.hpp"
#include "dqskin/load.hpp"
#include "dqskin/frame_view.hpp"
#include "dqskin/gpu_context.hpp"

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace dqskin {

// How surfaces are colored: lit (material base color factor, a key light fixed to the camera and an
// ambient term), normals (world normal n as the color 0.5 n + 0.5), weights and mode-diff (a per-vertex
// scalar in [0, 1] as a heat map; the scalar comes from the caller: a joint's weight, or the distance
// between the lbs and dqs positions divided by its largest value over the animation).
enum class Shade { kLit, kNormals, kWeights, kModeDiff };
bool parse_shade(const std::string& text, Shade& shade);

// An axis-aligned box in world space; empty until a point is added.
struct Bounds {
  glm::vec3 min{1.0f}, max{-1.0f};
  bool empty() const { return min.x > max.x; }
  void add(const glm::vec3& point);
  void add(const FrameView& frame);  // every vertex of every primitive
};

// Where the camera looks from. Angles in degrees; yaw turns the view about +Y from the front (+Z, where
// glTF models face) towards +X, pitch raises it. The default is a three-quarter view from above.
struct CameraOptions {
  double yaw = 35, pitch = 20;
  double fov = 35;                  // vertical field of view (perspective only)
  std::optional<double> distance;   // from the box center, world units; default: the nearest that fits
  bool ortho = false;               // orthographic: the view fits the box whatever the distance
};

struct Camera {
  glm::mat4 view{1.0f}, projection{1.0f};
  glm::vec3 eye{0.0f};
};

// The camera that looks at the center of `box` and fits all its corners into a viewport of `aspect`
// (width / height) with a small margin. `box` must not be empty.
Camera frame_camera(const Bounds& box, const CameraOptions& options, double aspect);

// --camera NODE: the index of the node named `name` that carries a glTF camera. Throws InputError when
// no such node exists (naming the camera nodes there are) or when the name is ambiguous.
int find_camera_node(const Asset& asset, const std::string& name);

// The view through a glTF camera whose node has the world matrix `world` (§3.10: the camera looks down its
// local −Z with +Y up; scale and shear in the matrix are removed, as the specification does not let them
// change the projection). Projections are §3.10.3's (finite or infinite perspective, orthographic) with
// `aspect`, the image's width / height, in place of the camera's aspectRatio (and xmag = ymag × aspect),
// so that images are never stretched; render sizes the image in the camera's ratio unless told a size.
// Throws InputError for a camera the loader found invalid (SceneCamera::problem), a yfov of π or more,
// a matrix with no orientation (zero scale), or values that overflow single precision.
Camera scene_camera(const SceneCamera& camera, const Mat4<double>& world, double aspect);

// The glTF camera of `node` (which must have one).
const SceneCamera& camera_of_node(const Asset& asset, int node);

struct RendererOptions {
  int width = 512, height = 512;
  int samples = 4;  // MSAA samples per pixel; fixed, so images do not depend on the driver's default
  glm::vec4 background{0.2f, 0.2f, 0.2f, 1.0f};  // linear RGBA
  Shade shade = Shade::kLit;
};

// Linear RGBA floats, top row first (as image files store them).
struct Image {
  int width = 0, height = 0;
  std::vector<float> rgba;
};

// Draws FrameViews of one asset's mesh instances (triangle primitives; points and lines are skipped)
// into an offscreen framebuffer: an MSAA RGBA16F color and depth renderbuffer, resolved into a
// single-sample one and read back. Uploads the index lists once. Uses `context` from the calling thread
// only; not thread-safe. Holds no time-dependent state, so equal inputs give equal images.
class Renderer {
public:
  // `context` and `asset` must outlive the renderer. Throws InputError for a size or sample count the
  // context cannot offer, NoGpuContext when it lacks an entry point, std::runtime_error naming the shader
  // file when a shader does not compile.
  Renderer(GpuContext& context, const Asset& asset, std::vector<MeshInstance> instances, const RendererOptions& options);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // `frame` has the primitives of the instances in order (as frame_view). `scalars` (weights, mode-diff):
  // one array per primitive with one value per vertex in [0, 1], or empty for 0 everywhere.
  Image render(const FrameView& frame, const Camera& camera, std::span<const std::vector<float>> scalars = {});

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Per primitive of the instances (in order), per vertex: the normalised skin weight of the joint node
// named `joint` (0 where it has no influence; 1 for rigid instances drawn by that node). Throws
// InputError when no node has that name.
std::vector<std::vector<float>> joint_weights(const Asset& asset, const std::vector<MeshInstance>& instances,
                                              const std::string& joint);

enum class ImageFormat { kPng, kExr };
bool parse_image_format(const std::string& text, ImageFormat& format);
const char* extension(ImageFormat format);

// Writes `image` atomically: PNG as 8-bit sRGB (RGBA, converted from linear here, rounded to nearest),
// EXR as 32-bit linear float, no time stamp in either. Throws OutputError naming `path`.
Committed write_image(const std::string& path, const Image& image, ImageFormat format,
                      const CommitOptions& options = {});

// 8-bit sRGB RGBA pixels, top row first: what PNG and GIF store, and what a contact sheet keeps per frame.
struct Image8 {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
};

// `image` encoded as write_image encodes PNGs (sRGB color, linear alpha, rounded to nearest).
Image8 to_srgb8(const Image& image);

// Contact sheets (--sheet): one PNG with every frame of a clip as a cell of a near-square grid
// (columns = ceil(sqrt(n)), rows as needed, frames left to right then top to bottom), each cell the frame
// resized (OpenImageIO's resize, single-threaded, in linear light) to `cell_width` pixels wide with its
// aspect kept, its frame number drawn in its top-left corner in a built-in 5x7 digit font (white on
// black, no system fonts), and a gap of kSheetGap dark pixels around and between the cells. Only the
// cells are kept while a clip renders, not the full frames.
constexpr int kSheetGap = 2;
class ContactSheet {
public:
  explicit ContactSheet(int cell_width = 256);
  void add(const Image& frame, int number);  // resizes the frame now
  size_t size() const { return cells_.size(); }
  Image8 compose() const;  // throws InputError when empty
  // compose() written atomically as an 8-bit sRGB PNG. Throws OutputError naming `path`.
  Committed write(const std::string& path, const CommitOptions& options = {}) const;

private:
  int cell_width_;
  int frames_width_ = 0, frames_height_ = 0;
  std::vector<Image8> cells_;
  std::vector<int> numbers_;
};

// Draws `number` (decimal digits) at (x, y) in the built-in 5x7 font, every font pixel a `scale` square,
// on a black box with a one-font-pixel margin; clipped to the image. Returns the box's width.
int draw_number(Image8& image, int x, int y, int number, int scale);

// Animated GIFs (--gif): frames appended as they arrive (OpenImageIO's GIF writer, 256-color palette per
// frame, looping), so that no frame is kept; written to a temporary and renamed by commit(). `fps` sets
// the frame delay (GIF counts it in hundredths of a second). Throws OutputError naming `path`.
class GifWriter {
public:
  GifWriter(std::string path, double fps);
  ~GifWriter();
  GifWriter(const GifWriter&) = delete;
  GifWriter& operator=(const GifWriter&) = delete;
  void add(const Image& frame);  // every frame the size of the first
  size_t frames() const { return frames_; }
  Committed commit(const CommitOptions& options = {});

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  size_t frames_ = 0;
};

// `dqskin render` as a library call: the inputs' animations planned as bake plans them (same frames,
// clips, shards and names: OUT/<stem>/<anim>/frame_NNNN.png), each clip deformed twice on the GPU: once
// for its bounding box over every frame (so that all frames, and all shards, share one camera), once to
// render this shard's frames.
struct RenderOptions {
  std::string out_dir;
  LoadOptions load;  // resource roots and limits for reading the inputs
  std::string clips = "all";
  FrameSpec frames;
  BlendMode mode = BlendMode::kDqs;  // lbs or dqs: the geometry drawn (mode-diff deforms with both)
  Backend backend = Backend::kAuto;  // draws on its context; cpu: deformed on the CPU reference
  int scene = -1;
  Shard shard;  // this process renders the shard's frames of the plan (dqskin/job_plan.hpp)
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
  GpuContextInfo gpu;
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
