#include "mesh.hpp"

#include "dqskin/error.hpp"
#include "dqskin/triangles.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>
#include <utility>

namespace dqskin::gltf {
namespace {

[[noreturn]] void fail(const std::string& message) { throw InputError(message); }

constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
constexpr int kByte = TINYGLTF_COMPONENT_TYPE_BYTE;
constexpr int kUByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kShort = TINYGLTF_COMPONENT_TYPE_SHORT;
constexpr int kUShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
constexpr int kUInt = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;

template <typename V>
std::vector<V> to_vectors(const std::vector<float>& f) {
  constexpr size_t n = sizeof(V) / sizeof(float);
  std::vector<V> out(f.size() / n);
  for (size_t i = 0; i < out.size(); ++i)
    for (size_t c = 0; c < n; ++c) out[i][int(c)] = f[i * n + c];
  return out;
}

// Attribute shapes of glTF 2.0 §3.7.2.1; KHR_mesh_quantization widens them to every integer type.
// Morph targets (§3.7.2.2): KHR_mesh_quantization allows POSITION displacements as byte or short, plain or
// normalized, and NORMAL and TANGENT ones as normalized byte or short only.
struct Shapes {
  AccessorShape position, normal, tangent, texcoord, joints, weights, target, target_position;
  // COLOR_n is the same with or without quantization.
  AccessorShape color{{TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4}, {kFloat, kUByte, kUShort}, true};
};

Shapes shapes_for(bool quantized) {
  if (quantized)
    return {{{TINYGLTF_TYPE_VEC3}, {kFloat, kByte, kUByte, kShort, kUShort}},
            {{TINYGLTF_TYPE_VEC3}, {kFloat, kByte, kShort}, true},
            {{TINYGLTF_TYPE_VEC4}, {kFloat, kByte, kShort}, true},
            {{TINYGLTF_TYPE_VEC2}, {kFloat, kByte, kUByte, kShort, kUShort}},
            {{TINYGLTF_TYPE_VEC4}, {kUByte, kUShort}},
            {{TINYGLTF_TYPE_VEC4}, {kFloat, kUByte, kUShort}, true},
            {{TINYGLTF_TYPE_VEC3}, {kFloat, kByte, kShort}, true},
            {{TINYGLTF_TYPE_VEC3}, {kFloat, kByte, kShort}}};
  return {{{TINYGLTF_TYPE_VEC3}, {kFloat}},
          {{TINYGLTF_TYPE_VEC3}, {kFloat}},
          {{TINYGLTF_TYPE_VEC4}, {kFloat}},
          {{TINYGLTF_TYPE_VEC2}, {kFloat, kUByte, kUShort}, true},
          {{TINYGLTF_TYPE_VEC4}, {kUByte, kUShort}},
          {{TINYGLTF_TYPE_VEC4}, {kFloat, kUByte, kUShort}, true},
          {{TINYGLTF_TYPE_VEC3}, {kFloat}},
          {{TINYGLTF_TYPE_VEC3}, {kFloat}}};
}

int find_attribute(const std::map<std::string, int>& attributes, const std::string& name) {
  const auto it = attributes.find(name);
  return it == attributes.end() ? -1 : it->second;
}

// Skin influences (§3.7.3.3): every JOINTS_n/WEIGHTS_n pair, numbered from 0 without gaps (§3.7.2.1:
// "indices MUST start with 0 and be continuous positive integers"), at most kMaxInfluenceSets of them,
// into prim.joints/weights, 4 per set and vertex. Every set is read before the merged arrays are made, so
// each value is copied once.
void read_influences(const tinygltf::Primitive& p, const AccessorReader& reader, const Shapes& shape,
                     const std::string& what, Primitive& prim) {
  const int highest = highest_influence_set(p);
  if (highest < 0) return;
  if (highest >= kMaxInfluenceSets)
    fail(what + ": has JOINTS_" + std::to_string(highest) + "/WEIGHTS_" + std::to_string(highest) + ": more than " +
         std::to_string(kMaxInfluences) + " influences per vertex (" + std::to_string(kMaxInfluenceSets) +
         " sets), which dqskin does not read");
  const size_t n = prim.positions.size(), sets = size_t(highest) + 1;
  std::vector<std::vector<uint32_t>> joints(sets);
  std::vector<std::vector<float>> weights(sets);
  for (size_t set = 0; set < sets; ++set) {
    const std::string js = "JOINTS_" + std::to_string(set), ws = "WEIGHTS_" + std::to_string(set);
    const int ja = find_attribute(p.attributes, js), wa = find_attribute(p.attributes, ws);
    if (ja < 0 && wa < 0)
      fail(what + ": has JOINTS_" + std::to_string(highest) + " or WEIGHTS_" + std::to_string(highest) + " but not " +
           js + " or " + ws + " (sets are numbered from 0 without gaps)");
    if (ja < 0 || wa < 0) fail(what + ": has " + (ja < 0 ? ws : js) + " without " + (ja < 0 ? js : ws));
    for (const auto& [accessor, name] : {std::pair{ja, js}, std::pair{wa, ws}}) {
      const size_t count = reader.count(accessor, what + " " + name);
      if (count != n)
        fail(what + ": " + name + " has " + std::to_string(count) + " elements, POSITION has " + std::to_string(n));
    }
    joints[set] = reader.uints(ja, shape.joints, what + " " + js);
    weights[set] = reader.floats(wa, shape.weights, what + " " + ws);
    for (size_t v = 0; v < n; ++v)
      for (size_t k = 0; k < 4; ++k)
        if (weights[set][v * 4 + k] < 0) fail(what + ": " + ws + " of vertex " + std::to_string(v) + " is negative");
  }
  const size_t per = 4 * sets;
  prim.influences = int(per);
  prim.joints.resize(n * per);
  prim.weights.resize(n * per);
  for (size_t set = 0; set < sets; ++set) {
    for (size_t v = 0; v < n; ++v)
      for (size_t k = 0; k < 4; ++k) {
        prim.joints[v * per + 4 * set + k] = uint16_t(joints[set][v * 4 + k]);
        prim.weights[v * per + 4 * set + k] = weights[set][v * 4 + k];
      }
    joints[set] = {};
    weights[set] = {};
  }
}

Primitive read_primitive(const tinygltf::Primitive& p, const AccessorReader& reader, const Shapes& shape,
                         const std::string& what, std::vector<std::string>& warnings) {
  Primitive prim;
  if (p.mode < 0 || p.mode > 6) fail(what + ": mode " + std::to_string(p.mode) + " is not a glTF primitive mode");
  prim.mode = PrimitiveMode(p.mode);
  prim.material = p.material;

  const int position = find_attribute(p.attributes, "POSITION");
  if (position < 0) fail(what + ": has no POSITION");
  prim.position_accessor = position;
  for (const auto& [name, accessor] : p.attributes) prim.vertex_accessors.emplace_back(name, accessor);
  for (size_t t = 0; t < p.targets.size(); ++t)
    for (const auto& [name, accessor] : p.targets[t]) prim.vertex_accessors.emplace_back(std::to_string(t) + "/" + name, accessor);
  prim.positions = to_vectors<glm::vec3>(reader.floats(position, shape.position, what + " POSITION"));
  const size_t n = prim.positions.size();
  auto same_count = [&](int accessor, const std::string& name) {
    const size_t c = reader.count(accessor, what + " " + name);
    if (c != n) fail(what + ": " + name + " has " + std::to_string(c) + " elements, POSITION has " + std::to_string(n));
  };

  if (const int a = find_attribute(p.attributes, "NORMAL"); a >= 0) {
    same_count(a, "NORMAL");
    prim.normals = to_vectors<glm::vec3>(reader.floats(a, shape.normal, what + " NORMAL"));
  }
  if (const int a = find_attribute(p.attributes, "TANGENT"); a >= 0) {
    same_count(a, "TANGENT");
    prim.tangents = to_vectors<glm::vec4>(reader.floats(a, shape.tangent, what + " TANGENT"));
  }
  if (const int a = find_attribute(p.attributes, "TEXCOORD_0"); a >= 0) {
    same_count(a, "TEXCOORD_0");
    prim.uv0 = to_vectors<glm::vec2>(reader.floats(a, shape.texcoord, what + " TEXCOORD_0"));
  }
  // Only the renderer reads these, and they do not move the surface: a bad one is dropped with a warning
  // (as materials.cpp does), so that the file still bakes.
  try {
    if (const int a = find_attribute(p.attributes, "TEXCOORD_1"); a >= 0) {
      same_count(a, "TEXCOORD_1");
      prim.uv1 = to_vectors<glm::vec2>(reader.floats(a, shape.texcoord, what + " TEXCOORD_1"));
    }
  } catch (const InputError& e) {
    warnings.push_back(std::string(e.what()) + "; TEXCOORD_1 is ignored");
  }
  try {
    if (const int a = find_attribute(p.attributes, "COLOR_0"); a >= 0) {
      same_count(a, "COLOR_0");
      const std::vector<float> c = reader.floats(a, shape.color, what + " COLOR_0");
      if (reader.components(a, what + " COLOR_0") == 4) {
        prim.colors = to_vectors<glm::vec4>(c);
      } else {
        prim.colors.resize(n);
        for (size_t v = 0; v < n; ++v) prim.colors[v] = {c[3 * v], c[3 * v + 1], c[3 * v + 2], 1.0f};
      }
    }
  } catch (const InputError& e) {
    warnings.push_back(std::string(e.what()) + "; COLOR_0 is ignored");
  }
  if (p.indices >= 0) {
    prim.indices = reader.uints(p.indices, {{TINYGLTF_TYPE_SCALAR}, {kUByte, kUShort, kUInt}}, what + " indices");
    for (size_t i = 0; i < prim.indices.size(); ++i)
      if (prim.indices[i] >= n)
        fail(what + ": index " + std::to_string(i) + " is " + std::to_string(prim.indices[i]) + ", but there are " +
             std::to_string(n) + " vertices");
  }

  read_influences(p, reader, shape, what, prim);

  for (size_t t = 0; t < p.targets.size(); ++t) {
    MorphTarget target;
    const std::string twhat = what + " target " + std::to_string(t);
    for (const auto& [name, accessor] : p.targets[t]) {
      std::vector<glm::vec3>* dest = name == "POSITION" ? &target.positions
                                     : name == "NORMAL" ? &target.normals
                                     : name == "TANGENT" ? &target.tangents
                                                         : nullptr;
      if (!dest) continue;  // other attributes (TEXCOORD_n, COLOR_n) do not move the surface
      same_count(accessor, "target " + std::to_string(t) + " " + name);
      const AccessorShape& target_shape = dest == &target.positions ? shape.target_position : shape.target;
      *dest = to_vectors<glm::vec3>(reader.floats(accessor, target_shape, twhat + " " + name));
    }
    prim.targets.push_back(std::move(target));
  }

  const bool triangles = prim.mode == PrimitiveMode::kTriangles || prim.mode == PrimitiveMode::kTriangleStrip ||
                         prim.mode == PrimitiveMode::kTriangleFan;
  if (prim.normals.empty() && triangles) {
    prim.normals = smooth_normals(prim);
    prim.normals_generated = true;
  }
  return prim;
}

}  // namespace

std::string no_influences_reason(size_t node, int mesh, size_t primitive) {
  return "node " + std::to_string(node) + ": is skinned, but mesh " + std::to_string(mesh) + " primitive " +
         std::to_string(primitive) + " has no JOINTS_0/WEIGHTS_0";
}

int highest_influence_set(const tinygltf::Primitive& p) {
  int highest = -1;
  for (const auto& [name, accessor] : p.attributes)
    for (const std::string_view prefix : {std::string_view("JOINTS_"), std::string_view("WEIGHTS_")}) {
      const std::string_view view(name);
      if (view.substr(0, prefix.size()) != prefix || view.size() == prefix.size() || view.size() > prefix.size() + 9)
        continue;
      const std::string_view digits = view.substr(prefix.size());
      if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) continue;
      highest = std::max(highest, std::stoi(std::string(digits)));
    }
  return highest;
}

void read_meshes(const tinygltf::Model& model, const AccessorReader& reader, Asset& asset) {
  bool quantized = false;
  for (const std::string& e : model.extensionsUsed) quantized = quantized || e == "KHR_mesh_quantization";
  const Shapes shape = shapes_for(quantized);

  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const tinygltf::Mesh& mesh = model.meshes[m];
    const std::string what = "mesh " + std::to_string(m);
    Mesh out;
    out.name = mesh.name;
    if (mesh.primitives.empty()) fail(what + ": has no primitives");
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      out.primitives.push_back(
          read_primitive(mesh.primitives[p], reader, shape, what + " primitive " + std::to_string(p), asset.warnings));
      if (out.primitives.back().targets.size() != out.primitives.front().targets.size())
        fail(what + ": its primitives have different numbers of morph targets");
    }
    const size_t targets = out.primitives.front().targets.size();
    if (!mesh.weights.empty() && mesh.weights.size() != targets)
      fail(what + ": has " + std::to_string(mesh.weights.size()) + " weights for " + std::to_string(targets) + " morph targets");
    for (double w : mesh.weights) {
      if (!std::isfinite(w)) fail(what + ": weights are not finite");
      out.weights.push_back(float(w));
    }
    out.weights.resize(targets, 0.0f);
    asset.meshes.push_back(std::move(out));
  }

  // Node-level checks that need the meshes: morph weight counts, and joint indices against the skin.
  for (size_t i = 0; i < asset.nodes.size(); ++i) {
    const Node& node = asset.nodes[i];
    if (node.mesh < 0) continue;
    const Mesh& mesh = asset.meshes[size_t(node.mesh)];
    if (!node.weights.empty() && node.weights.size() != mesh.weights.size())
      fail("node " + std::to_string(i) + ": has " + std::to_string(node.weights.size()) + " weights for " +
           std::to_string(mesh.weights.size()) + " morph targets");
    if (node.skin < 0) continue;
    const size_t joints = asset.skins[size_t(node.skin)].joints.size();
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const Primitive& prim = mesh.primitives[p];
      // Viewers draw such a primitive unskinned; a deformation of it is not defined (§3.7.3), so only the
      // deforming commands refuse it.
      if (prim.influences == 0) {
        asset.cannot_deform.push_back(no_influences_reason(i, node.mesh, p));
        continue;
      }
      for (size_t k = 0; k < prim.joints.size(); ++k)
        if (prim.joints[k] >= joints)
          fail("mesh " + std::to_string(node.mesh) + " primitive " + std::to_string(p) + ": vertex " +
               std::to_string(k / size_t(prim.influences)) + " uses joint " + std::to_string(prim.joints[k]) +
               ", but skin " + std::to_string(node.skin) + " has " + std::to_string(joints) + " joints");
    }
  }
}

}  // namespace dqskin::gltf
