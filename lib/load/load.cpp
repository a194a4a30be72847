// tinygltf::Model → Asset: structure (scenes, node hierarchy, skins, animations) with every reference
// checked (glTF 2.0 §3.5-3.11). Mesh primitives are decoded in mesh.cpp.
#include "dqskin/load.hpp"

#include "accessor.hpp"
#include "animations.hpp"
#include "../base/byte_size.hpp"
#include "dqskin/error.hpp"
#include "draco.hpp"
#include "influence_limit.hpp"
#include "materials.hpp"
#include "memory_estimate.hpp"
#include "mesh.hpp"
#include "model_io.hpp"
#include "skinned_node_transform.hpp"
#include "structure.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <set>

namespace dqskin {
namespace {

using gltf::AccessorReader;
using gltf::AccessorShape;

[[noreturn]] void fail(const std::string& message) { throw InputError(message); }

std::string at(const char* kind, size_t index) { return std::string(kind) + " " + std::to_string(index); }

// Extensions that change what the geometry or animation data mean; without them a file must not be
// loaded (§3.12: a required extension the loader does not support makes the asset unusable).
bool is_supported_extension(const std::string& name) {
  static const std::set<std::string> supported = {
      "KHR_mesh_quantization",  // integer attributes: the accessor reader decodes every component type
      "EXT_meshopt_compression",  // compressed buffer views: decoded when the file is read (meshopt.hpp)
      "KHR_draco_mesh_compression",  // compressed primitives: decoded before the meshes are read (draco.hpp)
      // Appearance only: the deformation does not depend on them.
      "KHR_materials_emissive_strength", "KHR_materials_unlit", "KHR_materials_pbrSpecularGlossiness",
      "KHR_materials_clearcoat", "KHR_materials_ior", "KHR_materials_specular", "KHR_materials_transmission",
      "KHR_materials_volume", "KHR_materials_sheen", "KHR_materials_iridescence", "KHR_materials_variants",
      "KHR_texture_transform", "KHR_texture_basisu", "EXT_texture_webp", "KHR_lights_punctual",
      // Channels that name their property by a JSON pointer: those on nodes and meshes are read as ordinary
      // channels, the others (appearance, cameras) ignored with a warning (animations.cpp).
      "KHR_animation_pointer"};
  return supported.count(name) > 0;
}

LocalTransform read_local(const tinygltf::Node& n, const std::string& what) {
  LocalTransform t;
  auto finite = [&](const std::vector<double>& v, const char* field) {
    for (double x : v)
      if (!std::isfinite(x)) fail(what + ": " + field + " is not finite");
  };
  if (!n.matrix.empty()) {
    if (n.matrix.size() != 16) fail(what + ": matrix must have 16 numbers");
    finite(n.matrix, "matrix");
    t.has_matrix = true;
    t.matrix = glm::make_mat4(n.matrix.data());  // column-major, as glTF stores it
    // §5.25: the matrix must be decomposable to TRS, so its last row is (0, 0, 0, 1).
    if (t.matrix[0][3] != 0 || t.matrix[1][3] != 0 || t.matrix[2][3] != 0 || t.matrix[3][3] != 1)
      fail(what + ": matrix is not affine (its last row must be 0, 0, 0, 1)");
    if (!n.translation.empty() || !n.rotation.empty() || !n.scale.empty())
      fail(what + ": has both matrix and translation/rotation/scale");
  }
  if (!n.translation.empty()) {
    if (n.translation.size() != 3) fail(what + ": translation must have 3 numbers");
    finite(n.translation, "translation");
    t.translation = {n.translation[0], n.translation[1], n.translation[2]};
  }
  if (!n.rotation.empty()) {
    if (n.rotation.size() != 4) fail(what + ": rotation must have 4 numbers");
    finite(n.rotation, "rotation");
    const Quat<double> q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
    const double length = glm::length(q);
    if (!(length > 1e-6)) fail(what + ": rotation is a zero quaternion");
    t.rotation = q / length;  // §5.25 asks for unit quaternions; writers round, so renormalise
  }
  if (!n.scale.empty()) {
    if (n.scale.size() != 3) fail(what + ": scale must have 3 numbers");
    finite(n.scale, "scale");
    t.scale = {n.scale[0], n.scale[1], n.scale[2]};
  }
  return t;
}

void read_nodes(const tinygltf::Model& m, Asset& asset) {
  asset.nodes.resize(m.nodes.size());
  for (size_t i = 0; i < m.nodes.size(); ++i) {
    const tinygltf::Node& n = m.nodes[i];
    Node& node = asset.nodes[i];
    const std::string what = at("node", i);
    node.name = n.name;
    node.local = read_local(n, what);
    if (n.mesh >= 0 && size_t(n.mesh) >= m.meshes.size()) fail(what + ": mesh " + std::to_string(n.mesh) + " does not exist");
    if (n.skin >= 0 && size_t(n.skin) >= m.skins.size()) fail(what + ": skin " + std::to_string(n.skin) + " does not exist");
    if (n.skin >= 0 && n.mesh < 0) fail(what + ": has a skin but no mesh");
    node.mesh = n.mesh;
    node.skin = n.skin;
    for (double w : n.weights) {
      if (!std::isfinite(w)) fail(what + ": weights are not finite");
      node.weights.push_back(float(w));
    }
    for (int c : n.children) {
      if (c < 0 || size_t(c) >= m.nodes.size()) fail(what + ": child " + std::to_string(c) + " does not exist");
      if (asset.nodes[size_t(c)].parent >= 0)
        fail(at("node", size_t(c)) + ": has two parents (nodes " + std::to_string(asset.nodes[size_t(c)].parent) +
             " and " + std::to_string(i) + ")");
      asset.nodes[size_t(c)].parent = int(i);
      node.children.push_back(c);
    }
  }
  // §3.5.3: the hierarchy is a set of disjoint trees. With one parent each, a cycle is the only way to
  // fail that. Walk up from every node, marking the path; each node is walked once (linear time even for
  // a chain of a million nodes).
  enum : char { kUnseen, kOnPath, kRooted };
  std::vector<char> state(asset.nodes.size(), kUnseen);
  std::vector<size_t> path;
  for (size_t i = 0; i < asset.nodes.size(); ++i) {
    path.clear();
    int p = int(i);
    while (p >= 0 && state[size_t(p)] == kUnseen) {
      state[size_t(p)] = kOnPath;
      path.push_back(size_t(p));
      p = asset.nodes[size_t(p)].parent;
    }
    if (p >= 0 && state[size_t(p)] == kOnPath) fail(at("node", size_t(p)) + ": is its own ancestor (the hierarchy has a cycle)");
    for (size_t n : path) state[n] = kRooted;
  }
}

void read_scenes(const tinygltf::Model& m, Asset& asset) {
  for (size_t i = 0; i < m.scenes.size(); ++i) {
    Scene scene{m.scenes[i].name, {}};
    for (int r : m.scenes[i].nodes) {
      if (r < 0 || size_t(r) >= asset.nodes.size()) fail(at("scene", i) + ": node " + std::to_string(r) + " does not exist");
      if (asset.nodes[size_t(r)].parent >= 0) fail(at("scene", i) + ": node " + std::to_string(r) + " is not a root node");
      scene.roots.push_back(r);
    }
    asset.scenes.push_back(std::move(scene));
  }
  if (m.defaultScene >= 0 && size_t(m.defaultScene) >= asset.scenes.size())
    fail("scene " + std::to_string(m.defaultScene) + " (the default scene) does not exist");
  asset.default_scene = m.defaultScene;
}

void read_skins(const tinygltf::Model& m, const AccessorReader& reader, Asset& asset) {
  for (size_t i = 0; i < m.skins.size(); ++i) {
    const tinygltf::Skin& s = m.skins[i];
    const std::string what = at("skin", i);
    Skin skin;
    skin.name = s.name;
    if (s.joints.empty()) fail(what + ": has no joints");
    std::set<int> seen;
    for (int j : s.joints) {
      if (j < 0 || size_t(j) >= asset.nodes.size()) fail(what + ": joint node " + std::to_string(j) + " does not exist");
      if (!seen.insert(j).second) fail(what + ": lists node " + std::to_string(j) + " twice");
      skin.joints.push_back(j);
    }
    if (s.skeleton >= 0 && size_t(s.skeleton) >= asset.nodes.size())
      fail(what + ": skeleton node " + std::to_string(s.skeleton) + " does not exist");
    skin.skeleton = s.skeleton;
    if (s.inverseBindMatrices >= 0) {
      const std::vector<float> ibm = reader.floats(
          s.inverseBindMatrices, {{TINYGLTF_TYPE_MAT4}, {TINYGLTF_COMPONENT_TYPE_FLOAT}}, what + " inverseBindMatrices");
      if (ibm.size() / 16 < skin.joints.size())
        fail(what + ": has " + std::to_string(ibm.size() / 16) + " inverse bind matrices for " +
             std::to_string(skin.joints.size()) + " joints");
      for (size_t j = 0; j < skin.joints.size(); ++j) skin.inverse_bind.push_back(Mat4<double>(glm::make_mat4(&ibm[16 * j])));
    } else {
      skin.inverse_bind.assign(skin.joints.size(), Mat4<double>(1.0));  // §3.7.3.1: identity when absent
    }
    asset.skins.push_back(std::move(skin));
  }
}

// Things that are valid, or that dqskin corrects, but that a user may want to know (the Khronos
// validator reports the same situations): warnings, and the notices only some commands print.
void add_warnings(const tinygltf::Model& m, Asset& asset) {
  for (size_t i = 0; i < m.nodes.size(); ++i) {
    const std::vector<double>& r = m.nodes[i].rotation;
    if (r.size() == 4 && std::abs(std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[3] * r[3]) - 1) > 1e-5)
      asset.warnings.push_back(at("node", i) + ": rotation is not a unit quaternion; it is normalized");
  }
  // §3.7.3.1: the skinned mesh node's transform does not apply, nor do its parents'. Exporters write one
  // on purpose (an armature's scale, a Z-up turn), so it is a notice, once per file, not a warning per node.
  const std::string notice =
      gltf::skinned_node_transform_notice(asset.nodes, gltf::skinned_nodes_with_transform(asset.nodes));
  if (!notice.empty()) asset.notices.push_back(notice);
  for (const std::string& ext : m.extensionsUsed)
    if (!is_supported_extension(ext) &&
        std::find(m.extensionsRequired.begin(), m.extensionsRequired.end(), ext) == m.extensionsRequired.end())
      asset.warnings.push_back("extension " + ext + " is used but not supported; it is ignored");
}

// Refuses a file whose decoding would take more than options.max_memory, before anything is decoded.
// `json_bytes`: what parsing its JSON took (still held: the checked document and the model).
void check_memory(const tinygltf::Model& m, uint64_t json_bytes, const LoadOptions& options) {
  gltf::MemoryEstimate need = gltf::estimate_memory(m, options.decoded_images, options.keep_source);
  need.json = json_bytes;
  if (need.total() > options.max_memory)
    fail("loading it needs about " + byte_size(need.total()) + " (" + byte_size(need.asset) + " decoded by " +
         std::to_string(need.accessor_uses) + " accessor reads, " + byte_size(need.transient) +
         " while the largest is decoded, " + byte_size(need.file) + " of buffers and images, " +
         (need.decoded ? byte_size(need.decoded) + " of compressed data decoded, " : std::string()) +
         byte_size(need.json) +
         " for its JSON" +
         (need.images ? ", " + byte_size(need.images) + " of decoded images" : std::string()) +
         "), more than --max-memory " + byte_size(options.max_memory));
}

Asset convert(tinygltf::Model& m, uint64_t json_bytes, const std::string& path, const LoadOptions& options) {
  for (const std::string& ext : m.extensionsRequired)
    if (!is_supported_extension(ext)) fail("requires extension " + ext + ", which dqskin does not support");
  check_memory(m, json_bytes, options);
  gltf::decode_draco(m);  // into ordinary accessors, within the estimate just checked

  Asset asset;
  asset.path = path;
  const AccessorReader reader{m, options.max_unbacked_elements};
  read_nodes(m, asset);
  read_scenes(m, asset);
  read_skins(m, reader, asset);
  gltf::read_meshes(m, reader, asset);
  gltf::keep_largest_influences(asset, options.max_influences);  // --max-influences, once, before anything deforms
  gltf::read_appearance(m, asset);
  gltf::read_animations(m, reader, asset);
  add_warnings(m, asset);
  return asset;
}

}  // namespace

Asset gltf::read_structure(tinygltf::Model& m, uint64_t json_bytes, const std::string& path,
                           const LoadOptions& options, AnimationOrigins* animations) {
  for (const std::string& ext : m.extensionsRequired)
    if (!is_supported_extension(ext)) fail("requires extension " + ext + ", which dqskin does not support");
  check_memory(m, json_bytes, options);
  gltf::decode_draco(m);
  Asset asset;
  asset.path = path;
  const AccessorReader reader{m, options.max_unbacked_elements};
  read_nodes(m, asset);
  read_scenes(m, asset);
  read_skins(m, reader, asset);
  AnimationOrigins origins = gltf::read_animations(m, reader, asset);
  if (animations) *animations = std::move(origins);
  return asset;
}

Mat4<double> LocalTransform::to_matrix() const {
  if (has_matrix) return matrix;
  // T * R * S (§3.5.2)
  return glm::scale(glm::translate(Mat4<double>(1.0), translation) * glm::mat4_cast(rotation), scale);
}

Asset load_asset(const std::string& path, const LoadOptions& options) {
  // The file is held whole while it loads: it counts toward max_memory too. read_regular_file's messages do
  // not name the path; the caller names it.
  const std::vector<uint8_t> bytes = gltf::read_regular_file(path, std::min(options.max_file_bytes, options.max_memory));
  return load_asset_from_memory(bytes, path, gltf::folder_of(path), options);
}

Asset load_asset_from_memory(std::span<const uint8_t> bytes, const std::string& name, const std::string& base_dir,
                             const LoadOptions& options) {
  if (bytes.empty()) fail("the file is empty");
  gltf::ParsedModel parsed = gltf::parse_model(bytes, base_dir, options);
  Asset asset = convert(parsed.model, parsed.json_bytes, name, options);
  if (options.refuse_undeformable && !asset.cannot_deform.empty()) fail(asset.cannot_deform.front());
  asset.warnings.insert(asset.warnings.begin(), parsed.warnings.begin(), parsed.warnings.end());
  if (options.keep_source) asset.source = gltf::keep_source(parsed, asset, options);
  return asset;
}

}  // namespace dqskin
