// Bake's reading of a job plan (internal to lib/bake): which frames a clip deforms and which files it
// writes, for the formats asked for.
#pragma once

#include "dqskin/bake.hpp"
#include "../job/job_plan.hpp"

namespace dqskin::texture {
struct DecodeCheck;
}

namespace dqskin::bake_detail {

// Frames to deform: all of them when whole-animation textures or the morph animation are due, else the
// shard's own.
std::vector<size_t> frames_to_deform(const ClipPlan& clip, unsigned formats);

// Every frame time and, between neighbours, the midpoint: t0, (t0+t1)/2, t1, … (2n − 1 times; frame f at
// index 2f). The texture passes sample there: what a runtime interpolating between frames shows.
std::vector<double> frames_and_midpoints(const std::vector<double>& times);

// The skinned mesh written beside a clip's bone textures (texture/bones_mesh_glb.hpp).
inline constexpr const char* kBonesMeshFile = "bones_mesh.glb";

// The files one clip writes, relative to the output folder, for the formats (and texture profiles) asked
// for. Throws InputError when a texture profile cannot hold the clip.
std::vector<std::string> planned_files(const InputPlan& input, const ClipPlan& clip, const BakeOptions& options);

// A decode-back check's figures as the bake reports them, for texture `texture` of `clip` of `input`.
TextureCheck texture_check(const texture::DecodeCheck& check, const std::string& input, const std::string& clip,
                           const std::string& texture);

}  // namespace dqskin::bake_detail
