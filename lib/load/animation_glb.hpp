// A glTF file written back as one .glb with its animation samplers replaced (internal: `dqskin optimize`).
// As fixed_glb.hpp: the file's own JSON document is kept, so everything the optimizer does not touch
// (meshes, skins, node transforms, materials, extensions, names) stays; every buffer goes into the one BIN
// chunk and external images are embedded. Unlike --fix, what the new samplers replace leaves the file:
// accessors and bufferViews nothing refers to any more are removed, so the animation's bytes shrink.
#pragma once

#include "dqskin/load.hpp"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace dqskin::gltf {

// New data for one sampler, by its indices in the source document: `times` (the input accessor) and
// `values` (the output: components × keys floats, × 3 for CUBICSPLINE), stored as `component`
// (float, or a normalized integer type as the source stored it; values are then exact multiples of its
// step), and the sampler's interpolation.
struct SamplerEdit {
  size_t animation = 0, sampler = 0;
  std::vector<float> times;
  std::vector<float> values;
  int components = 1;
  int component = 5126;
  const char* interpolation = "LINEAR";
};

struct AnimationEdits {
  std::vector<SamplerEdit> samplers;
  std::vector<std::pair<size_t, size_t>> drop_channels;  // (animation, channel)
};

struct AnimationGlb {
  std::string glb;
  // Bytes of the accessors that animation samplers read (their elements, without padding), before and after.
  uint64_t animation_bytes_before = 0, animation_bytes_after = 0;
  // Empty when unused data was removed; else why it was kept (an extension that may refer to it).
  std::string kept_unused;
};

// The .glb of `path` with `edits` applied: samplers no channel uses any more are removed, then accessors
// and bufferViews nothing refers to, unless an extension outside those whose references are known is
// used (kept_unused says which). Throws InputError for a file it cannot write back faithfully (compressed
// geometry, an image that could not be read).
AnimationGlb animation_glb(const std::string& path, const LoadOptions& options, const AnimationEdits& edits);

}  // namespace dqskin::gltf
