#include "accessor.hpp"

#include "dqskin/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace dqskin::gltf {
namespace {

[[noreturn]] void fail(const std::string& what, const std::string& message) {
  throw InputError(what + ": " + message);
}

size_t component_size(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

// One component as double: raw integer value, or the normalized mapping of glTF 2.0 §3.11.
double decode(const uint8_t* p, int component_type, bool normalized) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? *p / 255.0 : *p;
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    default: {
      float v;
      std::memcpy(&v, p, 4);
      return double(v);
    }
  }
}

struct View {
  const uint8_t* data = nullptr;  // first byte of element 0; null when the accessor has no buffer view
  size_t stride = 0;
};

// The bytes behind accessor data at (buffer_view, byte_offset) holding `count` elements of
// `element_size` bytes, after checking that all of them lie inside the view and the buffer.
View locate(const tinygltf::Model& model, int buffer_view, size_t byte_offset, size_t count, size_t element_size,
            bool allow_stride, const std::string& what) {
  if (buffer_view < 0 || size_t(buffer_view) >= model.bufferViews.size())
    fail(what, "bufferView " + std::to_string(buffer_view) + " does not exist");
  const tinygltf::BufferView& bv = model.bufferViews[size_t(buffer_view)];
  const std::string view_name = "bufferView " + std::to_string(buffer_view);
  if (bv.buffer < 0 || size_t(bv.buffer) >= model.buffers.size())
    fail(what, view_name + " refers to buffer " + std::to_string(bv.buffer) + ", which does not exist");
  const std::vector<unsigned char>& buffer = model.buffers[size_t(bv.buffer)].data;
  if (bv.byteOffset > buffer.size() || bv.byteLength > buffer.size() - bv.byteOffset)
    fail(what, view_name + " (offset " + std::to_string(bv.byteOffset) + ", length " + std::to_string(bv.byteLength) +
                   ") runs past the end of buffer " + std::to_string(bv.buffer) + " (" + std::to_string(buffer.size()) +
                   " bytes)");
  size_t stride = element_size;
  if (allow_stride && bv.byteStride != 0) {
    if (bv.byteStride < element_size || bv.byteStride > 252)
      fail(what, view_name + " has byteStride " + std::to_string(bv.byteStride) + ", but elements are " +
                     std::to_string(element_size) + " bytes (stride must be " + std::to_string(element_size) +
                     "..252)");
    stride = bv.byteStride;
  }
  // Last byte needed: offset + (count − 1) stride + element size, computed without overflow.
  const size_t length = bv.byteLength;
  if (byte_offset > length || count > (length - byte_offset) / stride + 1 ||
      (count - 1) * stride + element_size > length - byte_offset)
    fail(what, std::to_string(count) + " elements of " + std::to_string(element_size) + " bytes (stride " +
                   std::to_string(stride) + ", offset " + std::to_string(byte_offset) + ") do not fit in " +
                   view_name + " (" + std::to_string(length) + " bytes)");
  return {buffer.data() + bv.byteOffset + byte_offset, stride};
}

const char* type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "an unknown type";
  }
}

const char* component_name(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "byte";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "unsigned byte";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "short";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "unsigned short";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "unsigned int";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "float";
    default: return nullptr;
  }
}

// Decodes every element of the accessor, dense data then sparse substitution (§3.6.2.3), to doubles.
std::vector<double> decode_all(const AccessorReader& reader, int index, const AccessorShape& shape,
                               bool want_normalized, const std::string& what_in) {
  const tinygltf::Model& model = reader.model;
  const std::string what = what_in + " (accessor " + std::to_string(index) + ")";
  const int comps = reader.components(index, what_in);
  const tinygltf::Accessor& a = model.accessors[size_t(index)];

  if (std::find(shape.types.begin(), shape.types.end(), a.type) == shape.types.end())
    fail(what, std::string("has type ") + type_name(a.type) + ", which is not allowed here");
  if (std::find(shape.component_types.begin(), shape.component_types.end(), a.componentType) ==
      shape.component_types.end())
    fail(what, "has component type " +
                   (component_name(a.componentType) ? std::string(component_name(a.componentType))
                                                    : std::to_string(a.componentType) + " (not a glTF component type)") +
                   ", which is not allowed here");
  const size_t csize = component_size(a.componentType);
  const bool is_float = a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
  if (a.normalized && (is_float || a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
    fail(what, "is normalized, which only byte and short components may be");
  if (!is_float && want_normalized && shape.integers_must_be_normalized && !a.normalized)
    fail(what, std::string("has ") + component_name(a.componentType) + " components that are not normalized");
  if (a.count == 0) fail(what, "has count 0");

  const size_t count = a.count;
  const size_t element = csize * size_t(comps);
  std::vector<double> out;
  if (a.bufferView >= 0) {
    const View v = locate(model, a.bufferView, a.byteOffset, count, element, true, what);
    out.resize(count * size_t(comps));
    for (size_t i = 0; i < count; ++i)
      for (size_t c = 0; c < size_t(comps); ++c)
        out[i * size_t(comps) + c] = decode(v.data + i * v.stride + c * csize, a.componentType, a.normalized);
  } else {
    if (count > reader.max_unbacked_elements / size_t(comps))
      fail(what, "has count " + std::to_string(count) + " without a bufferView, more than dqskin accepts (" +
                     std::to_string(count) + " × " + std::to_string(comps) + " values; the limit is " +
                     std::to_string(reader.max_unbacked_elements) + ")");
    out.assign(count * size_t(comps), 0.0);  // §3.6.2.3: no bufferView means zeros
  }

  if (a.sparse.isSparse) {
    const auto& sparse = a.sparse;
    if (sparse.count <= 0 || size_t(sparse.count) > count)
      fail(what, "has sparse count " + std::to_string(sparse.count) + ", which must be 1.." + std::to_string(count));
    const size_t n = size_t(sparse.count);
    const int itype = sparse.indices.componentType;
    if (itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      fail(what, "has sparse indices that are not unsigned byte, short or int");
    const size_t isize = component_size(itype);
    const View iv = locate(model, sparse.indices.bufferView, size_t(sparse.indices.byteOffset), n, isize, false,
                           what + " sparse indices");
    const View vv = locate(model, sparse.values.bufferView, size_t(sparse.values.byteOffset), n, element, false,
                           what + " sparse values");
    double previous = -1;
    for (size_t k = 0; k < n; ++k) {
      const double target = decode(iv.data + k * isize, itype, false);
      if (target <= previous) fail(what, "has sparse indices that do not strictly increase");
      if (target >= double(count))
        fail(what, "has sparse index " + std::to_string(uint64_t(target)) + ", but count is " + std::to_string(count));
      previous = target;
      const size_t i = size_t(target);
      for (size_t c = 0; c < size_t(comps); ++c)
        out[i * size_t(comps) + c] = decode(vv.data + k * element + c * csize, a.componentType, a.normalized);
    }
  }

  if (is_float) {
    for (size_t i = 0; i < out.size(); ++i)
      if (!std::isfinite(out[i]))
        fail(what, "element " + std::to_string(i / size_t(comps)) + " is " + (std::isnan(out[i]) ? "NaN" : "infinite"));
  }
  return out;
}

}  // namespace

int AccessorReader::components(int accessor, const std::string& what) const {
  if (accessor < 0 || size_t(accessor) >= model.accessors.size())
    fail(what, "accessor " + std::to_string(accessor) + " does not exist");
  switch (model.accessors[size_t(accessor)].type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: fail(what + " (accessor " + std::to_string(accessor) + ")", "has an unknown type");
  }
}

size_t AccessorReader::count(int accessor, const std::string& what) const {
  components(accessor, what);
  return model.accessors[size_t(accessor)].count;
}

std::vector<float> AccessorReader::floats(int accessor, const AccessorShape& shape, const std::string& what) const {
  const std::vector<double> d = decode_all(*this, accessor, shape, true, what);
  std::vector<float> out(d.size());
  for (size_t i = 0; i < d.size(); ++i) {
    out[i] = float(d[i]);
    if (!std::isfinite(out[i]))  // finite double, but beyond float's range
      fail(what + " (accessor " + std::to_string(accessor) + ")", "element " + std::to_string(i) + " overflows float");
  }
  return out;
}

std::vector<uint32_t> AccessorReader::uints(int accessor, const AccessorShape& shape, const std::string& what) const {
  const std::string where = what + " (accessor " + std::to_string(accessor) + ")";
  components(accessor, what);
  if (model.accessors[size_t(accessor)].componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
    fail(where, "has float components where integers are required");
  if (model.accessors[size_t(accessor)].normalized) fail(where, "is normalized, but holds indices");
  const std::vector<double> d = decode_all(*this, accessor, shape, false, what);
  std::vector<uint32_t> out(d.size());
  for (size_t i = 0; i < d.size(); ++i) out[i] = uint32_t(d[i]);
  return out;
}

}  // namespace dqskin::gltf
