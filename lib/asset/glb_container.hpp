// The .glb container (glTF 2.0 §4.4 "Binary glTF") and the BIN chunk being filled, shared by every writer
// of .glb files: the frame, morph and rest-mesh writers and lint's corrected copy.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace dqskin::glb {

using nlohmann::json;

// glTF bufferView.target values (§3.6.2.3 "Buffer views").
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
// accessor.componentType values (§3.6.2.2 "Accessor data types").
constexpr int kShort = 5122;
constexpr int kUnsignedShort = 5123;
constexpr int kUnsignedInt = 5125;
constexpr int kFloat = 5126;

// The GLB BIN chunk being filled and the bufferViews and accessors that describe it.
struct BinWriter {
  std::string bytes;
  json views = json::array();
  json accessors = json::array();
  // When set, the bytes go here as they come instead of into `bytes` (a morph animation's gigabyte, which
  // memory need not hold beside the frames it is made of); `spilled` counts them.
  std::function<void(std::span<const char>)> spill;
  uint64_t spilled = 0;
  uint64_t size() const { return spill ? spilled : bytes.size(); }
  // Appends bytes (no view of their own): what the writer copies from another BinWriter first.
  void append(std::span<const char> data);

  // Appends `size` bytes as a bufferView of their own, starting on a 4-byte boundary (§3.6.2.4 "Data
  // alignment": every accessor offset must be a multiple of its component size). target 0 = none
  // (images). Returns the view's index.
  int view(const void* data, size_t size, int target);
  // A float accessor of `count` elements of `type` (VEC2 …) over `values`, in a view of its own.
  int floats(std::span<const float> values, size_t count, const char* type);
  // A POSITION accessor (VEC3 float) with the min and max that §3.7.2.1 requires, taken from the floats
  // written.
  int positions(std::span<const float> xyz);
  // Indices as UNSIGNED_SHORT when every index is below 65535, else UNSIGNED_INT: §3.7.2.1 forbids the
  // primitive-restart value (the type's largest) as an index.
  int indices(std::span<const uint32_t> indices);
};

// A .glb file (glTF 2.0 §4.4 "Binary glTF"): a 12-byte header, the JSON chunk padded with spaces, the BIN
// chunk (when not empty) padded with zeros, all little-endian. Throws OutputError past 4 GiB.
std::string glb_container(const json& doc, std::string bin);

// The same file in two parts that are written one after the other: the header, the JSON chunk and the BIN
// chunk's header, then the BIN chunk's bytes, never copied (a morph animation's run to gigabytes).
struct GlbParts {
  std::string head;
  uint64_t spilled = 0;  // the BIN chunk's first bytes, written to a BinWriter's spill rather than `bin`
  std::string bin;       // the BIN chunk's (other) bytes
  uint64_t size() const { return head.size() + spilled + bin.size(); }
};
GlbParts glb_container_parts(const json& doc, std::string bin, uint64_t spilled = 0);

// The .glb of a document whose objects are complete but for the buffer: `bin`'s accessors, views and
// buffer go in, top-level arrays left empty are removed (§5.1 forbids empty ones), extensionsUsed lists
// every extension named in an `extensions` object (§3.12) and `own` (extensions the writer's data needs
// without naming them, such as KHR_mesh_quantization), and extensionsRequired those of `source_required`
// still used, then `own`.
GlbParts finish_glb_parts(json doc, BinWriter bin, const std::vector<std::string>& source_required,
                          const std::vector<std::string>& own = {});
// finish_glb_parts() as one string.
std::string finish_glb(json doc, BinWriter bin, const std::vector<std::string>& source_required,
                       const std::vector<std::string>& own = {});

}  // namespace dqskin::glb
