// The raw skin data of a glTF file, as plain data (internal: lib/load reads it, lib/lint checks and fixes
// it). The Asset keeps what deforming needs and the loader refuses what it cannot deform (joint indices
// out of range, negative weights); a linter must see exactly those, with the component type each was
// stored in. No tinygltf type appears here.
#pragma once

#include "animation_origins.hpp"
#include "dqskin/asset.hpp"
#include "dqskin/load.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace dqskin::gltf {

// glTF accessor.componentType values of skin data (§3.6.2.2).
constexpr int kComponentUnsignedByte = 5121;
constexpr int kComponentUnsignedShort = 5123;
constexpr int kComponentFloat = 5126;

// One JOINTS_n / WEIGHTS_n pair (§3.7.3.3): four influences per vertex, vertex-major.
struct InfluenceSet {
  int joints_component = kComponentUnsignedByte;  // unsigned byte or short
  int weights_component = kComponentFloat;        // float, or normalized unsigned byte or short
  std::vector<uint32_t> joints;                   // 4 per vertex, as stored (not checked against a skin)
  std::vector<double> weights;                    // 4 per vertex, normalized integers decoded (c / 255 …)
};

// A mesh primitive with influences, and the skins that deform it (from every node that draws its mesh
// with a skin; none when no node does).
struct SkinnedPrimitive {
  size_t mesh = 0, primitive = 0;
  size_t vertices = 0;
  std::vector<glm::vec3> positions;  // POSITION in bind space (quantized ones decoded)
  std::vector<InfluenceSet> sets;    // JOINTS_0/WEIGHTS_0, JOINTS_1/WEIGHTS_1, … in order
  std::vector<int> skins;            // sorted, unique
};

// Where a rotation channel of `structure.clips` comes from in the file, so that a fix can replace its
// sampler's output.
struct RotationSource {
  size_t clip = 0, channel = 0;  // indices into structure.clips[clip].channels
  size_t animation = 0, sampler = 0;
  int output_component = kComponentFloat;  // float, or normalized (unsigned) byte or short
};

struct SkinData {
  // Nodes (rest transforms, parents), scenes, skins (joints, inverse bind matrices, skeleton) and clips
  // (raw key values: rotations as stored, not renormalized), read and checked as the loader reads them.
  Asset structure;
  std::vector<SkinnedPrimitive> primitives;  // every primitive with JOINTS_0, in mesh and primitive order
  std::vector<RotationSource> rotations;     // every rotation channel of structure.clips
  std::vector<DuplicateChannel> duplicate_channels;  // channels that repeat a target (kept out of the clips)
  bool rewritable = true;                    // false when a fix cannot write the file back (see why_not)
  std::string why_not;
};

// Reads `path` (.gltf or .glb) under `options`' limits (the raw sets and positions count against
// max_memory too). Influence sets must come in pairs numbered from 0 without gaps, at most
// kMaxInfluenceSets of them (asset.hpp: the loader's bound too), with POSITION's count, JOINTS_n as
// unsigned byte or short, WEIGHTS_n as float or normalized unsigned byte or short (§3.7.3.3); their
// values are not judged. Throws InputError for a file that is not valid glTF otherwise.
SkinData read_skin_data(const std::string& path, const LoadOptions& options);

}  // namespace dqskin::gltf
