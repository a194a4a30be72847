#include "precheck.hpp"

#include "dqskin/error.hpp"

#include <nlohmann/json.hpp>

#include <cstring>
#include <string>

namespace dqskin::gltf {
namespace {

[[noreturn]] void fail(const std::string& message) { throw InputError(message); }

uint32_t le32(const uint8_t* p) { return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24; }

// A non-negative integer property, or `fallback` when absent. Anything else is an error.
uint64_t count_property(const nlohmann::json& object, const char* key, uint64_t fallback, const std::string& what) {
  const auto it = object.find(key);
  if (it == object.end()) return fallback;
  if (!it->is_number_unsigned() && !(it->is_number_integer() && it->get<int64_t>() >= 0))
    fail(what + ": " + key + " must be a non-negative integer");
  return it->get<uint64_t>();
}

}  // namespace

std::span<const uint8_t> json_chunk(std::span<const uint8_t> bytes, bool glb) {
  if (!glb) return bytes;
  // Header: magic, version, length; then chunks of (length, type, data) with 4-byte alignment.
  if (bytes.size() < 20) fail("GLB is truncated: " + std::to_string(bytes.size()) + " bytes, shorter than its header");
  const uint32_t version = le32(&bytes[4]), length = le32(&bytes[8]);
  if (version != 2) fail("GLB version " + std::to_string(version) + ", but glTF 2.0 needs version 2");
  if (length > bytes.size())
    fail("GLB is truncated: its header gives a length of " + std::to_string(length) + " bytes, the file has " +
         std::to_string(bytes.size()));
  const uint32_t json_length = le32(&bytes[12]);
  if (std::memcmp(&bytes[16], "JSON", 4) != 0) fail("GLB does not start with a JSON chunk");
  if (json_length > length - 20)
    fail("GLB JSON chunk of " + std::to_string(json_length) + " bytes runs past the GLB length (" + std::to_string(length) + ")");
  size_t next = 20 + size_t(json_length);
  next = (next + 3) & ~size_t(3);
  if (next + 8 <= length) {
    const uint32_t chunk_length = le32(&bytes[next]);
    if (chunk_length > length - next - 8)
      fail("GLB chunk at byte " + std::to_string(next) + " (" + std::to_string(chunk_length) +
           " bytes) runs past the GLB length (" + std::to_string(length) + ")");
  }
  return bytes.subspan(20, json_length);
}

void precheck_json(std::span<const uint8_t> text, uint64_t max_buffer_bytes) {
  const nlohmann::json doc = nlohmann::json::parse(text.begin(), text.end(), nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) return;  // tinygltf reports malformed JSON in its words

  const auto asset = doc.find("asset");
  if (asset == doc.end() || !asset->is_object()) fail("no asset object (glTF 2.0 requires asset.version)");
  const auto version = asset->find("version");
  if (version == asset->end() || !version->is_string()) fail("asset.version is missing");
  const std::string v = version->get<std::string>();
  if (v.rfind("2.", 0) != 0) fail("asset.version is " + v + ", but dqskin reads glTF 2.x");
  if (const auto min = asset->find("minVersion"); min != asset->end()) {
    if (!min->is_string() || min->get<std::string>() != "2.0")
      fail("asset.minVersion is " + min->dump() + ", newer than the glTF 2.0 dqskin reads");
  }

  std::vector<uint64_t> buffer_lengths;
  if (const auto buffers = doc.find("buffers"); buffers != doc.end() && buffers->is_array()) {
    for (size_t i = 0; i < buffers->size(); ++i) {
      const std::string what = "buffer " + std::to_string(i);
      if (!(*buffers)[i].is_object()) fail(what + ": is not an object");
      const uint64_t length = count_property((*buffers)[i], "byteLength", 0, what);
      if (length == 0) fail(what + ": byteLength must be at least 1");
      if (length > max_buffer_bytes)
        fail(what + ": byteLength " + std::to_string(length) + " is more than dqskin reads (" +
             std::to_string(max_buffer_bytes) + ")");
      buffer_lengths.push_back(length);
    }
  }
  size_t view_count = 0;
  if (const auto views = doc.find("bufferViews"); views != doc.end() && views->is_array()) {
    view_count = views->size();
    for (size_t i = 0; i < views->size(); ++i) {
      const std::string what = "bufferView " + std::to_string(i);
      const nlohmann::json& view = (*views)[i];
      if (!view.is_object()) fail(what + ": is not an object");
      const uint64_t buffer = count_property(view, "buffer", UINT64_MAX, what);
      if (buffer >= buffer_lengths.size()) fail(what + ": buffer does not exist");
      const uint64_t offset = count_property(view, "byteOffset", 0, what);
      const uint64_t length = count_property(view, "byteLength", 0, what);
      if (length == 0) fail(what + ": byteLength must be at least 1");
      if (offset > buffer_lengths[buffer] || length > buffer_lengths[buffer] - offset)
        fail(what + " (offset " + std::to_string(offset) + ", length " + std::to_string(length) +
             ") runs past the end of buffer " + std::to_string(buffer) + " (" + std::to_string(buffer_lengths[buffer]) +
             " bytes)");
    }
  }
  if (const auto images = doc.find("images"); images != doc.end() && images->is_array()) {
    for (size_t i = 0; i < images->size(); ++i) {
      const std::string what = "image " + std::to_string(i);
      if (!(*images)[i].is_object()) fail(what + ": is not an object");
      const uint64_t view = count_property((*images)[i], "bufferView", UINT64_MAX, what);
      if (view != UINT64_MAX && view >= view_count) fail(what + ": bufferView " + std::to_string(view) + " does not exist");
    }
  }
}

}  // namespace dqskin::gltf
