// A glTF file written back as one .glb with some skin data replaced (internal: `dqskin lint --fix`). The
// file's own JSON document is kept as it was read, so everything the fix does not touch (materials,
// extensions, extras, names) stays; every buffer goes into the one BIN chunk, external images are
// embedded, and each replaced accessor gets a new, tightly packed bufferView at the end.
#pragma once

#include "dqskin/load.hpp"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace dqskin::gltf {

// New influences for one primitive: JOINTS_0.. and WEIGHTS_0.. replaced by `sets` sets (the old ones
// removed). `weights` are the values to store: for normalized integers exact multiples of 1/255 or 1/65535.
struct InfluenceEdit {
  size_t mesh = 0, primitive = 0;
  size_t vertices = 0, sets = 1;
  int joints_component = 5121;   // unsigned byte or short
  int weights_component = 5126;  // float, or normalized unsigned byte or short
  std::vector<uint32_t> joints;  // sets × 4 per vertex, vertex-major
  std::vector<double> weights;
};

// New output keys for one animation sampler (rotation): `values` as floats, stored in `component` (float,
// or normalized byte, unsigned byte, short, unsigned short as the original was).
struct KeyEdit {
  size_t animation = 0, sampler = 0;
  int component = 5126;
  std::vector<float> values;
};

// Skins whose `skeleton` property is removed (it is optional; one that is not a common root of the joints
// is wrong, and viewers that trust it misplace the skeleton).
// Channels removed, as (animation, channel): the later ones of channels that share a target (§3.11).
struct FileEdits {
  std::vector<InfluenceEdit> influences;
  std::vector<KeyEdit> keys;
  std::vector<size_t> drop_skeleton;
  std::vector<std::pair<size_t, size_t>> drop_channels;
};

// The .glb bytes of `path` with the edits applied. Throws InputError for a file it cannot write back
// faithfully (EXT_meshopt_compression, KHR_draco_mesh_compression, an image that could not be read).
std::string fixed_glb(const std::string& path, const LoadOptions& options, const FileEdits& edits);

}  // namespace dqskin::gltf
