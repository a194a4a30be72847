// Keeping what the .glb writer copies from the source file (asset/source_document.hpp): the loader's side,
// which reads it from the parsed model.
#include "../asset/source_document.hpp"

#include "accessor.hpp"
#include "dqskin/error.hpp"
#include "model_io.hpp"

#include <algorithm>

namespace dqskin::gltf {
namespace {

// A fixed attribute (TEXCOORD_n, COLOR_n) decoded to float; throws InputError naming it.
SourceAttribute read_attribute(const AccessorReader& reader, int accessor, const std::string& name, bool quantized,
                               size_t vertices, const std::string& what) {
  const bool color = name.rfind("COLOR_", 0) == 0;
  // §3.7.2.1's attribute table; KHR_mesh_quantization adds signed and unnormalized texture coordinates.
  const AccessorShape shape =
      color       ? AccessorShape{{TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4},
                                  {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                                  true}
      : quantized ? AccessorShape{{TINYGLTF_TYPE_VEC2},
                                  {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                                  false}
                  : AccessorShape{{TINYGLTF_TYPE_VEC2},
                                  {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                                  true};
  const std::string full = what + " " + name;
  SourceAttribute out;
  out.name = name;
  out.count = reader.count(accessor, full);
  if (out.count != vertices)
    throw InputError(what + ": " + name + " has " + std::to_string(out.count) + " elements, POSITION has " +
                     std::to_string(vertices));
  out.components = reader.components(accessor, full);
  out.values = reader.floats(accessor, shape, full);
  if (color)  // float colours outside [0, 1] are invalid (§3.7.2.1); keep the file valid
    for (float& v : out.values) v = std::clamp(v, 0.0f, 1.0f);
  return out;
}

}  // namespace

std::shared_ptr<const SourceDocument> keep_source(ParsedModel& parsed, const Asset& asset, const LoadOptions& options) {
  const tinygltf::Model& model = parsed.model;
  auto out = std::make_shared<SourceDocument>();
  out->json = std::move(parsed.doc);
  bool quantized = false;
  for (const std::string& e : model.extensionsUsed) quantized = quantized || e == "KHR_mesh_quantization";
  const AccessorReader reader{model, options.max_unbacked_elements};
  out->meshes.resize(asset.meshes.size());
  for (size_t m = 0; m < asset.meshes.size(); ++m) {
    for (size_t p = 0; p < asset.meshes[m].primitives.size(); ++p) {
      const std::string what = "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
      SourcePrimitive prim;
      try {
        for (const auto& [name, accessor] : model.meshes[m].primitives[p].attributes)  // std::map: sorted
          if (name.rfind("TEXCOORD_", 0) == 0 || name.rfind("COLOR_", 0) == 0)
            prim.attributes.push_back(read_attribute(reader, accessor, name, quantized,
                                                     asset.meshes[m].primitives[p].vertex_count(), what));
      } catch (const InputError& e) {
        prim.attributes.clear();
        prim.error = e.what();
      }
      out->meshes[m].push_back(std::move(prim));
    }
  }
  return out;
}

}  // namespace dqskin::gltf
