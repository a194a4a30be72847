// Reading a file's raw skin data for `dqskin lint` (skin_data.hpp): the structure as the loader reads it,
// then every JOINTS_n/WEIGHTS_n set leniently (glTF 2.0 §3.7.3.3), and where each rotation channel comes
// from.
#include "skin_data.hpp"

#include "accessor.hpp"
#include "dqskin/error.hpp"
#include "mesh.hpp"
#include "model_io.hpp"
#include "structure.hpp"

#include <algorithm>
#include <cstdint>
#include <map>
#include <string_view>

namespace dqskin::gltf {
namespace {

int find_attribute(const std::map<std::string, int>& attributes, const std::string& name) {
  const auto it = attributes.find(name);
  return it == attributes.end() ? -1 : it->second;
}

// Every influence set of one primitive. Values are read as they are (negative weights, any joint index);
// only the shapes §3.7.3.3 allows are accepted, as anything else has no meaning as a weight. Sets must be
// numbered from 0 without gaps (§3.7.3.3, "TEXCOORD_n, COLOR_n, JOINTS_n, WEIGHTS_n": indices must start
// with 0 and be continuous). `memory_left` is what decoding may still take; each set takes 48 bytes a vertex.
std::vector<InfluenceSet> read_sets(const tinygltf::Primitive& p, const AccessorReader& reader, size_t vertices,
                                    const std::string& what, uint64_t& memory_left) {
  const int highest = highest_influence_set(p);
  // The loader's bound (asset.hpp), so that lint reads every file the deforming commands read.
  if (highest >= dqskin::kMaxInfluenceSets)
    throw InputError(what + ": has JOINTS_" + std::to_string(highest) + "/WEIGHTS_" + std::to_string(highest) +
                     ": more than " + std::to_string(dqskin::kMaxInfluences) +
                     " influences per vertex, which lint does not read");
  std::vector<InfluenceSet> sets;
  for (int n = 0; n <= highest; ++n) {
    const std::string js = "JOINTS_" + std::to_string(n), ws = "WEIGHTS_" + std::to_string(n);
    const int ja = find_attribute(p.attributes, js), wa = find_attribute(p.attributes, ws);
    if (ja < 0 && wa < 0)
      throw InputError(what + ": has JOINTS_" + std::to_string(highest) + " or WEIGHTS_" + std::to_string(highest) +
                       " but not " + js + " or " + ws + " (sets are numbered from 0 without gaps)");
    if (ja < 0 || wa < 0) throw InputError(what + ": has " + (ja < 0 ? ws : js) + " without " + (ja < 0 ? js : ws));
    const uint64_t bytes = uint64_t(vertices) * 4 * (sizeof(uint32_t) + sizeof(double));
    if (bytes > memory_left) throw InputError(what + ": its influence sets need more memory than --max-memory allows");
    memory_left -= bytes;
    for (const auto& [accessor, name] : {std::pair{ja, js}, std::pair{wa, ws}}) {
      const size_t count = reader.count(accessor, what + " " + name);
      if (count != vertices)
        throw InputError(what + ": " + name + " has " + std::to_string(count) + " elements, POSITION has " +
                         std::to_string(vertices));
    }
    InfluenceSet set;
    set.joints =
        reader.uints(ja, {{TINYGLTF_TYPE_VEC4}, {kComponentUnsignedByte, kComponentUnsignedShort}}, what + " " + js);
    const std::vector<float> w = reader.floats(
        wa, {{TINYGLTF_TYPE_VEC4}, {kComponentFloat, kComponentUnsignedByte, kComponentUnsignedShort}, true},
        what + " " + ws);
    set.weights.assign(w.begin(), w.end());
    set.joints_component = reader.model.accessors[size_t(ja)].componentType;
    set.weights_component = reader.model.accessors[size_t(wa)].componentType;
    sets.push_back(std::move(set));
  }
  return sets;
}

// Why a fix could not write this file back faithfully, or "" when it can: compressed data is decoded when
// read, and writing it back uncompressed or re-encoding it is not what a fix should silently do.
std::string why_not_rewritable(const tinygltf::Model& model) {
  for (const std::string& e : model.extensionsUsed)
    if (e == "EXT_meshopt_compression" || e == "KHR_draco_mesh_compression")
      return "it uses " + e + ", which --fix does not write back";
  return "";
}

}  // namespace

SkinData read_skin_data(const std::string& path, const LoadOptions& options) {
  const std::vector<uint8_t> bytes = read_regular_file(path, std::min(options.max_file_bytes, options.max_memory));
  if (bytes.empty()) throw InputError("the file is empty");
  ParsedModel parsed = parse_model(bytes, folder_of(path), options);
  tinygltf::Model& m = parsed.model;
  SkinData data;
  data.why_not = why_not_rewritable(m);
  data.rewritable = data.why_not.empty();
  AnimationOrigins origins;
  data.structure = read_structure(m, parsed.json_bytes, path, options, &origins);
  // The loader's one mesh-level reason not to deform (mesh.cpp), which read_structure does not read: a
  // skinned node's primitive without influences. lint reports it as cannot-deform, in the same words.
  for (size_t n = 0; n < data.structure.nodes.size(); ++n) {
    const Node& node = data.structure.nodes[n];
    if (node.mesh < 0 || node.skin < 0) continue;
    const std::vector<tinygltf::Primitive>& primitives = m.meshes[size_t(node.mesh)].primitives;
    for (size_t k = 0; k < primitives.size(); ++k)
      if (highest_influence_set(primitives[k]) < 0)
        data.structure.cannot_deform.push_back(no_influences_reason(n, node.mesh, k));
  }
  const Asset& asset = data.structure;
  const AccessorReader reader{m, options.max_unbacked_elements};
  // What the raw sets may take besides what loading the structure took (primitives may share accessors,
  // so the file's size says nothing about it): the rest of --max-memory after the file and its model.
  const uint64_t used = uint64_t(bytes.size()) * 2 + parsed.json_bytes;
  uint64_t memory_left = options.max_memory > used ? options.max_memory - used : 0;

  std::vector<std::vector<int>> mesh_skins(m.meshes.size());
  for (const Node& node : asset.nodes)
    if (node.mesh >= 0 && node.skin >= 0) mesh_skins[size_t(node.mesh)].push_back(node.skin);
  for (size_t i = 0; i < m.meshes.size(); ++i) {
    std::vector<int>& skins = mesh_skins[i];
    std::sort(skins.begin(), skins.end());
    skins.erase(std::unique(skins.begin(), skins.end()), skins.end());
    for (size_t k = 0; k < m.meshes[i].primitives.size(); ++k) {
      const tinygltf::Primitive& p = m.meshes[i].primitives[k];
      const std::string what = "mesh " + std::to_string(i) + " primitive " + std::to_string(k);
      if (highest_influence_set(p) < 0) continue;
      const int position = find_attribute(p.attributes, "POSITION");
      if (position < 0) throw InputError(what + ": has no POSITION");
      SkinnedPrimitive prim;
      prim.mesh = i;
      prim.primitive = k;
      // KHR_mesh_quantization allows every component type for POSITION; the reader decodes each.
      const std::vector<float> xyz = reader.floats(
          position,
          {{TINYGLTF_TYPE_VEC3}, {kComponentFloat, 5120, kComponentUnsignedByte, 5122, kComponentUnsignedShort}},
          what + " POSITION");
      prim.vertices = xyz.size() / 3;
      if (uint64_t(prim.vertices) * sizeof(glm::vec3) > memory_left)
        throw InputError(what + ": its positions need more memory than --max-memory allows");
      memory_left -= uint64_t(prim.vertices) * sizeof(glm::vec3);
      prim.positions.resize(prim.vertices);
      for (size_t v = 0; v < prim.vertices; ++v) prim.positions[v] = {xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]};
      prim.sets = read_sets(p, reader, prim.vertices, what, memory_left);
      prim.skins = skins;
      data.primitives.push_back(std::move(prim));
    }
  }

  // The rotation channels of the clips, with the sampler each reads in the file (channels without a node,
  // pointers to other properties and duplicates are not in the clips).
  for (size_t a = 0; a < origins.channels.size(); ++a)
    for (size_t c = 0; c < origins.channels[a].size(); ++c) {
      if (asset.clips[a].channels[c].path != TargetPath::kRotation) continue;
      const ChannelOrigin& from = origins.channels[a][c];
      const int output = m.animations[a].samplers[from.sampler].output;
      data.rotations.push_back({a, c, a, from.sampler, m.accessors[size_t(output)].componentType});
    }
  data.duplicate_channels = std::move(origins.duplicates);
  return data;
}

}  // namespace dqskin::gltf
