// Writing a glTF file back as one .glb with new animation samplers, and what they replace removed
// (animation_glb.hpp). The document and BIN chunk come from source_glb.hpp.
#include "animation_glb.hpp"

#include "source_glb.hpp"
#include "dqskin/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <set>

namespace dqskin::gltf {
namespace {

using nlohmann::json;

// Bytes of one component of `component_type` (§3.6.2.2); 4 for float and unsigned int.
size_t component_size(int component_type) {
  switch (component_type) {
    case 5120:
    case 5121: return 1;
    case 5122:
    case 5123: return 2;
    default: return 4;
  }
}

size_t type_components(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4" || type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

const char* type_name(int components) {
  switch (components) {
    case 1: return "SCALAR";
    case 2: return "VEC2";
    case 3: return "VEC3";
    default: return "VEC4";
  }
}

template <typename T>
void put(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

// An accessor of `values` (components per element) stored as `component_type`; integer types are
// normalized (§3.11: rotations and morph weights only) and rounded from value × the type's largest
// value. With `bounds`, its min and max, which a sampler's input must have (§3.11).
int write_accessor(glb::BinWriter& bin, const std::vector<float>& values, int components, int component_type,
                   bool bounds) {
  std::string bytes;
  bytes.reserve(values.size() * component_size(component_type));
  for (float v : values) {
    switch (component_type) {
      case 5120: put(bytes, int8_t(std::clamp(std::lround(double(v) * 127), -127L, 127L))); break;
      case 5121: put(bytes, uint8_t(std::clamp(std::lround(double(v) * 255), 0L, 255L))); break;
      case 5122: put(bytes, int16_t(std::clamp(std::lround(double(v) * 32767), -32767L, 32767L))); break;
      case 5123: put(bytes, uint16_t(std::clamp(std::lround(double(v) * 65535), 0L, 65535L))); break;
      default: put(bytes, v); break;
    }
  }
  const size_t count = values.size() / size_t(components);
  json a = {{"bufferView", bin.view(bytes.data(), bytes.size(), 0)},
            {"componentType", component_type},
            {"count", count},
            {"type", type_name(components)}};
  if (component_type != 5126) a["normalized"] = true;
  if (bounds && count > 0) {
    json lo = json::array(), hi = json::array();
    for (int c = 0; c < components; ++c) {
      float mn = values[size_t(c)], mx = mn;
      for (size_t i = 0; i < count; ++i) {
        mn = std::min(mn, values[i * size_t(components) + size_t(c)]);
        mx = std::max(mx, values[i * size_t(components) + size_t(c)]);
      }
      lo.push_back(mn);
      hi.push_back(mx);
    }
    a["min"] = lo;
    a["max"] = hi;
  }
  bin.accessors.push_back(std::move(a));
  return int(bin.accessors.size()) - 1;
}

// Bytes of the elements of the accessors animation samplers read, each counted once.
uint64_t animation_bytes(const json& doc, const json& accessors) {
  std::set<size_t> used;
  for (const json& animation : doc.value("animations", json::array()))
    for (const json& sampler : animation.value("samplers", json::array()))
      for (const char* key : {"input", "output"})
        if (sampler.contains(key) && (sampler[key].is_number_unsigned() || sampler[key].is_number_integer()))
          used.insert(sampler[key].get<size_t>());
  uint64_t bytes = 0;
  for (size_t a : used) {
    if (a >= accessors.size()) continue;
    const json& accessor = accessors[a];
    bytes += accessor.value("count", uint64_t(0)) * type_components(accessor.value("type", std::string())) *
             component_size(accessor.value("componentType", 5126));
  }
  return bytes;
}

// Extensions whose references to accessors and bufferViews are all known here (or that have none): with
// any other, unused data is kept, as that extension may use it.
bool references_are_known(const std::string& extension) {
  static const char* const kKnown[] = {"KHR_mesh_quantization", "KHR_texture_transform", "KHR_texture_basisu",
                                       "EXT_texture_webp", "KHR_lights_punctual", "KHR_materials_variants",
                                       "KHR_animation_pointer", "EXT_mesh_gpu_instancing", "KHR_xmp_json_ld"};
  if (extension.rfind("KHR_materials_", 0) == 0) return true;
  return std::any_of(std::begin(kKnown), std::end(kKnown), [&](const char* k) { return extension == k; });
}

// Whether `j` is an index: a whole number of at least 0 (parsed ones are unsigned, ones we set signed).
bool is_index(const json& j) { return j.is_number_unsigned() || (j.is_number_integer() && j.get<int64_t>() >= 0); }

// Calls `visit` with every reference to an accessor in `doc` (as a json number that may be rewritten).
template <typename Visit>
void for_each_accessor_reference(json& doc, const Visit& visit) {
  auto each = [&](json& holder, const char* key) {
    if (holder.is_object() && holder.contains(key) && is_index(holder[key])) visit(holder[key]);
  };
  if (doc.contains("meshes"))
    for (json& mesh : doc["meshes"])
      for (json& primitive : mesh["primitives"]) {
        each(primitive, "indices");
        if (primitive.contains("attributes"))
          for (auto& item : primitive["attributes"].items())
            if (is_index(item.value())) visit(item.value());
        if (primitive.contains("targets"))
          for (json& target : primitive["targets"])
            for (auto& item : target.items())
              if (is_index(item.value())) visit(item.value());
      }
  if (doc.contains("skins"))
    for (json& skin : doc["skins"]) each(skin, "inverseBindMatrices");
  if (doc.contains("animations"))
    for (json& animation : doc["animations"])
      for (json& sampler : animation["samplers"]) {
        each(sampler, "input");
        each(sampler, "output");
      }
  if (doc.contains("nodes"))
    for (json& node : doc["nodes"])
      if (node.contains("extensions") && node["extensions"].contains("EXT_mesh_gpu_instancing")) {
        json& instancing = node["extensions"]["EXT_mesh_gpu_instancing"];
        if (instancing.contains("attributes"))
          for (auto& item : instancing["attributes"].items())
            if (is_index(item.value())) visit(item.value());
      }
}

// Every reference to a bufferView: accessors (and their sparse parts) and images.
template <typename Visit>
void for_each_view_reference(json& doc, json& accessors, const Visit& visit) {
  for (json& accessor : accessors) {
    if (accessor.contains("bufferView") && is_index(accessor["bufferView"])) visit(accessor["bufferView"]);
    if (accessor.contains("sparse")) {
      json& sparse = accessor["sparse"];
      if (sparse.contains("indices") && sparse["indices"].contains("bufferView")) visit(sparse["indices"]["bufferView"]);
      if (sparse.contains("values") && sparse["values"].contains("bufferView")) visit(sparse["values"]["bufferView"]);
    }
  }
  if (doc.contains("images"))
    for (json& image : doc["images"])
      if (image.contains("bufferView") && is_index(image["bufferView"])) visit(image["bufferView"]);
}

// Removes the accessors and bufferViews nothing refers to, renumbering the references, and copies the
// views that stay into a new BIN chunk, each on a 4-byte boundary.
void remove_unused(json& doc, glb::BinWriter& bin) {
  std::vector<bool> used(bin.accessors.size(), false);
  for_each_accessor_reference(doc, [&](json& r) {
    const size_t a = r.get<size_t>();
    if (a < used.size()) used[a] = true;
  });
  std::vector<size_t> renumbered(used.size());
  json accessors = json::array();
  for (size_t a = 0; a < used.size(); ++a) {
    renumbered[a] = accessors.size();
    if (used[a]) accessors.push_back(std::move(bin.accessors[a]));
  }
  for_each_accessor_reference(doc, [&](json& r) { r = renumbered[r.get<size_t>()]; });

  std::vector<bool> view_used(bin.views.size(), false);
  for_each_view_reference(doc, accessors, [&](json& r) {
    const size_t v = r.get<size_t>();
    if (v < view_used.size()) view_used[v] = true;
  });
  glb::BinWriter out;
  std::vector<size_t> view_number(bin.views.size());
  for (size_t v = 0; v < bin.views.size(); ++v) {
    view_number[v] = out.views.size();
    if (!view_used[v]) continue;
    json view = std::move(bin.views[v]);
    const size_t offset = view.value("byteOffset", size_t(0)), length = view.value("byteLength", size_t(0));
    if (offset > bin.bytes.size() || length > bin.bytes.size() - offset)
      throw InputError("bufferView " + std::to_string(v) + " lies outside its buffer");
    out.bytes.resize((out.bytes.size() + 3) & ~size_t(3), '\0');
    view["byteOffset"] = out.bytes.size();
    out.bytes.append(bin.bytes, offset, length);
    out.views.push_back(std::move(view));
  }
  for_each_view_reference(doc, accessors, [&](json& r) { r = view_number[r.get<size_t>()]; });
  out.accessors = std::move(accessors);
  bin = std::move(out);
}

}  // namespace

AnimationGlb animation_glb(const std::string& path, const LoadOptions& options, const AnimationEdits& edits) {
  SourceGlb source = open_source_glb(path, options, "optimize");
  json& doc = source.doc;
  glb::BinWriter& bin = source.bin;
  AnimationGlb result;
  result.animation_bytes_before = animation_bytes(doc, bin.accessors);

  // Samplers with the same key times share one input accessor, as exporters write them.
  std::map<std::vector<float>, int> inputs;
  for (const SamplerEdit& e : edits.samplers) {
    json& sampler = doc["animations"][e.animation]["samplers"][e.sampler];
    const auto [it, added] = inputs.emplace(e.times, -1);
    if (added) it->second = write_accessor(bin, e.times, 1, 5126, true);
    sampler["input"] = it->second;
    sampler["output"] = write_accessor(bin, e.values, e.components, e.component, false);
    if (std::strcmp(e.interpolation, "LINEAR") == 0) sampler.erase("interpolation");  // the default (§5.10)
    else sampler["interpolation"] = e.interpolation;
  }

  // Channels dropped, last to first; then each animation's samplers that no channel uses, renumbered.
  std::vector<std::pair<size_t, size_t>> channels = edits.drop_channels;
  std::sort(channels.begin(), channels.end());
  channels.erase(std::unique(channels.begin(), channels.end()), channels.end());
  for (auto it = channels.rbegin(); it != channels.rend(); ++it) doc["animations"][it->first]["channels"].erase(it->second);
  if (doc.contains("animations"))
    for (json& animation : doc["animations"]) {
      json& samplers = animation["samplers"];
      std::vector<size_t> number(samplers.size(), SIZE_MAX);
      json kept = json::array();
      for (json& channel : animation["channels"]) {
        const size_t s = channel.value("sampler", size_t(0));
        if (s >= samplers.size()) continue;
        if (number[s] == SIZE_MAX) {
          number[s] = kept.size();
          kept.push_back(samplers[s]);
        }
        channel["sampler"] = number[s];
      }
      samplers = std::move(kept);
    }

  for (const std::string& e : doc.value("extensionsUsed", std::vector<std::string>()))
    if (!references_are_known(e) && result.kept_unused.empty())
      result.kept_unused = "it uses " + e + ", which may refer to data no sampler uses any more";
  if (result.kept_unused.empty()) remove_unused(doc, bin);

  result.animation_bytes_after = animation_bytes(doc, bin.accessors);
  result.glb = glb::finish_glb(std::move(doc), std::move(bin), source.required, source.own);
  return result;
}

}  // namespace dqskin::gltf
