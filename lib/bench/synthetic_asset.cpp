#include "synthetic_asset.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace dqskin::bench_detail {

Asset make_synthetic_asset(size_t vertices, size_t joints, bool with_scale) {
  constexpr double kSegment = 0.5;  // joint spacing along y
  Asset asset;
  asset.path = "synthetic";
  asset.nodes.resize(joints + 1);
  Skin skin;
  for (size_t j = 0; j < joints; ++j) {
    Node& node = asset.nodes[j];
    node.name = "joint" + std::to_string(j);
    node.parent = j == 0 ? -1 : int(j - 1);
    if (j + 1 < joints) node.children = {int(j + 1)};
    node.local.translation = {0, j == 0 ? 0 : kSegment, 0};
    skin.joints.push_back(int(j));
    skin.inverse_bind.push_back(glm::translate(Mat4<double>(1.0), Vec3<double>(0, -kSegment * double(j), 0)));
  }
  asset.skins.push_back(skin);
  Node& mesh_node = asset.nodes[joints];
  mesh_node.name = "body";
  mesh_node.mesh = 0;
  mesh_node.skin = 0;
  asset.scenes.push_back({"scene", {0, int(joints)}});
  asset.default_scene = 0;

  // Rings of 64 vertices up the chain; each vertex takes the 4 joints nearest its height.
  Primitive prim;
  prim.mode = PrimitiveMode::kPoints;  // the benchmark deforms vertices; no faces are needed
  prim.influences = 4;
  const double height = kSegment * double(joints - 1);
  const size_t around = 64;
  for (size_t v = 0; v < vertices; ++v) {
    const double angle = 2 * M_PI * double(v % around) / double(around);
    const double y = height * double(v / around) / double(std::max<size_t>(1, vertices / around));
    prim.positions.emplace_back(std::cos(angle), y, std::sin(angle));
    prim.normals.emplace_back(std::cos(angle), 0, std::sin(angle));
    const double at = y / kSegment;  // position along the chain in joints
    const size_t first = size_t(std::clamp(std::floor(at) - 1, 0.0, double(joints >= 4 ? joints - 4 : 0)));
    float sum = 0;
    float w[4];
    for (size_t k = 0; k < 4; ++k) sum += (w[k] = float(1.0 / (1.0 + std::abs(at - double(first + k)))));
    for (size_t k = 0; k < 4; ++k) {
      prim.joints.push_back(uint16_t(std::min(first + k, joints - 1)));
      prim.weights.push_back(w[k] / sum);
    }
  }
  prim.position_accessor = 0;
  asset.meshes.push_back({"body", {prim}, {}});

  Clip clip;
  clip.name = with_scale ? "bend_and_scale" : "bend";
  clip.first_key = 0;
  clip.last_key = 2;
  for (size_t j = 0; j < joints; ++j) {
    Channel rot;
    rot.node = int(j);
    rot.path = TargetPath::kRotation;
    rot.components = 4;
    for (int k = 0; k <= 8; ++k) {
      const double t = 0.25 * k, a = 0.4 * std::sin(M_PI * t + double(j));
      rot.times.push_back(float(t));
      rot.values.insert(rot.values.end(), {0, 0, float(std::sin(a / 2)), float(std::cos(a / 2))});
    }
    clip.channels.push_back(rot);
    if (with_scale) {
      Channel scale = rot;
      scale.path = TargetPath::kScale;
      scale.components = 3;
      scale.values.clear();
      for (int k = 0; k <= 8; ++k) {
        const float s = float(1 + 0.2 * std::sin(M_PI * 0.25 * k));
        scale.values.insert(scale.values.end(), {s, 2 - s, 1});
      }
      clip.channels.push_back(scale);
    }
  }
  asset.clips.push_back(clip);
  return asset;
}

}  // namespace dqskin::bench_detail
