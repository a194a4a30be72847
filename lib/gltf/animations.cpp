// Animations (glTF 2.0 §3.11): each channel with its sampler's keys decoded and checked, into Asset::clips.
#include "animations.hpp"

#include "dqskin/error.hpp"

#include <set>
#include <string>
#include <utility>

namespace dqskin::gltf {
namespace {

[[noreturn]] void fail(const std::string& message) { throw InputError(message); }

std::string at(const char* kind, size_t index) { return std::string(kind) + " " + std::to_string(index); }

Interpolation parse_interpolation(const std::string& name, const std::string& what) {
  if (name.empty() || name == "LINEAR") return Interpolation::kLinear;
  if (name == "STEP") return Interpolation::kStep;
  if (name == "CUBICSPLINE") return Interpolation::kCubicSpline;
  fail(what + ": unknown interpolation '" + name + "'");
}

// Read from the file rather than the Asset's meshes, so that read_structure (which reads no mesh) can read
// animations too; read_meshes checks that every primitive has as many targets as the first.
int morph_target_count(const tinygltf::Model& model, const Asset& asset, int node) {
  const int mesh = asset.nodes[size_t(node)].mesh;
  if (mesh < 0) return 0;
  const tinygltf::Mesh& m = model.meshes[size_t(mesh)];
  return m.primitives.empty() ? int(m.weights.size()) : int(m.primitives.front().targets.size());
}

}  // namespace

void read_animations(const tinygltf::Model& m, const AccessorReader& reader, Asset& asset) {
  for (size_t a = 0; a < m.animations.size(); ++a) {
    const tinygltf::Animation& anim = m.animations[a];
    Clip clip;
    clip.name = anim.name.empty() ? "animation" + std::to_string(a) : anim.name;
    bool first = true;
    std::set<std::pair<int, int>> targets;
    for (size_t c = 0; c < anim.channels.size(); ++c) {
      const tinygltf::AnimationChannel& ch = anim.channels[c];
      const std::string what = at("animation", a) + " channel " + std::to_string(c);
      if (ch.target_node < 0) continue;  // §3.11: no node means the channel is ignored (an extension may use it)
      if (size_t(ch.target_node) >= asset.nodes.size())
        fail(what + ": target node " + std::to_string(ch.target_node) + " does not exist");
      if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size())
        fail(what + ": sampler " + std::to_string(ch.sampler) + " does not exist");
      Channel channel;
      channel.node = ch.target_node;
      if (ch.target_path == "translation") channel.path = TargetPath::kTranslation, channel.components = 3;
      else if (ch.target_path == "rotation") channel.path = TargetPath::kRotation, channel.components = 4;
      else if (ch.target_path == "scale") channel.path = TargetPath::kScale, channel.components = 3;
      else if (ch.target_path == "weights") {
        channel.path = TargetPath::kWeights;
        channel.components = morph_target_count(m, asset, ch.target_node);
        if (channel.components == 0) fail(what + ": animates weights of a node without morph targets");
      } else {
        fail(what + ": unknown target path '" + ch.target_path + "'");
      }
      if (!targets.insert({ch.target_node, int(channel.path)}).second)
        fail(what + ": a second channel for the same node and path");
      if (channel.path != TargetPath::kWeights && asset.nodes[size_t(ch.target_node)].local.has_matrix)
        fail(what + ": animates node " + std::to_string(ch.target_node) + ", which has a matrix (§3.11 forbids it)");

      const tinygltf::AnimationSampler& s = anim.samplers[size_t(ch.sampler)];
      const std::string swhat = at("animation", a) + " sampler " + std::to_string(ch.sampler);
      channel.interpolation = parse_interpolation(s.interpolation, swhat);
      channel.times = reader.floats(s.input, {{TINYGLTF_TYPE_SCALAR}, {TINYGLTF_COMPONENT_TYPE_FLOAT}}, swhat + " input");
      for (size_t k = 0; k < channel.times.size(); ++k) {
        if (channel.times[k] < 0) fail(swhat + ": key time " + std::to_string(channel.times[k]) + " is negative");
        if (k > 0 && !(channel.times[k] > channel.times[k - 1]))
          fail(swhat + ": key times do not increase (key " + std::to_string(k) + ")");
      }
      // Rotations and weights may be normalized integers (§3.11, "Animation samplers" table).
      const bool int_ok = channel.path == TargetPath::kRotation || channel.path == TargetPath::kWeights;
      const AccessorShape vshape =
          int_ok ? AccessorShape{{channel.path == TargetPath::kRotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_SCALAR},
                                 {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
                                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                                 true}
                 : AccessorShape{{TINYGLTF_TYPE_VEC3}, {TINYGLTF_COMPONENT_TYPE_FLOAT}};
      channel.values = reader.floats(s.output, vshape, swhat + " output");
      const size_t per_key = size_t(channel.components) * (channel.interpolation == Interpolation::kCubicSpline ? 3 : 1);
      if (channel.values.size() != channel.times.size() * per_key)
        fail(swhat + ": output has " + std::to_string(channel.values.size()) + " values for " +
             std::to_string(channel.times.size()) + " keys (expected " +
             std::to_string(channel.times.size() * per_key) + ")");
      if (channel.interpolation == Interpolation::kCubicSpline && channel.times.size() < 2)
        fail(swhat + ": CUBICSPLINE needs at least 2 keys");
      if (first || double(channel.times.front()) < clip.first_key) clip.first_key = double(channel.times.front());
      if (first || double(channel.times.back()) > clip.last_key) clip.last_key = double(channel.times.back());
      first = false;
      clip.channels.push_back(std::move(channel));
    }
    asset.clips.push_back(std::move(clip));
  }
}

}  // namespace dqskin::gltf
