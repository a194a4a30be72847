// How much memory loading a parsed file will take, known before anything is decoded (internal to the
// loader): so that a small file whose primitives share one large accessor a thousand times is refused in
// one line instead of exhausting the machine.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>

namespace dqskin::gltf {

struct MemoryEstimate {
  uint64_t file = 0;       // what tinygltf already holds: buffers and encoded images
  uint64_t decoded = 0;    // EXT_meshopt_compression views decoded (meshopt.hpp), accessors written from
                           // KHR_draco_mesh_compression (draco.hpp)
  uint64_t json = 0;       // what parsing the JSON took (precheck.hpp json_memory)
  uint64_t images = 0;     // decoded images (RGBA, 8 bits) by their declared size, when they are decoded
  uint64_t asset = 0;      // the Asset: decoded attributes (every use of an accessor counted), morph
                           // targets, generated normals, skins, animation keys, nodes, copied images
  uint64_t transient = 0;  // the largest temporary of one decode (an accessor as double, normals' sums, a
                           // Draco mesh)
  uint64_t accessor_uses = 0;  // accessor reads by meshes, skins and animations, for the message
  uint64_t total() const;      // saturating sum
};

// Estimates from the model's declared counts (no accessor is read, no image decoded). `decoded_images`:
// the caller will decode the images (the renderer), so their declared sizes count too. Saturates instead of
// overflowing.
// `kept_source`: LoadOptions::keep_source, which decodes every TEXCOORD_n and COLOR_n once more.
MemoryEstimate estimate_memory(const tinygltf::Model& model, bool decoded_images = false, bool kept_source = false);

}  // namespace dqskin::gltf
