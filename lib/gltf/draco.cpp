#include "draco.hpp"

#include "dqskin/error.hpp"
#include "../io/saturating.hpp"

#include <draco/compression/decode.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <string>
#include <utility>

namespace dqskin::gltf {
namespace {

constexpr const char* kName = "KHR_draco_mesh_compression";

[[noreturn]] void fail(const std::string& message) { throw InputError(message); }

size_t component_size(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    default: return 4;
  }
}

// Components of an accessor type, 0 when it is not one.
int components(int type) {
  const int n = tinygltf::GetNumComponentsInType(uint32_t(type));
  return n > 0 ? n : 0;
}

// The extension's object of a primitive: bufferView and the attribute map, or nothing.
struct Extension {
  int view = -1;
  std::map<std::string, int> attributes;  // name → unique id
};

bool read_extension(const tinygltf::Primitive& p, Extension& out, const std::string& what) {
  const auto it = p.extensions.find(kName);
  if (it == p.extensions.end()) return false;
  const tinygltf::Value& ext = it->second;
  if (!ext.IsObject()) fail(what + ": " + kName + " is not an object");
  const tinygltf::Value& view = ext.Get("bufferView");
  if (!view.IsInt()) fail(what + ": " + kName + ".bufferView is missing");
  out.view = view.Get<int>();
  const tinygltf::Value& attributes = ext.Get("attributes");
  if (!attributes.IsObject()) fail(what + ": " + kName + ".attributes is missing");
  for (const std::string& name : attributes.Keys()) {
    const tinygltf::Value& id = attributes.Get(name);
    if (!id.IsInt() || id.Get<int>() < 0) fail(what + ": " + kName + ".attributes." + name + " is not a unique id");
    out.attributes[name] = id.Get<int>();
  }
  return true;
}

// One decoded attribute converted to the accessor's component type, `n` components per point.
template <typename T>
bool convert(const draco::PointAttribute& attribute, size_t points, int n, uint8_t* out) {
  T value[16];
  for (size_t i = 0; i < points; ++i) {
    if (!attribute.ConvertValue<T>(attribute.mapped_index(draco::PointIndex(uint32_t(i))), int8_t(n), value)) return false;
    std::memcpy(out + i * size_t(n) * sizeof(T), value, size_t(n) * sizeof(T));
  }
  return true;
}

bool convert_as(int component_type, const draco::PointAttribute& attribute, size_t points, int n, uint8_t* out) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return convert<int8_t>(attribute, points, n, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return convert<uint8_t>(attribute, points, n, out);
    case TINYGLTF_COMPONENT_TYPE_SHORT: return convert<int16_t>(attribute, points, n, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return convert<uint16_t>(attribute, points, n, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return convert<uint32_t>(attribute, points, n, out);
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return convert<float>(attribute, points, n, out);
    default: return false;
  }
}

// Appends `bytes` as a new view of buffer `buffer` (4-byte aligned) and points accessor `index` at it.
void attach(tinygltf::Model& model, int buffer, int index, const std::vector<uint8_t>& bytes) {
  std::vector<unsigned char>& data = model.buffers[size_t(buffer)].data;
  data.resize((data.size() + 3) & ~size_t(3));
  tinygltf::BufferView view;
  view.buffer = buffer;
  view.byteOffset = data.size();
  view.byteLength = bytes.size();
  data.insert(data.end(), bytes.begin(), bytes.end());
  model.bufferViews.push_back(std::move(view));
  tinygltf::Accessor& a = model.accessors[size_t(index)];
  a.bufferView = int(model.bufferViews.size()) - 1;
  a.byteOffset = 0;
}

}  // namespace

DracoEstimate estimate_draco(const tinygltf::Model& model) {
  using saturating::add;
  using saturating::mul;
  DracoEstimate e;
  std::map<int, bool> counted;
  auto bytes_of = [&](int index) -> uint64_t {
    if (index < 0 || size_t(index) >= model.accessors.size()) return 0;
    const tinygltf::Accessor& a = model.accessors[size_t(index)];
    return mul(mul(a.count, uint64_t(components(a.type))), component_size(a.componentType));
  };
  for (const tinygltf::Mesh& mesh : model.meshes)
    for (const tinygltf::Primitive& p : mesh.primitives) {
      Extension ext;
      try {
        if (!read_extension(p, ext, "")) continue;
      } catch (const InputError&) {
        continue;  // decode_draco reports it
      }
      uint64_t mesh_bytes = 0, points = 0;
      for (const auto& [name, id] : ext.attributes) {
        const auto it = p.attributes.find(name);
        if (it == p.attributes.end()) continue;
        const uint64_t b = bytes_of(it->second);
        // Draco holds every value as its own type, at most 4 bytes a component: as many bytes, or 4× for bytes.
        mesh_bytes = add(mesh_bytes, mul(b, 4));
        if (size_t(it->second) < model.accessors.size()) points = std::max<uint64_t>(points, model.accessors[size_t(it->second)].count);
        if (!counted[it->second]) counted[it->second] = true, e.decoded = add(e.decoded, b);
      }
      if (p.indices >= 0 && size_t(p.indices) < model.accessors.size()) {
        const uint64_t corners = model.accessors[size_t(p.indices)].count;
        // Faces (3 × 4 bytes), and the decoder's corner table and its vertex maps (about 8 ints a corner).
        mesh_bytes = add(mesh_bytes, add(mul(corners, 4 + 32), mul(points, 16)));
        if (!counted[p.indices]) counted[p.indices] = true, e.decoded = add(e.decoded, bytes_of(p.indices));
      }
      e.transient = std::max(e.transient, mesh_bytes);
    }
  return e;
}

void decode_draco(tinygltf::Model& model) {
  // Accessors already written, by the view and unique id they came from: primitives that share a Draco
  // mesh (gltf-transform writes one for primitives with the same data) share its accessors.
  std::map<int, std::pair<int, int>> written;
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    for (size_t pi = 0; pi < model.meshes[m].primitives.size(); ++pi) {
      const tinygltf::Primitive& p = model.meshes[m].primitives[pi];
      const std::string what = "mesh " + std::to_string(m) + " primitive " + std::to_string(pi);
      const std::string prefix = what + ": " + kName + " ";
      Extension ext;
      if (!read_extension(p, ext, what)) continue;
      if (ext.view < 0 || size_t(ext.view) >= model.bufferViews.size())
        fail(prefix + "bufferView " + std::to_string(ext.view) + " does not exist");
      if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != -1)
        fail(prefix + "is on a primitive of mode " + std::to_string(p.mode) + "; dqskin decodes triangle lists (mode 4)");
      if (p.indices < 0) fail(prefix + "needs the primitive's indices accessor for the decoded faces");

      // Everything this primitive writes must be new, or the same data written before.
      auto seen = [&](int accessor, int id) {
        const auto it = written.find(accessor);
        if (it == written.end()) return false;
        if (it->second != std::make_pair(ext.view, id))
          fail(prefix + "accessor " + std::to_string(accessor) + " is also decoded from other Draco data");
        return true;
      };
      std::vector<std::pair<std::string, int>> todo;  // attribute name → unique id
      for (const auto& [name, id] : ext.attributes) {
        const auto it = p.attributes.find(name);
        if (it == p.attributes.end()) fail(prefix + "attribute " + name + " is not an attribute of the primitive");
        if (it->second < 0 || size_t(it->second) >= model.accessors.size())
          fail(prefix + "attribute " + name + ": accessor " + std::to_string(it->second) + " does not exist");
        if (!seen(it->second, id)) todo.emplace_back(name, id);
      }
      if (size_t(p.indices) >= model.accessors.size())
        fail(what + " indices: accessor " + std::to_string(p.indices) + " does not exist");
      const bool indices_done = seen(p.indices, -1);
      if (todo.empty() && indices_done) continue;

      const tinygltf::BufferView& view = model.bufferViews[size_t(ext.view)];
      if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
        fail(prefix + "bufferView " + std::to_string(ext.view) + " has no buffer");
      const std::vector<unsigned char>& source = model.buffers[size_t(view.buffer)].data;
      if (view.byteOffset > source.size() || view.byteLength > source.size() - view.byteOffset)
        fail(prefix + "bufferView " + std::to_string(ext.view) + " runs past the end of its buffer");
      draco::DecoderBuffer buffer;
      buffer.Init(reinterpret_cast<const char*>(source.data() + view.byteOffset), view.byteLength);
      const auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
      if (!type.ok()) fail(prefix + "data is malformed (" + type.status().error_msg_string() + ")");
      if (type.value() != draco::TRIANGULAR_MESH) fail(prefix + "data is a point cloud, not a triangle mesh");
      draco::Decoder decoder;
      auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
      if (!decoded.ok()) fail(prefix + "data is malformed (" + decoded.status().error_msg_string() + ")");
      const draco::Mesh& mesh = *decoded.value();
      const size_t points = mesh.num_points(), faces = mesh.num_faces();

      // The decoded data goes to a buffer of its own.
      const int out_buffer = int(model.buffers.size());
      model.buffers.emplace_back();
      for (const auto& [name, id] : todo) {
        const int index = model.meshes[m].primitives[pi].attributes.at(name);
        const tinygltf::Accessor& a = model.accessors[size_t(index)];
        const draco::PointAttribute* attribute = mesh.GetAttributeByUniqueId(uint32_t(id));
        if (!attribute)
          fail(prefix + "attribute " + name + ": unique id " + std::to_string(id) + " is not in the compressed data");
        const int n = components(a.type);
        if (n == 0 || n > 4 || attribute->num_components() != n)
          fail(prefix + "attribute " + name + " has " + std::to_string(attribute->num_components()) +
               " components in the compressed data, its accessor " + std::to_string(n));
        if (a.count != points)
          fail(prefix + "attribute " + name + ": accessor " + std::to_string(index) + " has count " +
               std::to_string(a.count) + ", the compressed data " + std::to_string(points) + " points");
        std::vector<uint8_t> bytes(points * size_t(n) * component_size(a.componentType));
        if (!convert_as(a.componentType, *attribute, points, n, bytes.data()))
          fail(prefix + "attribute " + name + ": the decoded values do not fit accessor " + std::to_string(index) +
               "'s component type " + std::to_string(a.componentType));
        attach(model, out_buffer, index, bytes);
        written[index] = {ext.view, id};
      }
      if (!indices_done) {
        const tinygltf::Accessor& a = model.accessors[size_t(p.indices)];
        if (a.count != faces * 3)
          fail(prefix + "indices: accessor " + std::to_string(p.indices) + " has count " + std::to_string(a.count) +
               ", the compressed data " + std::to_string(faces) + " triangles (" + std::to_string(faces * 3) + " indices)");
        const size_t size = component_size(a.componentType);
        if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
          fail(prefix + "indices: accessor " + std::to_string(p.indices) + " is not of unsigned integers");
        const uint64_t largest = size == 4 ? UINT32_MAX : (uint64_t(1) << (8 * size)) - 1;
        std::vector<uint8_t> bytes(faces * 3 * size);
        for (size_t f = 0; f < faces; ++f) {
          const draco::Mesh::Face& face = mesh.face(draco::FaceIndex(uint32_t(f)));
          for (size_t c = 0; c < 3; ++c) {
            const uint32_t v = face[c].value();
            if (v > largest)
              fail(prefix + "indices: index " + std::to_string(v) + " does not fit accessor " + std::to_string(p.indices) +
                   "'s component type");
            std::memcpy(bytes.data() + (3 * f + c) * size, &v, size);  // little-endian
          }
        }
        attach(model, out_buffer, p.indices, bytes);
        written[p.indices] = {ext.view, -1};
      }
    }
  }
}

}  // namespace dqskin::gltf
