#include "draco.hpp"

#include "dqskin/error.hpp"
#include "../base/saturating.hpp"

#include <draco/compression/decode.h>
#include <draco/compression/mesh/mesh_edgebreaker_decoder.h>
#include <draco/compression/mesh/mesh_sequential_decoder.h>
#include <draco/compression/point_cloud/point_cloud_decoder.h>
#include <draco/core/varint_decoding.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <type_traits>
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

// What the document declares for one Draco mesh. libdraco allocates for the counts its stream claims
// (faces, points, attributes and their components) before it reads the data they describe, and a few bytes
// can claim billions; so the decoder below checks those counts against these as soon as it has read them,
// before it allocates for them, and every allocation that follows is bounded by what estimate_draco()
// counted from the same accessors (and --max-memory allowed).
struct Declared {
  std::string prefix;  // "mesh 0 primitive 1: KHR_draco_mesh_compression "
  int indices = -1;
  uint64_t index_count = 0;
  struct Attribute {
    std::string name;
    int id = 0, accessor = 0, components = 0;
    uint64_t count = 0;
  };
  std::vector<Attribute> attributes;  // every attribute the extension lists

  std::string count_mismatch(const Attribute& a, uint64_t points) const {
    return prefix + "attribute " + a.name + ": accessor " + std::to_string(a.accessor) + " has count " +
           std::to_string(a.count) + ", the compressed data " + std::to_string(points) + " points";
  }
  std::string face_mismatch(uint64_t faces) const {
    return prefix + "indices: accessor " + std::to_string(indices) + " has count " + std::to_string(index_count) +
           ", the compressed data " + std::to_string(faces) + " triangles (" + std::to_string(faces * 3) + " indices)";
  }
};

// Bytes a decoded component may take in libdraco at once: its value (up to 8 bytes, for 64-bit types)
// and the int32 of its portable (quantized or predicted) form. estimate_draco() counts as much.
constexpr uint64_t kBytesPerComponent = 12;
// An attribute's connectivity when its seams differ from the positions' (edgebreaker): its corner table,
// seam flags and value maps, about 5 ints a corner.
constexpr uint64_t kBytesPerAttributeCorner = 20;
// Draco metadata, a stream byte's worth at most (see estimate_draco()).
constexpr uint64_t kBytesPerMetadataByte = 64;

// libdraco's two mesh decoders (what draco::Decoder picks by the header's method), each checking the
// stream's counts against `declared` where libdraco has read them and not yet allocated for them:
// - the connectivity's header (faces; points for the sequential method, attribute connectivities for
//   edgebreaker), read ahead from a copy of the buffer before libdraco reads it;
// - the attributes' descriptions (unique ids, components, data types) and the final point count, once
//   libdraco has read them and before it decodes any value.
// A refusal is kept in `refusal` and stops the decoding (libdraco then reports a failure).
template <typename Base>
class CheckedDecoder : public Base {
public:
  explicit CheckedDecoder(const Declared& declared) : declared_(declared) {}
  std::string refusal;

protected:
  bool DecodeConnectivity() override {
    draco::DecoderBuffer peek(*this->buffer());
    if (!check_connectivity(peek)) return false;
    return Base::DecodeConnectivity();
  }

  bool DecodeAllAttributes() override {
    if (!check_attributes()) return false;
    return Base::DecodeAllAttributes();
  }

private:
  static constexpr bool kSequential = std::is_same_v<Base, draco::MeshSequentialDecoder>;

  bool refuse(std::string message) {
    refusal = std::move(message);
    return false;
  }

  // One uint32 count: fixed-size before bitstream 2.0, a varint since.
  bool read_count(draco::DecoderBuffer& b, uint32_t& out, uint16_t varint_since) const {
    if (this->bitstream_version() < varint_since) return b.Decode(&out);
    return draco::DecodeVarint(&out, &b);
  }

  // Reads what libdraco's DecodeConnectivity() reads first (draco 1.5.5, bitstreams 1.x to 2.2). A stream
  // too short for it is left to libdraco, which fails on it the same way.
  bool check_connectivity(draco::DecoderBuffer& b) {
    uint32_t faces = 0, points = 0;
    if constexpr (kSequential) {
      // Fixed-size counts before 2.2. libdraco then bounds points by 3 × faces, and faces by the bytes left.
      if (!read_count(b, faces, DRACO_BITSTREAM_VERSION(2, 2)) || !read_count(b, points, DRACO_BITSTREAM_VERSION(2, 2)))
        return true;
    } else {
      uint32_t skipped = 0;
      if (this->bitstream_version() < DRACO_BITSTREAM_VERSION(2, 2) &&
          !read_count(b, skipped, DRACO_BITSTREAM_VERSION(2, 0)))  // new vertices, before 2.2
        return true;
      uint32_t vertices = 0;
      uint8_t attribute_connectivities = 0;
      if (!read_count(b, vertices, DRACO_BITSTREAM_VERSION(2, 0)) || !read_count(b, faces, DRACO_BITSTREAM_VERSION(2, 0)) ||
          !b.Decode(&attribute_connectivities))
        return true;
      // libdraco allocates its corner table for `faces` (and bounds the vertices by 3 × faces), and one
      // connectivity a corner for each attribute whose seams differ from the positions'.
      if (uint64_t(faces) * 3 != declared_.index_count) return refuse(declared_.face_mismatch(faces));
      if (attribute_connectivities > declared_.attributes.size())
        return refuse(declared_.prefix + "data is malformed (" + std::to_string(attribute_connectivities) +
                      " attribute connectivities for " + std::to_string(declared_.attributes.size()) + " attributes)");
    }
    if (uint64_t(faces) * 3 != declared_.index_count) return refuse(declared_.face_mismatch(faces));
    if constexpr (kSequential)
      for (const Declared::Attribute& a : declared_.attributes)
        if (a.count != points) return refuse(declared_.count_mismatch(a, points));
    return true;
  }

  bool check_attributes() {
    const draco::PointCloud& pc = *this->point_cloud();
    const uint64_t points = pc.num_points();
    uint64_t allowed = 0;
    for (const Declared::Attribute& a : declared_.attributes) {
      if (a.count != points) return refuse(declared_.count_mismatch(a, points));
      const draco::PointAttribute* attribute = pc.GetAttributeByUniqueId(uint32_t(a.id));
      if (!attribute)
        return refuse(declared_.prefix + "attribute " + a.name + ": unique id " + std::to_string(a.id) +
                      " is not in the compressed data");
      if (a.components == 0 || a.components > 4 || attribute->num_components() != a.components)
        return refuse(declared_.prefix + "attribute " + a.name + " has " + std::to_string(attribute->num_components()) +
                      " components in the compressed data, its accessor " + std::to_string(a.components));
      allowed += points * uint64_t(a.components) * kBytesPerComponent;
    }
    // Attributes the extension does not list are decoded too: allowed within what the listed ones leave
    // (their values are rarely 8 bytes), and refused beyond it.
    uint64_t need = 0;
    for (int i = 0; i < pc.num_attributes(); ++i) {
      const draco::PointAttribute& attribute = *pc.attribute(i);
      need += points * uint64_t(attribute.num_components()) * (uint64_t(draco::DataTypeLength(attribute.data_type())) + 4);
    }
    if (need > allowed)
      return refuse(declared_.prefix + "data is malformed (its " + std::to_string(pc.num_attributes()) +
                    " attributes take " + std::to_string(need) + " bytes to decode, more than the " +
                    std::to_string(allowed) + " of the attributes the extension lists)");
    return true;
  }

  const Declared& declared_;
};

// Decodes the Draco mesh in `data`; throws InputError when it is malformed or disagrees with `declared`.
std::unique_ptr<draco::Mesh> decode_mesh(const unsigned char* data, size_t size, const Declared& declared) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data), size);
  draco::DracoHeader header;
  {
    draco::DecoderBuffer peek(buffer);
    const draco::Status status = draco::PointCloudDecoder::DecodeHeader(&peek, &header);
    if (!status.ok()) fail(declared.prefix + "data is malformed (" + status.error_msg_string() + ")");
  }
  if (header.encoder_type != draco::TRIANGULAR_MESH) fail(declared.prefix + "data is a point cloud, not a triangle mesh");
  auto decode = [&](auto decoder) {
    auto mesh = std::make_unique<draco::Mesh>();
    const draco::DecoderOptions options;
    const draco::Status status = decoder->Decode(options, &buffer, mesh.get());
    if (!decoder->refusal.empty()) fail(decoder->refusal);
    if (!status.ok()) fail(declared.prefix + "data is malformed (" + status.error_msg_string() + ")");
    return mesh;
  };
  if (header.encoder_method == draco::MESH_SEQUENTIAL_ENCODING)
    return decode(std::make_unique<CheckedDecoder<draco::MeshSequentialDecoder>>(declared));
  if (header.encoder_method == draco::MESH_EDGEBREAKER_ENCODING)
    return decode(std::make_unique<CheckedDecoder<draco::MeshEdgebreakerDecoder>>(declared));
  fail(declared.prefix + "data is malformed (unknown encoding method " + std::to_string(header.encoder_method) + ")");
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
        if (size_t(it->second) >= model.accessors.size()) continue;
        const tinygltf::Accessor& a = model.accessors[size_t(it->second)];
        // libdraco's values and their portable form (what CheckedDecoder lets the stream's attributes take).
        mesh_bytes = add(mesh_bytes, mul(mul(a.count, uint64_t(components(a.type))), kBytesPerComponent));
        points = std::max<uint64_t>(points, a.count);
        if (!counted[it->second]) counted[it->second] = true, e.decoded = add(e.decoded, b);
      }
      if (p.indices >= 0 && size_t(p.indices) < model.accessors.size()) {
        const uint64_t corners = model.accessors[size_t(p.indices)].count;
        // Faces (3 × 4 bytes), and the decoder's corner table and its vertex maps (about 8 ints a corner),
        // and an attribute connectivity for each listed attribute at most (edgebreaker).
        mesh_bytes = add(mesh_bytes, add(mul(corners, 4 + 32), mul(points, 16)));
        mesh_bytes = add(mesh_bytes, mul(mul(corners, kBytesPerAttributeCorner), ext.attributes.size()));
        if (!counted[p.indices]) counted[p.indices] = true, e.decoded = add(e.decoded, bytes_of(p.indices));
      }
      // Draco metadata (header flag 0x8000) is decoded before the connectivity, into maps of named entries
      // and nested metadata; libdraco bounds each of its counts by the bytes left, so it takes at most a
      // few dozen bytes a byte of the stream (measured: 22 for one-byte entries, 40 for empty attribute
      // metadata). Streams without it, as glTF encoders write them, are not charged.
      if (ext.view >= 0 && size_t(ext.view) < model.bufferViews.size()) {
        const tinygltf::BufferView& v = model.bufferViews[size_t(ext.view)];
        if (v.buffer >= 0 && size_t(v.buffer) < model.buffers.size()) {
          const std::vector<unsigned char>& data = model.buffers[size_t(v.buffer)].data;
          if (v.byteOffset <= data.size() && v.byteLength <= data.size() - v.byteOffset && v.byteLength >= 11 &&
              (data[v.byteOffset + 10] & 0x80))
            mesh_bytes = add(mesh_bytes, mul(v.byteLength, kBytesPerMetadataByte));
        }
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
      Declared declared;
      declared.prefix = prefix;
      declared.indices = p.indices;
      declared.index_count = model.accessors[size_t(p.indices)].count;
      for (const auto& [name, id] : ext.attributes) {
        const int index = p.attributes.at(name);
        const tinygltf::Accessor& a = model.accessors[size_t(index)];
        declared.attributes.push_back({name, id, index, components(a.type), a.count});
      }
      const std::unique_ptr<draco::Mesh> decoded = decode_mesh(source.data() + view.byteOffset, view.byteLength, declared);
      const draco::Mesh& mesh = *decoded;
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
