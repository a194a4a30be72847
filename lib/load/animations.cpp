// Animations (glTF 2.0 §3.11): each channel with its sampler's keys decoded and checked, into Asset::clips.
// A channel's target is a node and path, or (KHR_animation_pointer) a JSON pointer to the same properties
// or to a mesh's default weights; both kinds follow the same rules, and a pointer and an ordinary target
// naming the same property are the same target.
#include "animations.hpp"

#include "animation_pointer.hpp"
#include "dqskin/asset.hpp"
#include "dqskin/error.hpp"

#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace dqskin::gltf {
namespace {

[[noreturn]] void fail(const std::string& message) { throw InputError(message); }

std::string at(const char* kind, size_t index) { return std::string(kind) + " " + std::to_string(index); }

// "node 3 'Arm'", "mesh 0": an object by index, and its name when it has one.
std::string named(const char* kind, size_t index, const std::string& name) {
  return at(kind, index) + (name.empty() ? "" : " '" + name + "'");
}

// A pointer as messages quote it: a hostile file's may be megabytes long.
std::string quoted(const std::string& pointer) {
  return "'" + (pointer.size() > 80 ? pointer.substr(0, 80) + "..." : pointer) + "'";
}

Interpolation parse_interpolation(const std::string& name, const std::string& what) {
  if (name.empty() || name == "LINEAR") return Interpolation::kLinear;
  if (name == "STEP") return Interpolation::kStep;
  if (name == "CUBICSPLINE") return Interpolation::kCubicSpline;
  fail(what + ": unknown interpolation '" + name + "'");
}

// Read from the file rather than the Asset's meshes, so that read_structure (which reads no mesh) can read
// animations too; read_meshes checks that every primitive has as many targets as the first.
int mesh_target_count(const tinygltf::Model& model, int mesh) {
  if (mesh < 0) return 0;
  const tinygltf::Mesh& m = model.meshes[size_t(mesh)];
  return m.primitives.empty() ? int(m.weights.size()) : int(m.primitives.front().targets.size());
}

// What a channel animates. Two channels of one animation with equal targets are duplicates (§3.11; and
// KHR_animation_pointer: "the same node property with a pointer and with an unextended animation target").
struct Target {
  bool mesh = false;  // a mesh's default weights ("/meshes/M/weights"), else a node's property
  int index = -1;     // the node or mesh
  TargetPath path = TargetPath::kTranslation;
  bool operator<(const Target& o) const { return std::tie(mesh, index, path) < std::tie(o.mesh, o.index, o.path); }
};

// A KHR_animation_pointer channel's target, or nothing when its pointer names a property dqskin does not
// animate (added to `ignored`, quoted). Pointers to nodes and meshes must name ones that exist.
std::optional<Target> pointer_target(const tinygltf::AnimationChannel& ch, const tinygltf::Model& m,
                                     const Asset& asset, const std::string& what, std::vector<std::string>& ignored) {
  if (ch.target_node >= 0)
    fail(what + ": has a target node and path 'pointer' (KHR_animation_pointer: the node must not be set)");
  const std::string* pointer = channel_pointer(ch);
  if (!pointer) fail(what + ": path 'pointer' without a KHR_animation_pointer pointer string");
  const AnimationPointer p = parse_animation_pointer(*pointer);
  if (!p.problem.empty()) fail(what + ": pointer " + quoted(*pointer) + " " + p.problem);
  switch (p.property) {
    case PointerProperty::kOther: ignored.push_back(quoted(*pointer)); return std::nullopt;
    case PointerProperty::kMeshWeights:
      if (p.index >= m.meshes.size())
        fail(what + ": pointer " + quoted(*pointer) + " names mesh " + std::to_string(p.index) + ", which does not exist");
      return Target{true, int(p.index), TargetPath::kWeights};
    case PointerProperty::kNodeTranslation:
    case PointerProperty::kNodeRotation:
    case PointerProperty::kNodeScale:
    case PointerProperty::kNodeWeights: break;
  }
  if (p.index >= asset.nodes.size())
    fail(what + ": pointer " + quoted(*pointer) + " names node " + std::to_string(p.index) + ", which does not exist");
  const TargetPath path = p.property == PointerProperty::kNodeTranslation ? TargetPath::kTranslation
                          : p.property == PointerProperty::kNodeRotation  ? TargetPath::kRotation
                          : p.property == PointerProperty::kNodeScale     ? TargetPath::kScale
                                                                          : TargetPath::kWeights;
  return Target{false, int(p.index), path};
}

// The channel's target, or nothing when it is ignored: a channel without a node (§3.11: an extension may
// use it) or a pointer to a property dqskin does not animate.
std::optional<Target> channel_target(const tinygltf::AnimationChannel& ch, const tinygltf::Model& m,
                                     const Asset& asset, const std::string& what, std::vector<std::string>& ignored) {
  if (ch.target_path == "pointer") return pointer_target(ch, m, asset, what, ignored);
  if (ch.target_node < 0) return std::nullopt;
  if (size_t(ch.target_node) >= asset.nodes.size())
    fail(what + ": target node " + std::to_string(ch.target_node) + " does not exist");
  Target t{false, ch.target_node, TargetPath::kTranslation};
  if (ch.target_path == "translation") t.path = TargetPath::kTranslation;
  else if (ch.target_path == "rotation") t.path = TargetPath::kRotation;
  else if (ch.target_path == "scale") t.path = TargetPath::kScale;
  else if (ch.target_path == "weights") t.path = TargetPath::kWeights;
  else fail(what + ": unknown target path '" + ch.target_path + "'");
  return t;
}

// The channel's keys, checked against its target. Channel::node is the target's node (-1 for a mesh's
// weights: the caller gives it one per node that draws the mesh).
Channel read_channel(const tinygltf::Model& m, const AccessorReader& reader, Asset& asset, size_t a,
                     const tinygltf::AnimationChannel& ch, const Target& target, const std::string& what) {
  const tinygltf::Animation& anim = m.animations[a];
  if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size())
    fail(what + ": sampler " + std::to_string(ch.sampler) + " does not exist");
  Channel channel;
  channel.node = target.mesh ? -1 : target.index;
  channel.path = target.path;
  channel.components = target.path == TargetPath::kRotation ? 4 : 3;
  if (target.path == TargetPath::kWeights) {
    channel.components = mesh_target_count(m, target.mesh ? target.index : asset.nodes[size_t(target.index)].mesh);
    // A mesh's weights pointer names a property the mesh does not have: the pointer is broken. A node's
    // weights channel on a mesh without targets is ignored by viewers; what it would deform is unknown, so
    // only the deforming commands refuse (its keys are still read and checked). It stays in the clip with no
    // components, so that the clip's channels keep the file's order (skin_data.cpp matches them by position).
    if (channel.components == 0 && target.mesh) fail(what + ": animates weights of a mesh without morph targets");
    if (channel.components == 0) asset.cannot_deform.push_back(what + ": animates weights of a node without morph targets");
  } else if (asset.nodes[size_t(target.index)].local.has_matrix) {
    // §3.11 forbids it, but three.js and Blender open such a file (the matrix wins or is decomposed): it is
    // described, and only the deforming commands refuse it.
    asset.cannot_deform.push_back(what + ": animates node " + std::to_string(target.index) +
                                  ", which has a matrix (§3.11 forbids it)");
  }

  const tinygltf::AnimationSampler& s = anim.samplers[size_t(ch.sampler)];
  const std::string swhat = at("animation", a) + " sampler " + std::to_string(ch.sampler);
  channel.interpolation = parse_interpolation(s.interpolation, swhat);
  channel.times = reader.floats(s.input, {{TINYGLTF_TYPE_SCALAR}, {TINYGLTF_COMPONENT_TYPE_FLOAT}}, swhat + " input");
  for (size_t k = 0; k < channel.times.size(); ++k) {
    if (channel.times[k] < 0) fail(swhat + ": key time " + std::to_string(channel.times[k]) + " is negative");
    if (k > 0 && !(channel.times[k] > channel.times[k - 1]))
      fail(swhat + ": key times do not increase (key " + std::to_string(k) + ")");
  }
  // Rotations and weights may be normalized integers (§3.11, "Animation samplers" table). Pointer channels
  // take the same types as the ordinary channels they stand for.
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
  if (channel.components == 0) channel.values.clear();  // the weights of no morph target (cannot_deform)
  else if (channel.values.size() != channel.times.size() * per_key)
    fail(swhat + ": output has " + std::to_string(channel.values.size()) + " values for " +
         std::to_string(channel.times.size()) + " keys (expected " + std::to_string(channel.times.size() * per_key) +
         ")");
  if (channel.interpolation == Interpolation::kCubicSpline && channel.times.size() < 2)
    fail(swhat + ": CUBICSPLINE needs at least 2 keys");
  return channel;
}

bool same_keys(const Channel& a, const Channel& b) {
  return a.interpolation == b.interpolation && a.times == b.times && a.values == b.values;
}

// "node 5 'Arm' rotation", "mesh 0 'Body' weights"
std::string describe(const Target& t, const tinygltf::Model& m, const Asset& asset) {
  const std::string& name = t.mesh ? m.meshes[size_t(t.index)].name : asset.nodes[size_t(t.index)].name;
  return named(t.mesh ? "mesh" : "node", size_t(t.index), name) + " " + target_path_name(t.path);
}

// The quoted pointers of a list, at most 5, then how many more.
std::string pointer_list(const std::vector<std::string>& pointers) {
  std::string out;
  for (size_t i = 0; i < pointers.size() && i < 5; ++i) out += (i ? ", " : "") + pointers[i];
  if (pointers.size() > 5) out += " and " + std::to_string(pointers.size() - 5) + " more";
  return out;
}

struct ReadChannel {
  Target target;
  Channel channel;
  size_t file_channel = 0;
};

}  // namespace

AnimationOrigins read_animations(const tinygltf::Model& m, const AccessorReader& reader, Asset& asset) {
  AnimationOrigins origins;
  // The nodes that draw each mesh, in node order: a mesh's weights channel animates them (found once, so
  // that many such channels in a file of many nodes take time in proportion to what they animate).
  std::vector<std::vector<size_t>> drawn_by(m.meshes.size());
  for (size_t n = 0; n < asset.nodes.size(); ++n)
    if (asset.nodes[n].mesh >= 0) drawn_by[size_t(asset.nodes[n].mesh)].push_back(n);
  for (size_t a = 0; a < m.animations.size(); ++a) {
    const tinygltf::Animation& anim = m.animations[a];
    const std::string animation = named("animation", a, anim.name);
    Clip clip;
    clip.name = anim.name.empty() ? "animation" + std::to_string(a) : anim.name;
    std::vector<ReadChannel> kept;
    std::map<Target, size_t> first_of;  // target → index into kept
    std::vector<std::string> ignored;   // pointers to properties dqskin does not animate, quoted (cut short)
    size_t identical = 0;
    for (size_t c = 0; c < anim.channels.size(); ++c) {
      const tinygltf::AnimationChannel& ch = anim.channels[c];
      const std::string what = at("animation", a) + " channel " + std::to_string(c);
      const std::optional<Target> target = channel_target(ch, m, asset, what, ignored);
      if (!target) continue;
      Channel channel = read_channel(m, reader, asset, a, ch, *target, what);
      const auto [it, first] = first_of.emplace(*target, kept.size());
      if (first) {
        kept.push_back({*target, std::move(channel), c});
        continue;
      }
      // §3.11: "within one animation, each target MUST NOT be used more than once". Exporters repeat
      // byte-identical samplers (under new accessors, so the keys are compared, not the indices); viewers
      // play the file, and the first channel is what they show.
      const ReadChannel& earlier = kept[it->second];
      DuplicateChannel d{a, earlier.file_channel, c, same_keys(earlier.channel, channel), {}};
      const std::string both = "channels " + std::to_string(d.first) + " and " + std::to_string(c) +
                               " both animate " + describe(*target, m, asset);
      if (d.identical) {
        ++identical;
        d.message = animation + ": " + both + " with the same keys (glTF 2.0 §3.11: one channel per target)";
      } else {
        d.message = animation + ": " + both + " with different keys (glTF 2.0 §3.11: one channel per target)";
        asset.cannot_deform.push_back(d.message);
      }
      origins.duplicates.push_back(std::move(d));
    }
    if (identical > 0)
      asset.warnings.push_back(animation + ": " + std::to_string(identical) + " duplicate channel" +
                               (identical == 1 ? " (the same node, path and keys as an earlier channel) is ignored"
                                               : "s (the same node, path and keys as an earlier channel) are ignored"));
    if (!ignored.empty())
      asset.warnings.push_back(animation + ": " + std::to_string(ignored.size()) + " KHR_animation_pointer channel" +
                               (ignored.size() == 1 ? "" : "s") + " animating what dqskin does not deform " +
                               (ignored.size() == 1 ? "is" : "are") + " ignored: " + pointer_list(ignored));

    std::vector<ChannelOrigin>& from = origins.channels.emplace_back();
    for (ReadChannel& r : kept) {
      if (r.target.mesh) continue;
      from.push_back({r.file_channel, size_t(anim.channels[r.file_channel].sampler)});
      clip.channels.push_back(std::move(r.channel));
    }
    // A mesh's weights are the default of every node that draws the mesh without weights of its own
    // (§3.7.2.2; §5.23 mesh.weights, §5.25 node.weights): its channel animates those nodes, unless a channel for the
    // node's own weights does.
    for (const ReadChannel& r : kept) {
      if (!r.target.mesh) continue;
      for (size_t n : drawn_by[size_t(r.target.index)]) {
        if (!asset.nodes[n].weights.empty() || first_of.count(Target{false, int(n), TargetPath::kWeights})) continue;
        from.push_back({r.file_channel, size_t(anim.channels[r.file_channel].sampler)});
        clip.channels.push_back(r.channel);
        clip.channels.back().node = int(n);
      }
    }
    for (size_t k = 0; k < clip.channels.size(); ++k) {
      const Channel& ch = clip.channels[k];
      if (k == 0 || double(ch.times.front()) < clip.first_key) clip.first_key = double(ch.times.front());
      if (k == 0 || double(ch.times.back()) > clip.last_key) clip.last_key = double(ch.times.back());
    }
    asset.clips.push_back(std::move(clip));
  }
  return origins;
}

}  // namespace dqskin::gltf
