// The rasterizer of `dqskin render` (docs/DESIGN.md §1.1, draw): deformed frames
// drawn through a camera into an offscreen multisampled framebuffer of the borrowed headless context, and
// read back as linear float images. The one layer of rendering that needs a GPU context, so it is kept
// apart from the camera math and the image files. No GL type appears here.
#pragma once

#include "dqskin/asset.hpp"
#include "dqskin/camera.hpp"
#include "dqskin/frame_view.hpp"
#include "dqskin/gpu_context.hpp"
#include "dqskin/skinning.hpp"

#include <memory>
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

}  // namespace dqskin
