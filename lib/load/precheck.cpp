#include "precheck.hpp"

#include "../base/byte_size.hpp"
#include "dqskin/error.hpp"
#include "../base/saturating.hpp"
#include "meshopt.hpp"
#include "schema_values.hpp"

#include <cstring>
#include <string>

namespace dqskin::gltf {
namespace {

[[noreturn]] void fail(const std::string& message) { throw InputError(message); }

uint32_t le32(const uint8_t* p) { return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24; }

bool is_data_uri(const std::string& uri) { return uri.rfind("data:", 0) == 0; }

}  // namespace

std::span<const uint8_t> json_chunk(std::span<const uint8_t> bytes, bool glb) {
  if (!glb) return bytes;
  // §4.4: a 12-byte header (magic, version, length), then chunks of (length, type, data), each 4-byte
  // aligned; the first is JSON. Every size read here is checked against what the file holds before it is
  // used, and every subtraction is of a smaller number, so nothing can wrap around.
  constexpr size_t kHeader = 12, kChunkHeader = 8, kFirstChunkData = kHeader + kChunkHeader;
  if (bytes.size() < kFirstChunkData)
    fail("GLB is truncated: " + std::to_string(bytes.size()) + " bytes, shorter than its header");
  const uint32_t version = le32(&bytes[4]), length = le32(&bytes[8]);
  if (version != 2) fail("GLB version " + std::to_string(version) + ", but glTF 2.0 needs version 2");
  if (length < kFirstChunkData)
    fail("GLB header gives a length of " + std::to_string(length) + " bytes, less than its headers (" +
         std::to_string(kFirstChunkData) + ")");
  if (length > bytes.size())
    fail("GLB is truncated: its header gives a length of " + std::to_string(length) + " bytes, the file has " +
         std::to_string(bytes.size()));
  const uint32_t json_length = le32(&bytes[12]);
  if (std::memcmp(&bytes[16], "JSON", 4) != 0) fail("GLB does not start with a JSON chunk");
  if (json_length > length - kFirstChunkData)
    fail("GLB JSON chunk of " + std::to_string(json_length) + " bytes runs past the GLB length (" + std::to_string(length) + ")");
  // §4.4.3.1: chunks end 4-byte aligned (the JSON chunk padded with spaces). tinygltf looks for the next
  // chunk right after an unpadded one and would read its header past the length it checked.
  if (json_length % 4 != 0)
    fail("GLB JSON chunk of " + std::to_string(json_length) + " bytes is not padded to a multiple of 4");
  const size_t next = kFirstChunkData + size_t(json_length);
  if (next <= length && length - next >= kChunkHeader) {
    const uint32_t chunk_length = le32(&bytes[next]);
    if (chunk_length > length - next - kChunkHeader)
      fail("GLB chunk at byte " + std::to_string(next) + " (" + std::to_string(chunk_length) +
           " bytes) runs past the GLB length (" + std::to_string(length) + ")");
  }
  return bytes.subspan(kFirstChunkData, json_length);
}

JsonShape scan_json(std::span<const uint8_t> json) {
  JsonShape shape;
  size_t depth = 0;
  bool in_string = false, escaped = false;
  bool opened = false;  // just after '[' or '{': what follows is a first value, or the closing bracket
  for (size_t i = 0; i < json.size(); ++i) {
    const uint8_t c = json[i];
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
      continue;
    }
    if (c == ' ' || c == '\n' || c == '\r' || c == '\t') continue;
    if (opened && c != ']' && c != '}') ++shape.values;  // the first element or member
    opened = false;
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        fail("its JSON nests arrays and objects more than " + std::to_string(kMaxJsonDepth) + " deep (at byte " +
             std::to_string(i) + ")");
      shape.objects += c == '{';
      opened = true;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;  // unbalanced text is the JSON parser's to report
    } else if (c == ',') {
      ++shape.values;
    }
  }
  return shape;
}

uint64_t json_memory(const JsonShape& shape, uint64_t text_bytes) {
  using saturating::add;
  using saturating::mul;
  return add(add(mul(shape.values, 320), mul(shape.objects, 700)), mul(text_bytes, 2));
}

CheckedJson precheck_json(std::span<const uint8_t> text, const LoadOptions& options, const ResourceRoot& root,
                          bool glb) {
  const JsonShape shape = scan_json(text);
  CheckedJson out;
  out.json_bytes = json_memory(shape, text.size());
  if (out.json_bytes > options.max_memory)
    fail("its JSON (" + byte_size(text.size()) + ", " + std::to_string(shape.values) + " values) takes about " +
         byte_size(out.json_bytes) + " to parse, more than --max-memory " + byte_size(options.max_memory));
  nlohmann::json doc = nlohmann::json::parse(text.begin(), text.end(), nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) return out;  // tinygltf reports malformed JSON in its words

  const auto asset = doc.find("asset");
  if (asset == doc.end() || !asset->is_object()) fail("no asset object (glTF 2.0 requires asset.version)");
  const auto version = asset->find("version");
  if (version == asset->end() || !version->is_string()) fail("asset.version is missing");
  const std::string v = version->get<std::string>();
  if (v.rfind("2.", 0) != 0) fail("asset.version is " + v + ", but dqskin reads glTF 2.x");
  if (const auto min = asset->find("minVersion"); min != asset->end()) {
    if (!min->is_string() || min->get<std::string>() != "2.0")
      fail("asset.minVersion is " + min->dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) +
           ", newer than the glTF 2.0 dqskin reads");
  }

  out.warnings = check_schema_values(doc);
  out.changed = !out.warnings.empty();

  // Sizes and offsets are integers in range now (check_schema_values); what is left is how they fit.
  auto size_of = [&doc](const char* array, size_t i, const char* key, uint64_t fallback) {
    const nlohmann::json& object = doc[array][i];
    return object.contains(key) ? object[key].get<uint64_t>() : fallback;
  };
  auto array_size = [&doc](const char* key) {
    const auto it = doc.find(key);
    return it != doc.end() && it->is_array() ? it->size() : size_t(0);
  };
  auto object_at = [&doc](const char* array, size_t i, const std::string& what) -> const nlohmann::json& {
    if (!doc[array][i].is_object()) fail(what + ": is not an object");
    return doc[array][i];
  };

  // tinygltf decodes '+' in a URI as a space (form encoding); RFC 3986 and glTF mean a plus sign.
  auto keep_plus = [&out](nlohmann::json& object) {
    const auto uri = object.find("uri");
    if (uri == object.end() || !uri->is_string() || is_data_uri(uri->get<std::string>())) return;
    std::string u = uri->get<std::string>();
    for (size_t at; (at = u.find('+')) != std::string::npos;) u.replace(at, 1, "%2B");
    if (u != uri->get<std::string>()) *uri = u, out.changed = true;
  };

  std::vector<uint64_t> buffer_lengths;
  for (size_t i = 0; i < array_size("buffers"); ++i) object_at("buffers", i, "buffer " + std::to_string(i));
  out.dataless = dataless_buffers(doc, glb);
  for (size_t i = 0; i < array_size("buffers"); ++i) {
    const std::string what = "buffer " + std::to_string(i);
    const nlohmann::json& buffer = doc["buffers"][i];
    const uint64_t length = size_of("buffers", i, "byteLength", 0);
    if (length == 0) fail(what + ": byteLength must be at least 1");
    buffer_lengths.push_back(length);
    if (out.dataless[i]) continue;  // not read: its views are decoded from other buffers, and counted there
    if (length > options.max_file_bytes)
      fail(what + ": byteLength " + std::to_string(length) + " is more than dqskin reads (" +
           std::to_string(options.max_file_bytes) + ")");
    out.data_bytes = saturating::add(out.data_bytes, length);  // decoded, read or copied out of the GLB once
    if (const auto uri = buffer.find("uri"); uri != buffer.end() && uri->is_string()) {
      const std::string u = uri->get<std::string>();
      if (!is_data_uri(u) && !root.check(u, what)) fail(what + " uri '" + u + "': no such file beside the model");
    }
    keep_plus(doc["buffers"][i]);
  }
  const size_t view_count = array_size("bufferViews");
  for (size_t i = 0; i < view_count; ++i) {
    const std::string what = "bufferView " + std::to_string(i);
    object_at("bufferViews", i, what);
    const uint64_t buffer = size_of("bufferViews", i, "buffer", UINT64_MAX);
    if (buffer >= buffer_lengths.size()) fail(what + ": buffer does not exist");
    const uint64_t offset = size_of("bufferViews", i, "byteOffset", 0);
    const uint64_t length = size_of("bufferViews", i, "byteLength", 0);
    if (length == 0) fail(what + ": byteLength must be at least 1");
    if (offset > buffer_lengths[buffer] || length > buffer_lengths[buffer] - offset)
      fail(what + " (offset " + std::to_string(offset) + ", length " + std::to_string(length) +
           ") runs past the end of buffer " + std::to_string(buffer) + " (" + std::to_string(buffer_lengths[buffer]) +
           " bytes)");
    out.decoded_bytes = saturating::add(out.decoded_bytes, check_meshopt_view(doc, i, buffer_lengths, out.dataless));
  }
  // tinygltf reads every buffer (meshopt.hpp): a dataless one gets a byte that nothing reads.
  for (size_t i = 0; i < out.dataless.size(); ++i) {
    if (!out.dataless[i]) continue;
    nlohmann::json& buffer = doc["buffers"][i];
    buffer["byteLength"] = 1;
    buffer["uri"] = "data:application/octet-stream;base64,AA==";
    out.changed = true;
  }
  // §3.6.2.4: an accessor's offset into its view, and into its buffer, is a multiple of its component size
  // (typed-array readers such as WebGL's depend on it).
  for (size_t i = 0; i < array_size("accessors"); ++i) {
    const nlohmann::json& accessor = object_at("accessors", i, "accessor " + std::to_string(i));
    const uint64_t view = size_of("accessors", i, "bufferView", UINT64_MAX);
    const auto type = accessor.find("componentType");
    if (view >= view_count || type == accessor.end()) continue;
    const int64_t t = type->get<int64_t>();
    const uint64_t size = t == 5120 || t == 5121 ? 1 : t == 5122 || t == 5123 ? 2 : 4;
    const uint64_t offset = size_of("accessors", i, "byteOffset", 0);
    const uint64_t in_buffer = offset + size_of("bufferViews", size_t(view), "byteOffset", 0);
    if (offset % size != 0 || in_buffer % size != 0)
      fail("accessor " + std::to_string(i) + ": starts at byte " + std::to_string(offset) + " of bufferView " +
           std::to_string(view) + " (byte " + std::to_string(in_buffer) + " of its buffer), not a multiple of " +
           std::to_string(size) + ", the size of its components");
  }
  // tinygltf 2.7 refuses a primitive's indices accessor without bufferView, which KHR_draco_mesh_compression
  // prescribes: tinygltf gets the Draco view for it, and parse_model takes it away again (draco.hpp).
  for (size_t m = 0; m < array_size("meshes"); ++m) {
    const nlohmann::json& mesh = doc["meshes"][m];
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (size_t pi = 0; pi < mesh["primitives"].size(); ++pi) {
      const nlohmann::json& p = mesh["primitives"][pi];
      if (!p.is_object() || !p.contains("indices") || !p.contains("extensions") || !p["extensions"].is_object()) continue;
      const auto draco = p["extensions"].find("KHR_draco_mesh_compression");
      if (draco == p["extensions"].end() || !draco->is_object() || !draco->contains("bufferView")) continue;
      const nlohmann::json& view_value = (*draco)["bufferView"];
      if (!view_value.is_number_unsigned() || !p["indices"].is_number_unsigned()) continue;  // decode_draco reports it
      const uint64_t view = view_value.get<uint64_t>(), indices = p["indices"].get<uint64_t>();
      // Said here: tinygltf would otherwise report the indices accessor's view, which the file does not have.
      if (view >= view_count)
        fail("mesh " + std::to_string(m) + " primitive " + std::to_string(pi) +
             ": KHR_draco_mesh_compression bufferView " + std::to_string(view) + " does not exist");
      if (indices >= array_size("accessors") || !doc["accessors"][indices].is_object() ||
          doc["accessors"][indices].contains("bufferView"))
        continue;
      doc["accessors"][indices]["bufferView"] = view;
      out.unviewed_indices.push_back(size_t(indices));
      out.changed = true;
    }
  }
  // Images: each is copied once (from its buffer view, its data URI or its file). One whose URI leaves the
  // root is not read, like a missing one: the renderer then has no texture, bake drops it from its glbs.
  for (size_t i = 0; i < array_size("images"); ++i) {
    const std::string what = "image " + std::to_string(i);
    const nlohmann::json& image = object_at("images", i, what);
    const uint64_t view = size_of("images", i, "bufferView", UINT64_MAX);
    if (view != UINT64_MAX && view >= view_count) fail(what + ": bufferView " + std::to_string(view) + " does not exist");
    if (view != UINT64_MAX) {
      // tinygltf copies the image out of its view while it parses, before any view is decoded.
      const uint64_t buffer = size_of("bufferViews", size_t(view), "buffer", 0);
      if (buffer < out.dataless.size() && out.dataless[buffer])
        fail(what + ": bufferView " + std::to_string(view) + " is EXT_meshopt_compression data without a fallback; " +
             "dqskin reads images only from uncompressed views");
      out.data_bytes = saturating::add(out.data_bytes, size_of("bufferViews", size_t(view), "byteLength", 0));
    }
    const auto uri = image.find("uri");
    if (uri == image.end() || !uri->is_string()) continue;
    const std::string u = uri->get<std::string>();
    if (is_data_uri(u)) {
      out.data_bytes = saturating::add(out.data_bytes, u.size());
      continue;
    }
    try {
      if (root.check(u, what)) out.data_bytes = saturating::add(out.data_bytes, root.size_of(u));
    } catch (const InputError& e) {
      out.warnings.push_back(std::string(e.what()) + "; textures using it are not drawn");
    }
    keep_plus(doc["images"][i]);
  }
  const uint64_t total = saturating::add(saturating::add(out.json_bytes, out.data_bytes), out.decoded_bytes);
  if (total > options.max_memory)
    fail("reading it needs about " + byte_size(total) + " (" + byte_size(out.data_bytes) + " of buffers and images, " +
         (out.decoded_bytes ? byte_size(out.decoded_bytes) + " of EXT_meshopt_compression views decoded, " : std::string()) +
         byte_size(out.json_bytes) + " for its JSON), more than --max-memory " + byte_size(options.max_memory));
  out.doc = std::move(doc);
  return out;
}

}  // namespace dqskin::gltf
