// Opening a glTF file for writing back as one .glb (source_glb.hpp).
#include "source_glb.hpp"

#include "dqskin/error.hpp"
#include "model_io.hpp"

#include <algorithm>
#include <cstring>

namespace dqskin::gltf {
namespace {

using nlohmann::json;

// An image's MIME type (§5.17 requires one for an image in a bufferView): as declared, from a data: URI,
// or from the bytes' signature (PNG and JPEG for core glTF; WebP and KTX2 for EXT_texture_webp and
// KHR_texture_basisu).
std::string mime_type(const json& image, const std::vector<unsigned char>& bytes, const std::string& who) {
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
  throw InputError("image " + image.value("name", std::string()) + " has no MIME type that " + who + " can name");
}

}  // namespace

SourceGlb open_source_glb(const std::string& path, const LoadOptions& options, const std::string& who) {
  const std::vector<uint8_t> bytes = read_regular_file(path, std::min(options.max_file_bytes, options.max_memory));
  ParsedModel parsed = parse_model(bytes, folder_of(path), options);
  const tinygltf::Model& m = parsed.model;
  json doc = std::move(parsed.doc);
  std::vector<std::string> own;
  for (const std::string& e : m.extensionsUsed) {
    if (e == "EXT_meshopt_compression" || e == "KHR_draco_mesh_compression")
      throw InputError("it uses " + e + ", which " + who + " does not write back");
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
      image["mimeType"] = mime_type(image, data, who);
      image["bufferView"] = bin.view(data.data(), data.size(), 0);
      image.erase("uri");
    }

  std::vector<std::string> required;
  for (const std::string& e : m.extensionsRequired)
    if (std::find(own.begin(), own.end(), e) == own.end()) required.push_back(e);
  doc.erase("buffers");
  return {std::move(doc), std::move(bin), std::move(required), std::move(own)};
}

}  // namespace dqskin::gltf
