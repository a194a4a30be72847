// The .glb container and its BIN chunk (glb_container.hpp).
#include "glb_container.hpp"

#include "../base/byte_size.hpp"
#include "dqskin/error.hpp"

#include <glm/glm.hpp>

#include <algorithm>
#include <bit>
#include <limits>
#include <set>

namespace dqskin::glb {

static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian (§3.6.1)");

void BinWriter::append(std::span<const char> data) {
  if (!spill) {
    bytes.append(data.data(), data.size());
    return;
  }
  spill(data);
  spilled += data.size();
}

int BinWriter::view(const void* data, size_t size, int target) {
  static const char zeros[4] = {};
  append(std::span<const char>(zeros, size_t((4 - this->size() % 4) % 4)));
  json v = {{"buffer", 0}, {"byteOffset", this->size()}, {"byteLength", size}};
  if (target) v["target"] = target;
  append(std::span<const char>(static_cast<const char*>(data), size));
  views.push_back(std::move(v));
  return int(views.size()) - 1;
}

int BinWriter::floats(std::span<const float> values, size_t count, const char* type) {
  const int v = view(values.data(), values.size_bytes(), kArrayBuffer);
  accessors.push_back({{"bufferView", v}, {"componentType", kFloat}, {"count", count}, {"type", type}});
  return int(accessors.size()) - 1;
}

int BinWriter::positions(std::span<const float> xyz) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  for (size_t i = 0; i + 2 < xyz.size(); i += 3) {
    const glm::vec3 q(xyz[i], xyz[i + 1], xyz[i + 2]);
    lo = glm::min(lo, q), hi = glm::max(hi, q);
  }
  const int a = floats(xyz, xyz.size() / 3, "VEC3");
  accessors[size_t(a)]["min"] = {lo.x, lo.y, lo.z};
  accessors[size_t(a)]["max"] = {hi.x, hi.y, hi.z};
  return a;
}

int BinWriter::indices(std::span<const uint32_t> indices) {
  const uint32_t largest = indices.empty() ? 0 : *std::max_element(indices.begin(), indices.end());
  int v;
  if (largest < 0xFFFF) {
    std::vector<uint16_t> narrow(indices.begin(), indices.end());
    v = view(narrow.data(), narrow.size() * 2, kElementArrayBuffer);
  } else {
    v = view(indices.data(), indices.size_bytes(), kElementArrayBuffer);
  }
  accessors.push_back({{"bufferView", v},
                       {"componentType", largest < 0xFFFF ? kUnsignedShort : kUnsignedInt},
                       {"count", indices.size()},
                       {"type", "SCALAR"}});
  return int(accessors.size()) - 1;
}

namespace {

void put_u32(std::string& out, size_t value) {
  for (int shift = 0; shift < 32; shift += 8) out.push_back(char((value >> shift) & 0xFF));
}

}  // namespace

// §4.4: 12-byte header, a JSON chunk padded with spaces, a BIN chunk padded with zeros, all little-endian.
GlbParts glb_container_parts(const json& doc, std::string bin, uint64_t spilled) {
  std::string text = doc.dump(-1, ' ', false, json::error_handler_t::replace);
  text.resize((text.size() + 3) & ~size_t(3), ' ');
  bin.resize(size_t((spilled + bin.size() + 3) & ~uint64_t(3)) - size_t(spilled), '\0');
  const uint64_t bin_size = spilled + bin.size();
  const uint64_t total = 12 + 8 + text.size() + (bin_size == 0 ? 0 : 8 + bin_size);
  if (total > 0xFFFFFFFFu)
    throw OutputError("the .glb would be " + byte_size(total) + ", more than the 4 GiB the format can hold");
  GlbParts out;
  out.head.reserve(12 + 8 + text.size() + 8);
  out.head += "glTF";
  put_u32(out.head, 2);
  put_u32(out.head, uint32_t(total));
  put_u32(out.head, uint32_t(text.size()));
  out.head += "JSON";
  out.head += text;
  if (bin_size != 0) {
    put_u32(out.head, uint32_t(bin_size));
    out.head.append("BIN\0", 4);
  }
  out.spilled = spilled;
  out.bin = std::move(bin);
  return out;
}

std::string glb_container(const json& doc, std::string bin) {
  GlbParts parts = glb_container_parts(doc, std::move(bin));
  parts.head += parts.bin;
  return std::move(parts.head);
}

namespace {

// Every extension named in an `extensions` object anywhere in the document (§3.12: extensionsUsed must
// list them all, and should list no other).
void collect_extensions(const json& j, std::set<std::string>& names) {
  if (j.is_array()) {
    for (const json& v : j) collect_extensions(v, names);
  } else if (j.is_object()) {
    for (const auto& [key, value] : j.items()) {
      if (key == "extras") continue;
      if (key == "extensions" && value.is_object())
        for (const auto& [name, unused] : value.items()) names.insert(name);
      collect_extensions(value, names);
    }
  }
}

}  // namespace

GlbParts finish_glb_parts(json doc, BinWriter bin, const std::vector<std::string>& source_required,
                          const std::vector<std::string>& own) {
  static const char zeros[4] = {};
  bin.append(std::span<const char>(zeros, size_t((4 - bin.size() % 4) % 4)));
  doc["accessors"] = std::move(bin.accessors);
  doc["bufferViews"] = std::move(bin.views);
  if (bin.size() != 0) doc["buffers"] = json::array({{{"byteLength", bin.size()}}});
  std::vector<std::string> empty;
  for (const auto& [key, value] : doc.items())
    if (value.is_array() && value.empty()) empty.push_back(key);
  for (const std::string& key : empty) doc.erase(key);
  std::set<std::string> used;
  collect_extensions(doc, used);
  used.insert(own.begin(), own.end());
  if (!used.empty()) doc["extensionsUsed"] = used;
  json required = json::array();
  for (const std::string& e : source_required)
    if (used.count(e)) required.push_back(e);
  for (const std::string& e : own) required.push_back(e);
  if (!required.empty()) doc["extensionsRequired"] = std::move(required);
  return glb_container_parts(doc, std::move(bin.bytes), bin.spilled);
}

std::string finish_glb(json doc, BinWriter bin, const std::vector<std::string>& source_required,
                       const std::vector<std::string>& own) {
  GlbParts parts = finish_glb_parts(std::move(doc), std::move(bin), source_required, own);
  parts.head += parts.bin;
  return std::move(parts.head);
}

}  // namespace dqskin::glb
