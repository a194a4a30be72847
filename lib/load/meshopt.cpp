#include "meshopt.hpp"

#include "dqskin/error.hpp"

#include <meshoptimizer.h>

#include <cstdio>
#include <string>

namespace dqskin::gltf {
namespace {

using nlohmann::json;

constexpr const char* kName = "EXT_meshopt_compression";

[[noreturn]] void fail(const std::string& message) { throw InputError(message); }

// The extension object of `object`, or null when it has none.
const json* extension_of(const json& object) {
  if (!object.is_object()) return nullptr;
  const auto extensions = object.find("extensions");
  if (extensions == object.end() || !extensions->is_object()) return nullptr;
  const auto it = extensions->find(kName);
  return it == extensions->end() ? nullptr : &*it;
}

enum class Mode { kAttributes, kTriangles, kIndices };
enum class Filter { kNone, kOctahedral, kQuaternion, kExponential };

struct Compressed {
  uint64_t buffer = 0, offset = 0, length = 0, stride = 0, count = 0;
  Mode mode = Mode::kAttributes;
  Filter filter = Filter::kNone;
};

// The extension object of bufferView `view`, checked alone (check_schema_values has checked the integers'
// ranges where present).
Compressed read_extension(const json& ext, const std::string& what) {
  if (!ext.is_object()) fail(what + ": " + kName + " is not an object");
  auto integer = [&](const char* key, bool required) -> uint64_t {
    const auto it = ext.find(key);
    if (it == ext.end()) {
      if (required) fail(what + ": " + kName + "." + key + " is missing");
      return 0;
    }
    return it->get<uint64_t>();
  };
  Compressed c;
  c.buffer = integer("buffer", true);
  c.offset = integer("byteOffset", false);
  c.length = integer("byteLength", true);
  c.stride = integer("byteStride", true);
  c.count = integer("count", true);
  const auto mode = ext.find("mode");
  if (mode == ext.end()) fail(what + ": " + kName + ".mode is missing");
  const std::string m = mode->is_string() ? mode->get<std::string>() : std::string();
  if (m == "ATTRIBUTES") c.mode = Mode::kAttributes;
  else if (m == "TRIANGLES") c.mode = Mode::kTriangles;
  else if (m == "INDICES") c.mode = Mode::kIndices;
  else
    fail(what + ": " + kName + ".mode " + mode->dump(-1, ' ', false, json::error_handler_t::replace).substr(0, 40) +
         " must be \"ATTRIBUTES\", \"TRIANGLES\" or \"INDICES\"");
  if (const auto filter = ext.find("filter"); filter != ext.end()) {
    const std::string f = filter->is_string() ? filter->get<std::string>() : std::string();
    if (f == "NONE") c.filter = Filter::kNone;
    else if (f == "OCTAHEDRAL") c.filter = Filter::kOctahedral;
    else if (f == "QUATERNION") c.filter = Filter::kQuaternion;
    else if (f == "EXPONENTIAL") c.filter = Filter::kExponential;
    else
      fail(what + ": " + kName + ".filter " + filter->dump(-1, ' ', false, json::error_handler_t::replace).substr(0, 40) +
           " must be \"NONE\", \"OCTAHEDRAL\", \"QUATERNION\" or \"EXPONENTIAL\"");
  }
  return c;
}

const char* mode_name(Mode m) {
  return m == Mode::kAttributes ? "ATTRIBUTES" : m == Mode::kTriangles ? "TRIANGLES" : "INDICES";
}

const char* filter_name(Filter f) {
  return f == Filter::kOctahedral ? "OCTAHEDRAL" : f == Filter::kQuaternion ? "QUATERNION" : "EXPONENTIAL";
}

uint64_t member_or(const json& object, const char* key, uint64_t fallback) {
  const auto it = object.find(key);
  return it != object.end() && it->is_number_integer() ? it->get<uint64_t>() : fallback;
}

}  // namespace

std::vector<bool> dataless_buffers(const json& doc, bool glb) {
  std::vector<bool> out;
  const auto buffers = doc.find("buffers");
  if (buffers == doc.end() || !buffers->is_array()) return out;
  for (size_t i = 0; i < buffers->size(); ++i) {
    const json& buffer = (*buffers)[i];
    const json* ext = extension_of(buffer);
    // A fallback buffer is never read, even when it has a uri: the views that use it are decoded instead.
    const bool fallback = ext && ext->is_object() && ext->value("fallback", json(false)).is_boolean() &&
                          ext->value("fallback", false);
    const bool has_uri = buffer.is_object() && buffer.contains("uri");
    out.push_back(fallback || (!has_uri && !(glb && i == 0)));
  }
  return out;
}

uint64_t check_meshopt_view(const json& doc, size_t view, const std::vector<uint64_t>& buffer_lengths,
                            const std::vector<bool>& dataless) {
  const json& bv = doc["bufferViews"][view];
  const std::string what = "bufferView " + std::to_string(view);
  const uint64_t parent = member_or(bv, "buffer", UINT64_MAX);
  const json* ext = extension_of(bv);
  if (!ext) {
    if (parent < dataless.size() && dataless[parent])
      fail(what + ": buffer " + std::to_string(parent) + " has no data (an " + kName +
           " fallback, or no uri outside a .glb's first buffer), and the view is not compressed");
    return 0;
  }
  const Compressed c = read_extension(*ext, what);
  const uint64_t length = member_or(bv, "byteLength", 0);
  const std::string prefix = what + ": " + kName + " ";
  if (const uint64_t stride = member_or(bv, "byteStride", 0); stride != 0 && stride != c.stride)
    fail(prefix + "byteStride " + std::to_string(c.stride) + " differs from the view's byteStride " +
         std::to_string(stride));
  // Both at most 2^63 (check_schema_values) and the stride at most 256: the product cannot wrap.
  if (c.count > length || c.stride * c.count != length)
    fail(prefix + "holds " + std::to_string(c.count) + " elements of " + std::to_string(c.stride) +
         " bytes, but the view's byteLength is " + std::to_string(length));
  if (c.mode == Mode::kAttributes && c.stride % 4 != 0)
    fail(prefix + "byteStride " + std::to_string(c.stride) + " must be a multiple of 4 (up to 256) in ATTRIBUTES mode");
  if (c.mode != Mode::kAttributes) {
    if (c.stride != 2 && c.stride != 4)
      fail(prefix + "byteStride " + std::to_string(c.stride) + " must be 2 or 4 in " + mode_name(c.mode) + " mode");
    if (c.filter != Filter::kNone) fail(prefix + "filter " + filter_name(c.filter) + " is not allowed in " + mode_name(c.mode) + " mode");
    if (c.mode == Mode::kTriangles && c.count % 3 != 0)
      fail(prefix + "count " + std::to_string(c.count) + " is not a multiple of 3 in TRIANGLES mode");
  }
  if ((c.filter == Filter::kOctahedral && c.stride != 4 && c.stride != 8) ||
      (c.filter == Filter::kQuaternion && c.stride != 8) || (c.filter == Filter::kExponential && c.stride % 4 != 0))
    fail(prefix + "filter " + filter_name(c.filter) + " does not allow byteStride " + std::to_string(c.stride) +
         (c.filter == Filter::kOctahedral ? " (4 or 8)" : c.filter == Filter::kQuaternion ? " (8)" : " (a multiple of 4)"));
  if (c.buffer >= buffer_lengths.size()) fail(prefix + "buffer " + std::to_string(c.buffer) + " does not exist");
  if (dataless[c.buffer])
    fail(prefix + "buffer " + std::to_string(c.buffer) + " has no data (an " + kName +
         " fallback, or no uri outside a .glb's first buffer)");
  if (c.offset > buffer_lengths[c.buffer] || c.length > buffer_lengths[c.buffer] - c.offset)
    fail(prefix + "data (offset " + std::to_string(c.offset) + ", length " + std::to_string(c.length) +
         ") runs past the end of buffer " + std::to_string(c.buffer) + " (" + std::to_string(buffer_lengths[c.buffer]) +
         " bytes)");
  return length;
}

void decode_meshopt(tinygltf::Model& model, const json& doc, const std::vector<bool>& dataless) {
  const auto views = doc.find("bufferViews");
  const size_t original_buffers = model.buffers.size();
  for (size_t i = 0; views != doc.end() && views->is_array() && i < views->size() && i < model.bufferViews.size(); ++i) {
    const json* ext = extension_of((*views)[i]);
    if (!ext) continue;
    const std::string what = "bufferView " + std::to_string(i);
    const Compressed c = read_extension(*ext, what);  // checked by check_meshopt_view
    // Checked against the declared byteLength; the buffer read must hold it too.
    if (c.buffer >= original_buffers) fail(what + ": " + kName + " buffer " + std::to_string(c.buffer) + " does not exist");
    const std::vector<unsigned char>& source = model.buffers[size_t(c.buffer)].data;
    if (c.offset > source.size() || c.length > source.size() - c.offset)
      fail(what + ": " + kName + " data (offset " + std::to_string(c.offset) + ", length " + std::to_string(c.length) +
           ") runs past the end of buffer " + std::to_string(c.buffer) + " (" + std::to_string(source.size()) + " bytes read)");
    const unsigned char* data = source.data() + c.offset;
    const size_t count = size_t(c.count), stride = size_t(c.stride), length = size_t(c.length);

    tinygltf::Buffer decoded;
    decoded.data.resize(count * stride);
    int status;
    switch (c.mode) {
      case Mode::kAttributes:
        status = meshopt_decodeVertexBuffer(decoded.data.data(), count, stride, data, length);
        break;
      case Mode::kTriangles:
        status = meshopt_decodeIndexBuffer(decoded.data.data(), count, stride, data, length);
        break;
      default:
        status = meshopt_decodeIndexSequence(decoded.data.data(), count, stride, data, length);
        break;
    }
    if (status != 0) {
      // The codecs' header byte: 0xa0 attributes, 0xe0 triangles, 0xd0 index sequences (low 4 bits: version).
      const unsigned expected = c.mode == Mode::kAttributes ? 0xa0 : c.mode == Mode::kTriangles ? 0xe0 : 0xd0;
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02x", unsigned(data[0]));
      const std::string reason = (data[0] & 0xf0) != expected
                                     ? std::string("header byte ") + hex + " does not start " + mode_name(c.mode) + " data"
                                     : std::string(mode_name(c.mode)) + " decoder error " + std::to_string(status);
      fail(what + ": " + kName + " data is malformed (" + reason + "; " + std::to_string(length) + " bytes for " +
           std::to_string(count) + " elements of " + std::to_string(stride) + " bytes)");
    }
    switch (c.filter) {
      case Filter::kOctahedral: meshopt_decodeFilterOct(decoded.data.data(), count, stride); break;
      case Filter::kQuaternion: meshopt_decodeFilterQuat(decoded.data.data(), count, stride); break;
      case Filter::kExponential: meshopt_decodeFilterExp(decoded.data.data(), count, stride); break;
      case Filter::kNone: break;
    }
    tinygltf::BufferView& bv = model.bufferViews[i];
    bv.buffer = int(model.buffers.size());
    bv.byteOffset = 0;
    model.buffers.push_back(std::move(decoded));
  }
  // The placeholders tinygltf read for dataless buffers: nothing refers to them now.
  for (size_t b = 0; b < dataless.size() && b < original_buffers; ++b)
    if (dataless[b]) model.buffers[b].data = {};
}

}  // namespace dqskin::gltf
