// Writing a glTF file back as one .glb with replaced skin data (fixed_glb.hpp), from the document and BIN
// chunk of source_glb.hpp; the container is asset/glb_container.hpp, which every .glb writer shares.
#include "fixed_glb.hpp"

#include "../asset/glb_container.hpp"
#include "dqskin/error.hpp"
#include "skin_data.hpp"
#include "source_glb.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace dqskin::gltf {
namespace {

using nlohmann::json;

template <typename T>
void put(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

// A VEC4 accessor of `count` elements, component i being value(i) (stored as `component`, normalized for
// integer weights and rotations), in a view of its own. Integers are rounded from value × the type's
// largest value (§3.11 "Animations"). The bytes are written straight from the edit, with no copy of it as
// doubles: a rewrite of millions of vertices then takes about the output's size.
template <typename Value>
int vec4_accessor(glb::BinWriter& bin, size_t count, const Value& value, int component, bool normalized, int target) {
  const size_t size = component == 5120 || component == kComponentUnsignedByte ? 1
                      : component == 5122 || component == kComponentUnsignedShort ? 2
                                                                                  : 4;
  std::string bytes;
  bytes.reserve(count * 4 * size);
  for (size_t i = 0; i < count * 4; ++i) {
    const double v = value(i);
    switch (component) {
      case 5120: put(bytes, int8_t(std::clamp(std::lround(v * 127), -127L, 127L))); break;
      case kComponentUnsignedByte:
        put(bytes, uint8_t(std::clamp(std::lround(normalized ? v * 255 : v), 0L, 255L)));
        break;
      case 5122: put(bytes, int16_t(std::clamp(std::lround(v * 32767), -32767L, 32767L))); break;
      case kComponentUnsignedShort:
        put(bytes, uint16_t(std::clamp(std::lround(normalized ? v * 65535 : v), 0L, 65535L)));
        break;
      default: put(bytes, float(v)); break;
    }
  }
  const int view = bin.view(bytes.data(), bytes.size(), target);
  json a = {{"bufferView", view}, {"componentType", component}, {"count", count}, {"type", "VEC4"}};
  if (normalized && component != kComponentFloat) a["normalized"] = true;
  bin.accessors.push_back(std::move(a));
  return int(bin.accessors.size()) - 1;
}

bool is_influence_attribute(const std::string& name) {
  return name.rfind("JOINTS_", 0) == 0 || name.rfind("WEIGHTS_", 0) == 0;
}

}  // namespace

std::string fixed_glb(const std::string& path, const LoadOptions& options, const FileEdits& edits) {
  SourceGlb source = open_source_glb(path, options, "--fix");
  json& doc = source.doc;
  glb::BinWriter& bin = source.bin;

  for (const InfluenceEdit& e : edits.influences) {
    json& attributes = doc["meshes"][e.mesh]["primitives"][e.primitive]["attributes"];
    std::vector<std::string> old;
    for (const auto& item : attributes.items())
      if (is_influence_attribute(item.key())) old.push_back(item.key());
    for (const std::string& name : old) attributes.erase(name);
    for (size_t s = 0; s < e.sets; ++s) {
      // Element i of set s: vertex i / 4, slot i % 4 of that set (the edit holds every set of a vertex together).
      auto at = [&](size_t i) { return (i / 4 * e.sets + s) * 4 + i % 4; };
      attributes["JOINTS_" + std::to_string(s)] = vec4_accessor(
          bin, e.vertices, [&](size_t i) { return double(e.joints[at(i)]); }, e.joints_component, false,
          glb::kArrayBuffer);
      attributes["WEIGHTS_" + std::to_string(s)] =
          vec4_accessor(bin, e.vertices, [&](size_t i) { return e.weights[at(i)]; }, e.weights_component,
                        e.weights_component != kComponentFloat, glb::kArrayBuffer);
    }
  }
  for (const KeyEdit& e : edits.keys)
    doc["animations"][e.animation]["samplers"][e.sampler]["output"] =
        vec4_accessor(bin, e.values.size() / 4, [&](size_t i) { return double(e.values[i]); }, e.component,
                      e.component != kComponentFloat, 0);

  for (size_t skin : edits.drop_skeleton) doc["skins"][skin].erase("skeleton");
  // Last to first, so that the indices still to be removed stay valid. Their samplers and accessors stay
  // (the validator lists them as unused, an info), so that no index elsewhere changes.
  std::vector<std::pair<size_t, size_t>> channels = edits.drop_channels;
  std::sort(channels.begin(), channels.end());
  channels.erase(std::unique(channels.begin(), channels.end()), channels.end());
  for (auto it = channels.rbegin(); it != channels.rend(); ++it) doc["animations"][it->first]["channels"].erase(it->second);

  return glb::finish_glb(std::move(doc), std::move(bin), source.required, source.own);
}

}  // namespace dqskin::gltf
