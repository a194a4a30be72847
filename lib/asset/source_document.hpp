// What the .glb frame writer copies from a source file beyond the Asset, kept by the loader when asked
// (LoadOptions::keep_source) so that the writer never reads or parses the file a second time: the JSON as
// the loader checked it, and every primitive's TEXCOORD_n and COLOR_n attributes decoded to float. Data
// only (no tinygltf): lib/write reads it, lib/load fills it.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace dqskin {

// One TEXCOORD_n or COLOR_n attribute, decoded to float (colours clamped to [0, 1], as §3.7.2.1 requires
// of float colours), `components` values per vertex.
struct SourceAttribute {
  std::string name;
  int components = 0;
  size_t count = 0;
  std::vector<float> values;
};

struct SourcePrimitive {
  std::vector<SourceAttribute> attributes;  // by name, in name order
  // Why an attribute could not be decoded, or empty. Only a writer that copies the primitive fails on it:
  // the attributes play no part in deformation.
  std::string error;
};

struct SourceDocument {
  nlohmann::json json;  // the file's JSON as checked (precheck_json): appearance values refused are gone
  std::vector<std::vector<SourcePrimitive>> meshes;  // per mesh, per primitive
};

}  // namespace dqskin
