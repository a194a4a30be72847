// The automatic camera of `dqskin render`: looks at the center of the animation's bounding box from a
// yaw/pitch direction and fits the box's eight corners into the view, so every frame of an animation is
// seen through the same camera.
#include "dqskin/camera.hpp"

#include "dqskin/error.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace dqskin {

void Bounds::add(const glm::vec3& point) {
  if (empty()) {
    min = max = point;
    return;
  }
  min = glm::min(min, point);
  max = glm::max(max, point);
}

void Bounds::add(const FrameView& frame) {
  for (const PrimitiveView& p : frame.primitives)
    for (size_t v = 0; v + 2 < p.positions.size(); v += 3) add(glm::vec3(p.positions[v], p.positions[v + 1], p.positions[v + 2]));
}

Camera frame_camera(const Bounds& box, const CameraOptions& options, double aspect) {
  const glm::dvec3 lo(box.min), hi(box.max);
  const glm::dvec3 center = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * glm::length(hi - lo), 1e-6);  // a single point still gets a view
  const double yaw = glm::radians(options.yaw), pitch = glm::radians(options.pitch);
  // Unit vector from the center towards the eye: yaw 0, pitch 0 looks from +Z at the model's front.
  const glm::dvec3 back(std::sin(yaw) * std::cos(pitch), std::sin(pitch), std::cos(yaw) * std::cos(pitch));
  // Up is +Y unless the view looks straight down or up.
  const glm::dvec3 world_up = std::abs(back.y) > 0.999 ? glm::dvec3(0, 0, -1) : glm::dvec3(0, 1, 0);
  const glm::dvec3 right = glm::normalize(glm::cross(world_up, back));
  const glm::dvec3 up = glm::cross(back, right);

  const double margin = 1.08;  // a little air around the model
  const double tan_y = std::tan(glm::radians(options.fov) / 2), tan_x = tan_y * aspect;
  // The nearest distance at which every corner is inside the frustum: a corner at (x, y, z) in camera
  // axes (z towards the eye) needs |x| ≤ (d − z) tan_x and |y| ≤ (d − z) tan_y. For ortho, the half
  // extents of the view instead.
  double fit = 0, half_x = 0, half_y = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 c((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z);
    const glm::dvec3 d = c - center;
    const double x = std::abs(glm::dot(d, right)) * margin, y = std::abs(glm::dot(d, up)) * margin, z = glm::dot(d, back);
    fit = std::max({fit, z + x / tan_x, z + y / tan_y});
    half_x = std::max(half_x, x);
    half_y = std::max(half_y, y);
  }
  const double distance = options.distance.value_or(options.ortho ? 2 * radius : fit);

  Camera camera;
  const glm::dvec3 eye = center + back * distance;
  camera.eye = glm::vec3(eye);
  camera.view = glm::mat4(glm::lookAt(eye, center, up));
  // Depth range around the box's bounding sphere, never through or behind the eye.
  const double near_plane = std::max(distance - 1.5 * radius, 1e-3 * radius);
  const double far_plane = std::max(distance + 1.5 * radius, near_plane * 2);
  if (options.ortho) {
    half_x = std::max({half_x, half_y * aspect, 1e-6});
    half_y = half_x / aspect;
    camera.projection = glm::mat4(glm::ortho(-half_x, half_x, -half_y, half_y, near_plane, far_plane));
  } else {
    camera.projection = glm::mat4(glm::perspective(glm::radians(options.fov), aspect, near_plane, far_plane));
  }
  return camera;
}

int find_camera_node(const Asset& asset, const std::string& name) {
  int found = -1;
  std::string cameras;  // for the message: the camera nodes there are
  for (size_t i = 0; i < asset.nodes.size(); ++i) {
    const Node& node = asset.nodes[i];
    if (node.camera < 0) continue;
    cameras += (cameras.empty() ? "'" : ", '") + node.name + "'";
    if (node.name != name) continue;
    if (found >= 0) throw InputError("--camera '" + name + "': nodes " + std::to_string(found) + " and " + std::to_string(i) + " have that name");
    found = int(i);
  }
  if (found < 0)
    throw InputError("--camera '" + name + "': no node of that name has a camera" +
                     (cameras.empty() ? std::string(" (the file has none)") : " (camera nodes: " + cameras + ")"));
  return found;
}

Camera scene_camera(const SceneCamera& sc, const Mat4<double>& world, double aspect) {
  if (!sc.problem.empty()) throw InputError(sc.problem);
  // The rotation of the node: its columns orthonormalised (Gram-Schmidt from −Z, the viewing direction,
  // then +Y, the up direction), which removes scale and shear and keeps where the camera looks.
  glm::dvec3 forward = -glm::dvec3(world[2]), up = glm::dvec3(world[1]);
  if (!(glm::length(forward) > 1e-12) || !(glm::length(up) > 1e-12))
    throw InputError("camera '" + sc.name + "': its node's matrix is degenerate (zero scale)");
  forward = glm::normalize(forward);
  up -= forward * glm::dot(up, forward);
  if (!(glm::length(up) > 1e-12)) throw InputError("camera '" + sc.name + "': its node's matrix is degenerate");
  up = glm::normalize(up);
  const glm::dvec3 eye(world[3]);

  Camera camera;
  camera.eye = glm::vec3(eye);
  camera.view = glm::mat4(glm::lookAt(eye, eye + forward, up));
  // §3.10.3's matrices, with the image's aspect ratio in place of the camera's, so that an image is never
  // stretched: a perspective camera keeps its yfov, an orthographic one its ymag.
  if (sc.orthographic) {
    const double xmag = std::abs(sc.ymag) * aspect;
    camera.projection = glm::mat4(glm::ortho(-xmag, xmag, -std::abs(sc.ymag), std::abs(sc.ymag), sc.znear, sc.zfar));
  } else {
    if (!(sc.yfov < glm::pi<double>()))
      throw InputError("camera '" + sc.name + "': a yfov of pi or more cannot be drawn");
    camera.projection = glm::mat4(sc.zfar > 0 ? glm::perspective(sc.yfov, aspect, sc.znear, sc.zfar)
                                              : glm::infinitePerspective(sc.yfov, aspect, sc.znear));
  }
  // Values that are finite in double can overflow float (znear 1e200, yfov 1e-40): every frame would
  // come out empty.
  for (const glm::mat4* m : {&camera.view, &camera.projection})
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        if (!std::isfinite((*m)[c][r]))
          throw InputError("camera '" + sc.name + "': its values overflow single precision (znear, zfar, yfov, xmag, "
                           "ymag or the node's position)");
  return camera;
}

const SceneCamera& camera_of_node(const Asset& asset, int node) {
  return asset.cameras[size_t(asset.nodes[size_t(node)].camera)];
}

}  // namespace dqskin
