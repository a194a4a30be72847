// The morph-target animation's .glb (morph_glb.hpp). glTF 2.0 sections: §3.7.2.2 morph targets, §3.6.2.3
// sparse accessors, §3.6.2.4 data alignment, §3.11 animations; KHR_mesh_quantization for the integer types.
#include "morph_glb.hpp"

#include "vertex_sharing.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace dqskin::glb {

namespace {

constexpr int kNormalMax = 32767;  // normalized SHORT: c / 32767 (§3.6.2.2 "Accessor data types")

int16_t quantize_normal(float c) {
  return int16_t(std::clamp(std::lround(double(c) * kNormalMax), long(-kNormalMax), long(kNormalMax)));
}

double decode_normal(int c) { return std::max(double(c) / kNormalMax, -1.0); }

// float(a - b), the displacement a float target holds (correctly rounded, as float subtraction is).
float displacement(double a, double b) { return float(a - b); }

float round_down(double x) {
  float f = float(x);
  return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}

float round_up(double x) {
  float f = float(x);
  return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

// An accessor's elements: `components` values of T (float, int16_t, uint16_t) each.
template <class T>
struct Elements {
  std::span<const T> values;
  int components = 3;
  int component_type = kFloat;
  bool normalized = false;
  size_t count() const { return values.size() / size_t(components); }
};

const char* type_name(int components) { return components == 1 ? "SCALAR" : components == 2 ? "VEC2" : "VEC3"; }

// Writes `e` as an accessor and returns its index. Dense, each element in a vertex attribute's view padded
// to a multiple of 4 bytes with byteStride (§3.6.2.4); or, with `may_be_sparse` when that takes fewer
// bytes, sparse with no bufferView (§3.6.2.3: the accessor is all zeros, then the listed elements are
// substituted): the indices of the elements not all zero (at least one, as sparse.count ≥ 1), as
// UNSIGNED_SHORT when the count allows, and their values tightly packed. `bounds`: min and max of every
// element, zeros included (required for POSITION, §3.7.2.1, and animation inputs, §3.11). `target`: the
// bufferView target of a dense view (0 for animation data).
template <class T>
int write_accessor(BinWriter& bin, const Elements<T>& e, bool may_be_sparse, bool bounds, int target, MorphGlbStats* stats) {
  const size_t count = e.count(), element = sizeof(T) * size_t(e.components);
  const size_t stride = (element + 3) & ~size_t(3);
  std::vector<uint32_t> moved;
  for (size_t i = 0; i < count; ++i)
    for (int c = 0; c < e.components; ++c)
      if (e.values[i * size_t(e.components) + size_t(c)] != T(0)) {
        moved.push_back(uint32_t(i));
        break;
      }
  if (moved.empty()) moved.push_back(0);
  const bool short_indices = count <= 65536;
  const size_t index_bytes = short_indices ? 2 : 4;
  const size_t sparse_bytes = ((moved.size() * index_bytes + 3) & ~size_t(3)) + ((moved.size() * element + 3) & ~size_t(3));
  json accessor = {{"componentType", e.component_type}, {"count", count}, {"type", type_name(e.components)}};
  if (e.normalized) accessor["normalized"] = true;
  if (may_be_sparse && sparse_bytes < count * stride) {
    std::string indices, values;
    for (uint32_t i : moved) {
      if (short_indices) {
        const uint16_t s = uint16_t(i);
        indices.append(reinterpret_cast<const char*>(&s), 2);
      } else {
        indices.append(reinterpret_cast<const char*>(&i), 4);
      }
      values.append(reinterpret_cast<const char*>(&e.values[i * size_t(e.components)]), element);
    }
    const int iv = bin.view(indices.data(), indices.size(), 0);
    const int vv = bin.view(values.data(), values.size(), 0);
    accessor["sparse"] = {{"count", moved.size()},
                          {"indices", {{"bufferView", iv}, {"componentType", short_indices ? kUnsignedShort : kUnsignedInt}}},
                          {"values", {{"bufferView", vv}}}};
    if (stats) ++stats->sparse_accessors;
  } else {
    std::string bytes(count * stride, '\0');
    for (size_t i = 0; i < count; ++i) std::memcpy(&bytes[i * stride], &e.values[i * size_t(e.components)], element);
    const int v = bin.view(bytes.data(), bytes.size(), target);
    if (stride != element) bin.views[size_t(v)]["byteStride"] = stride;
    accessor["bufferView"] = v;
  }
  if (bounds) {
    json lo = json::array(), hi = json::array();
    for (int c = 0; c < e.components; ++c) {
      T a = std::numeric_limits<T>::max(), b = std::numeric_limits<T>::lowest();
      for (size_t i = 0; i < count; ++i) {
        a = std::min(a, e.values[i * size_t(e.components) + size_t(c)]);
        b = std::max(b, e.values[i * size_t(e.components) + size_t(c)]);
      }
      lo.push_back(a), hi.push_back(b);
    }
    accessor["min"] = std::move(lo);
    accessor["max"] = std::move(hi);
  }
  bin.accessors.push_back(std::move(accessor));
  return int(bin.accessors.size()) - 1;
}

// One primitive's base attributes and targets; `first` is its first vertex among all primitives.
json primitive_attributes(const MorphAnimation& a, size_t first, size_t n, bool normals, json& targets, BinWriter& bin,
                          MorphGlbStats* stats) {
  const MorphGrid& grid = a.grid;
  const float* base = a.positions[0].data() + 3 * first;
  const float* base_n = normals ? a.normals[0].data() + 3 * first : nullptr;
  json attributes = json::object();
  std::vector<glm::ivec3> q_base;  // with the grid
  std::vector<int16_t> qn_base;
  if (grid.on()) {
    std::vector<uint16_t> q(3 * n);
    for (size_t v = 0; v < n; ++v) {
      q_base.push_back(grid.quantize(base + 3 * v));
      for (int c = 0; c < 3; ++c) q[3 * v + size_t(c)] = uint16_t(q_base.back()[c]);
    }
    attributes["POSITION"] = write_accessor(bin, Elements<uint16_t>{q, 3, kUnsignedShort}, false, true, kArrayBuffer, stats);
    if (normals) {
      for (size_t i = 0; i < 3 * n; ++i) qn_base.push_back(quantize_normal(base_n[i]));
      attributes["NORMAL"] = write_accessor(bin, Elements<int16_t>{qn_base, 3, kShort, true}, false, false, kArrayBuffer, stats);
    }
  } else {
    attributes["POSITION"] = bin.positions(std::span(base, 3 * n));
    if (normals) attributes["NORMAL"] = bin.floats(std::span(base_n, 3 * n), n, "VEC3");
  }
  for (size_t k = 1; k < a.positions.size(); ++k) {
    const float* p = a.positions[k].data() + 3 * first;
    json target = json::object();
    if (grid.on()) {
      std::vector<int16_t> d(3 * n);
      for (size_t v = 0; v < n; ++v) {
        const glm::ivec3 q = grid.quantize(p + 3 * v) - q_base[v];
        for (int c = 0; c < 3; ++c) d[3 * v + size_t(c)] = int16_t(q[c]);  // within ±kMax: both on the grid
      }
      target["POSITION"] = write_accessor(bin, Elements<int16_t>{d, 3, kShort}, true, true, kArrayBuffer, stats);
    } else {
      std::vector<float> d(3 * n);
      for (size_t i = 0; i < 3 * n; ++i) d[i] = displacement(double(p[i]), double(base[i]));
      target["POSITION"] = write_accessor(bin, Elements<float>{d, 3, kFloat}, true, true, kArrayBuffer, stats);
    }
    if (normals) {
      const std::span<const float> key_n = a.normals[k].subspan(3 * first, 3 * n);
      if (grid.on() && short_normal_target(grid, std::span(base_n, 3 * n), key_n)) {
        std::vector<int16_t> d(3 * n);
        for (size_t i = 0; i < 3 * n; ++i) d[i] = int16_t(quantize_normal(key_n[i]) - qn_base[i]);
        target["NORMAL"] = write_accessor(bin, Elements<int16_t>{d, 3, kShort, true}, true, false, kArrayBuffer, stats);
      } else {
        if (grid.on() && stats) ++stats->float_normal_targets;
        std::vector<float> d(3 * n);
        for (size_t i = 0; i < 3 * n; ++i)
          d[i] = displacement(double(key_n[i]), grid.on() ? decode_normal(qn_base[i]) : double(base_n[i]));
        target["NORMAL"] = write_accessor(bin, Elements<float>{d, 3, kFloat}, true, false, kArrayBuffer, stats);
      }
    }
    targets.push_back(std::move(target));
  }
  return attributes;
}

}  // namespace

MorphGrid MorphGrid::over(const glm::dvec3& lo, const glm::dvec3& hi) {
  MorphGrid g;
  double extent = 0;
  for (int c = 0; c < 3; ++c) {
    g.origin[c] = double(round_down(lo[c]));
    extent = std::max(extent, hi[c] - g.origin[c]);
  }
  g.step = extent > 0 ? double(round_up(extent / kMax)) : 1.0;
  return g;
}

glm::ivec3 MorphGrid::quantize(const float* p) const {
  glm::ivec3 q;
  for (int c = 0; c < 3; ++c) q[c] = int(std::clamp(std::lround((double(p[c]) - origin[c]) / step), 0L, long(kMax)));
  return q;
}

double MorphGrid::bound() const { return step * std::sqrt(3.0) / 2; }

glm::dvec3 stored_position(const MorphGrid& grid, const float* base, const float* p) {
  if (grid.on()) return grid.decode(grid.quantize(p));
  glm::dvec3 out;
  for (int c = 0; c < 3; ++c) out[c] = double(base[c]) + double(displacement(double(p[c]), double(base[c])));
  return out;
}

bool short_normal_target(const MorphGrid& grid, std::span<const float> base, std::span<const float> key) {
  if (!grid.on()) return false;
  for (size_t i = 0; i < base.size(); ++i)
    if (std::abs(quantize_normal(key[i]) - quantize_normal(base[i])) > kNormalMax) return false;
  return true;
}

glm::dvec3 stored_normal(const MorphGrid& grid, bool short_target, const float* base, const float* n) {
  glm::dvec3 out;
  for (int c = 0; c < 3; ++c) {
    if (!grid.on()) {
      out[c] = double(base[c]) + double(displacement(double(n[c]), double(base[c])));
    } else {
      const int qb = quantize_normal(base[c]);
      out[c] = short_target ? decode_normal(qb) + double(quantize_normal(n[c]) - qb) / kNormalMax
                            : decode_normal(qb) + double(displacement(double(n[c]), decode_normal(qb)));
    }
  }
  return out;
}

GlbParts encode_morph_glb(const Asset& asset, const std::vector<MeshInstance>& instances,
                             const Appearance& appearance, const MorphAnimation& a, MorphGlbStats* stats,
                             std::function<void(std::span<const char>)> spill) {
  const size_t keys = a.positions.size();
  if (keys == 0 || a.times.size() != keys || a.normals.size() != keys || a.target_names.size() + 1 != keys)
    throw std::invalid_argument("encode_morph_glb: keys, times, normals and target names do not match");
  // The buffer at its largest from the start (every target dense float positions and normals, and the
  // weights): grown by doubling, it held the old and the new copy of a gigabyte at once.
  BinWriter bin;
  if (spill) {
    bin.spill = std::move(spill);
    bin.views = appearance.bin.views;
    bin.accessors = appearance.bin.accessors;
    bin.append(appearance.bin.bytes);
  } else {
    const size_t values = a.positions[0].size() + a.normals[0].size();
    bin.bytes.reserve(appearance.bin.bytes.size() + keys * (values * sizeof(float) + 64 * (a.with_normals.size() + 1)) +
                      keys * keys * sizeof(float) + 64);
    bin = appearance.bin;
  }
  json primitives = json::array();
  // A primitive that shares an earlier one's vertex data names that one's accessors, as the source does.
  const SharedVertexLayout sharing = shared_vertex_layout(asset, instances);
  std::vector<json> written_attributes(sharing.owner.size()), written_targets(sharing.owner.size());
  size_t p = 0, writer = 0;
  for (const MeshInstance& inst : instances) {
    const std::vector<FixedPrimitive>& fixed = appearance.meshes.at(size_t(inst.mesh));
    for (size_t i = 0; i < fixed.size(); ++i, ++p) {
      const Primitive& source = asset.meshes[size_t(inst.mesh)].primitives[i];
      const FixedPrimitive& f = fixed[i];
      const size_t n = source.vertex_count(), first = sharing.first_vertex[p];
      if (3 * (first + n) > a.positions[0].size())
        throw std::invalid_argument("encode_morph_glb: the keys hold fewer vertices than the instances draw");
      if (sharing.writes(p)) {
        json targets = json::array();
        json attributes = f.attributes;
        attributes.update(primitive_attributes(a, first, n, a.with_normals.at(writer++), targets, bin, stats));
        written_attributes[p] = std::move(attributes);
        written_targets[p] = std::move(targets);
      }
      json targets = written_targets[sharing.owner[p]];
      json out = {{"attributes", written_attributes[sharing.owner[p]]}};
      if (!targets.empty()) out["targets"] = std::move(targets);
      if (f.indices >= 0) out["indices"] = f.indices;
      if (source.mode != PrimitiveMode::kTriangles) out["mode"] = int(source.mode);  // the default (§5.24)
      if (f.material >= 0) out["material"] = f.material;
      if (!f.extras.is_null()) out["extras"] = f.extras;
      if (!f.extensions.is_null()) out["extensions"] = f.extensions;
      primitives.push_back(std::move(out));
    }
  }
  if (stats) stats->targets = keys - 1;

  json mesh = {{"name", a.name}, {"primitives", std::move(primitives)}};
  json node = {{"name", a.name}, {"mesh", 0}};
  if (a.grid.on()) {  // KHR_mesh_quantization: the node's transform decodes the grid
    node["translation"] = {float(a.grid.origin.x), float(a.grid.origin.y), float(a.grid.origin.z)};
    node["scale"] = {float(a.grid.step), float(a.grid.step), float(a.grid.step)};
  }
  json doc = appearance.doc;
  doc.erase("cameras");  // their nodes are not written
  if (keys > 1) {
    mesh["extras"] = {{"targetNames", a.target_names}};  // read by three.js's and Babylon.js's loaders
    // §3.11: the input holds times in seconds (min and max required), the output one weight per target and
    // key (count = keys × targets); one-hot weights, so at most one target is active at a key.
    std::vector<float> times;
    for (double t : a.times) times.push_back(float(t));
    const size_t targets = keys - 1;
    std::vector<float> weights(keys * targets, 0.0f);
    for (size_t k = 1; k < keys; ++k) weights[k * targets + k - 1] = 1.0f;
    const int input = write_accessor(bin, Elements<float>{times, 1, kFloat}, false, true, 0, stats);
    const int output = write_accessor(bin, Elements<float>{weights, 1, kFloat}, true, false, 0, stats);
    doc["animations"] = json::array({{{"name", a.clip},
                                      {"samplers", json::array({{{"input", input}, {"output", output}, {"interpolation", "LINEAR"}}})},
                                      {"channels", json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}}})}}});
  }
  doc["meshes"] = json::array({std::move(mesh)});
  doc["nodes"] = json::array({std::move(node)});
  json scene = appearance.scene_fields;
  scene["nodes"] = {0};
  doc["scenes"] = json::array({std::move(scene)});
  doc["scene"] = 0;
  std::vector<std::string> own;
  if (a.grid.on()) own.push_back("KHR_mesh_quantization");
  return finish_glb_parts(std::move(doc), std::move(bin), appearance.source_extensions_required, own);
}

}  // namespace dqskin::glb
