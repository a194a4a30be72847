// Writing a glTF file back as one .glb with replaced skin data (fixed_glb.hpp). The JSON document is the
// one the file was read from (ParsedModel::doc); buffers are concatenated into the BIN chunk (glTF 2.0
// §4.4: a .glb has one buffer, the BIN chunk, buffer 0 without uri) with every bufferView moved by its
// buffer's offset there; the container is asset/glb_container.hpp, which every .glb writer shares.
#include "fixed_glb.hpp"

#include "../asset/glb_container.hpp"
#include "dqskin/error.hpp"
#include "model_io.hpp"
#include "skin_data.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace dqskin::gltf {
namespace {

using nlohmann::json;

// An image's MIME type (§5.17 requires one for an image in a bufferView): as declared, from a data: URI,
// or from the bytes' signature (PNG and JPEG for core glTF; WebP and KTX2 for EXT_texture_webp and
// KHR_texture_basisu).
std::string mime_type(const json& image, const std::vector<unsigned char>& bytes) {
  if (image.contains("mimeType") && image["mimeType"].is_string()) return image["mimeType"].get<std::string>();
  const std::string uri = image.value("uri", std::string());
  if (uri.rfind("data:", 0) == 0) {
    const size_t end = uri.find_first_of(";,");
    if (end != std::string::npos && end > 5) return uri.substr(5, end - 5);
  }
  auto starts = [&](const char* magic, size_t n, size_t at = 0) {
    return bytes.size() >= at + n && std::memcmp(bytes.data() + at, magic, n) == 0;
  };
  if (starts("\x89PNG", 4)) return "image/png";
  if (starts("\xFF\xD8\xFF", 3)) return "image/jpeg";
  if (starts("RIFF", 4) && starts("WEBP", 4, 8)) return "image/webp";
  if (starts("\xABKTX 20\xBB", 8)) return "image/ktx2";
  throw InputError("image " + image.value("name", std::string()) + " has no MIME type that --fix can name");
}

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
  const std::vector<uint8_t> bytes = read_regular_file(path, std::min(options.max_file_bytes, options.max_memory));
  ParsedModel parsed = parse_model(bytes, folder_of(path), options);
  const tinygltf::Model& m = parsed.model;
  json doc = std::move(parsed.doc);
  std::vector<std::string> own;
  for (const std::string& e : m.extensionsUsed) {
    if (e == "EXT_meshopt_compression" || e == "KHR_draco_mesh_compression")
      throw InputError("it uses " + e + ", which --fix does not write back");
    if (e == "KHR_mesh_quantization") own.push_back(e);  // named by no extensions object, but still needed
  }
  if (m.buffers.size() != doc.value("buffers", json::array()).size())
    throw InputError("its buffers could not all be read");

  glb::BinWriter bin;
  std::vector<size_t> base;
  for (const tinygltf::Buffer& b : m.buffers) {
    bin.bytes.resize((bin.bytes.size() + 3) & ~size_t(3), '\0');
    base.push_back(bin.bytes.size());
    bin.bytes.append(reinterpret_cast<const char*>(b.data.data()), b.data.size());
  }
  bin.views = doc.value("bufferViews", json::array());
  for (json& v : bin.views) {
    const size_t buffer = v.value("buffer", size_t(0));
    v["byteOffset"] = base.at(buffer) + v.value("byteOffset", size_t(0));
    v["buffer"] = 0;
  }
  bin.accessors = doc.value("accessors", json::array());

  if (doc.contains("images"))
    for (size_t i = 0; i < doc["images"].size(); ++i) {
      json& image = doc["images"][i];
      if (!image.contains("uri")) continue;
      const std::vector<unsigned char>& data = i < m.images.size() ? m.images[i].image : std::vector<unsigned char>();
      if (data.empty()) throw InputError("image " + std::to_string(i) + " could not be read, so it cannot be embedded");
      image["mimeType"] = mime_type(image, data);
      image["bufferView"] = bin.view(data.data(), data.size(), 0);
      image.erase("uri");
    }

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

  std::vector<std::string> required;
  for (const std::string& e : m.extensionsRequired)
    if (std::find(own.begin(), own.end(), e) == own.end()) required.push_back(e);
  doc.erase("buffers");
  return glb::finish_glb(std::move(doc), std::move(bin), required, own);
}

}  // namespace dqskin::gltf
