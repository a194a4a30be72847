// The cameras of `dqskin render`: the automatic one, framed on the animation's bounding box from a yaw and
// pitch, and the glTF cameras that --camera looks through. Plain glm math, kept apart from the renderer
// because choosing a view needs no GPU context: the render job frames each clip on its bounds over every
// frame before it draws any, so that all frames and all shards share one camera.
#pragma once

#include "dqskin/asset.hpp"
#include "dqskin/frame_view.hpp"

#include <optional>
#include <string>

namespace dqskin {

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

}  // namespace dqskin
