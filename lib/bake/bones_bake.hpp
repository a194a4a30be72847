// The bone textures of one clip, or with --combine-clips of every clip of an input (docs/DESIGN.md §4.9), in
// a bake (internal to lib/bake): one texture per skin the input's instances
// use, in the profile asked for, each read back from its written file and checked before it is committed:
// the mesh skinned through the profile's shader model (texture/bone_profiles.hpp) from the texels read
// back, against the bake's deformed meshes at every frame, and halfway between frames where runtimes that
// sample bone textures show the earlier frame (Babylon.js's baked animation floors the frame; Cocos's baked
// animation steps frame by frame).
#pragma once

#include "bake_plan.hpp"
#include "../write/glb_appearance.hpp"

#include "dqskin/deformer.hpp"

#include <string>
#include <utility>
#include <vector>

namespace dqskin::bake_detail {

struct BonesClipResult {
  std::vector<std::pair<std::string, Committed>> files;  // relative to the output folder
  std::vector<TextureCheck> checks;                      // one per skin and clip, when checked
};

// Writes the set's bones_mesh.glb and, per skin, writes and (with options.textures.check, using `deformer`,
// which may then not be null) checks the bone textures of the set's clips, each clip on its own, then commits
// them. Throws InputError naming the clip and skin when a check fails
// (--max-error, one pose for a moving clip, a texel that is not finite); nothing is then committed.
// `look`: the source's materials and images for bones_mesh.glb (glb::read_look), or null.
BonesClipResult bake_bones_clip(Deformer* deformer, const InputPlan& input, const TextureClips& set,
                                const BakeOptions& options, const CommitOptions& commit, unsigned threads,
                                const glb::Appearance* look = nullptr);

}  // namespace dqskin::bake_detail
