// Validated decoding of glTF accessors (internal to the loader). Every read checks the accessor against
// its buffer view and buffer before touching a byte, so a file that claims more data than it has is an
// InputError, never an out-of-bounds read or a huge allocation.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <string>
#include <vector>

namespace dqskin::gltf {

// What an accessor must look like for one use (glTF 2.0 §3.7.2 and the attribute tables of §3.7.2.1).
struct AccessorShape {
  std::vector<int> types;            // TINYGLTF_TYPE_*
  std::vector<int> component_types;  // TINYGLTF_COMPONENT_TYPE_*
  bool integers_must_be_normalized = false;    // e.g. WEIGHTS_n as unsigned byte
};

struct AccessorReader {
  const tinygltf::Model& model;
  uint64_t max_unbacked_elements;

  // Number of components of the accessor's type (SCALAR 1 … MAT4 16). Checks the index.
  int components(int accessor, const std::string& what) const;
  size_t count(int accessor, const std::string& what) const;

  // Decodes to float, count × components values; normalized integers map to [0, 1] or [−1, 1] as the
  // specification says (§3.11, "Animations": c / 255 etc.). Every value must be finite.
  std::vector<float> floats(int accessor, const AccessorShape& shape, const std::string& what) const;

  // Decodes integer (not normalized) accessors: indices, joints.
  std::vector<uint32_t> uints(int accessor, const AccessorShape& shape, const std::string& what) const;
};

}  // namespace dqskin::gltf
