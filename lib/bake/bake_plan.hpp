// Bake's reading of a job plan (internal to lib/bake): which frames a clip deforms and which files it
// writes, for the formats asked for.
#pragma once

#include "dqskin/bake.hpp"
#include "../job/job_plan.hpp"

namespace dqskin::texture {
struct DecodeCheck;
}

namespace dqskin::bake_detail {

// The clips one texture holds (docs/DESIGN.md §4.9): one clip, in the clip's folder, or with
// --combine-clips every clip of the input, in the input's folder, the clips' frames one after another.
struct TextureClips {
  std::vector<const ClipPlan*> clips;
  std::string folder;  // relative to the output folder
  std::string what;    // for messages: "clip Walk", "clips Survey, Walk, Run"
  bool mine = false;   // this shard writes the textures (a combined texture goes with its first clip)
  // A shard's slice of one clip's textures (ClipPlan::texture_first, texture_end): frames [first, end),
  // whose rows it writes as pieces and whose figures it checks; `head`: it writes the other files too.
  // The whole texture when end is 0.
  size_t first = 0, end = 0;
  bool head = true;
  size_t frames() const;  // of every clip together
  bool sliced() const { return end != 0 && (first != 0 || end != frames()); }
};

// One clip's textures as this shard bakes them.
TextureClips clip_texture_set(const ClipPlan& clip);

// The texture sets of an input: one per clip (with the shard's slice of it), or one of every clip with
// `combine`.
std::vector<TextureClips> texture_clip_sets(const InputPlan& input, bool combine);

// The formats a clip's own pass bakes: with --combine-clips the textures (vat, bones) are baked once per
// input, from their own pass over every clip, so they leave the clips' passes.
unsigned per_clip_formats(const BakeOptions& options);

// Frames to deform: all of them when the morph animation is due; a texture slice's frames and its
// neighbours (the clip's first frame and the one after the slice, which its check compares with); and the
// shard's own per-frame outputs' frames.
std::vector<size_t> frames_to_deform(const ClipPlan& clip, unsigned formats);

// Every frame time and, between neighbours, the midpoint: t0, (t0+t1)/2, t1, … (2n − 1 times; frame f at
// index 2f). The texture passes sample there: what a runtime interpolating between frames shows.
std::vector<double> frames_and_midpoints(const std::vector<double>& times);

// The skinned mesh written beside a clip's bone textures (texture/bones_mesh_glb.hpp).
inline constexpr const char* kBonesMeshFile = "bones_mesh.glb";

// The files one clip writes, relative to the output folder, for the formats (and texture profiles) asked
// for. Throws InputError when a texture profile cannot hold the clip.
std::vector<std::string> planned_files(const InputPlan& input, const ClipPlan& clip, const BakeOptions& options);

// The texture files of a combined set (vat and bones), relative to the output folder, as planned_files
// lists a clip's. Throws InputError when a profile cannot hold the clips.
std::vector<std::string> planned_texture_files(const InputPlan& input, const TextureClips& set, const BakeOptions& options);

// A decode-back check's figures as the bake reports them, for texture `texture` of `clip` of `input`.
TextureCheck texture_check(const texture::DecodeCheck& check, const std::string& input, const std::string& clip,
                           const std::string& texture);

}  // namespace dqskin::bake_detail
