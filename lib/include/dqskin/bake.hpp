// `dqskin bake` as a library call (docs/DESIGN.md §1, the whole data flow): glTF files in, per-frame
// meshes, vertex-animation textures, bone textures and a manifest out, every file written atomically.
#pragma once

#include "dqskin/animation.hpp"
#include "dqskin/atomic_file.hpp"
#include "dqskin/deformer.hpp"
#include "dqskin/glb_images.hpp"
#include "dqskin/gpu_context.hpp"
#include "dqskin/job.hpp"
#include "dqskin/load.hpp"
#include "dqskin/skinning.hpp"

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace dqskin {

enum class BakeFormat : unsigned { kGlb = 1, kPly = 2, kObj = 4, kVat = 8, kBones = 16, kMorph = 32 };

// "glb,ply" → the formats' bits. Throws InputError naming an unknown format.
unsigned parse_bake_formats(const std::string& list);

// How textures are laid out and checked (docs/formats.md, "Texture profiles"). Names are checked when the
// bake starts (InputError for unknown ones or combinations a profile cannot write).
struct TextureOptions {
  std::string vat_profile = "dqskin";  // dqskin, openvat, houdini
  std::string bones_profile = "dq";    // dq, dq-cocos, mat3x4, mat4
  std::string encoding;                // float, half, png16, png8; empty: the profile's default
  std::string normals;                 // none, separate, packed, oct8, oct16; empty: the profile's default
  std::string exr_compression;         // zip, piz, rle, zips, none; empty: zip
  // Largest side of an image in texels; 0: no bound. 8192: the GL_MAX_TEXTURE_SIZE of desktop GPUs and of
  // recent mobile ones (16384 is mostly desktop), so a texture baked by default loads on both.
  size_t max_size = 8192;
  bool pot = false;                    // pad images to powers of two
  double max_error = 0;                // largest decoded error allowed, scene units; 0: no limit (also the
                                       // morph format's keyframe budget, at every baked frame)
  bool max_error_relative = false;     // max_error is a fraction of the clip's bounding-box diagonal
  uint64_t max_bytes = 0;              // GPU memory a clip's vertex-animation textures may take; 0: no limit
  bool check = true;                   // read every texture back and decode it (the decode-back check)
  // One texture (per format and skin) holding every clip of an input, with a clip table in its side file,
  // instead of one per clip (docs/DESIGN.md §4.9). Not for the houdini and dq-cocos profiles, whose
  // runtimes play one clip per texture.
  bool combine_clips = false;
};

// The morph-target animation (docs/formats.md, "Morph-target animations"). Its keyframe budget is
// TextureOptions::max_error: one --max-error bounds whatever a clip's outputs decode to.
struct MorphOptions {
  bool quantize = false;  // KHR_mesh_quantization: positions on a 15-bit grid, normals as normalized SHORT
};

// Sockets and root motion (docs/formats.md, "Sockets and root motion"; docs/DESIGN.md §3.11). Names are node
// names, or "#N" for node N; one that no node has, or more than one, fails that input.
struct MotionOptions {
  std::vector<std::string> sockets;  // nodes whose world transforms each clip records (sockets.json, .exr)
  bool in_place = false;             // take the root's ground motion out of every frame (root_motion.json)
  std::string root_joint;            // the root for in_place; empty: the skin's skeleton, or its topmost joint
};

struct BakeOptions {
  // Output folder, inputs' loading, animations, frames, scene, and the shard this process bakes (its units
  // of the plan, lib/job/job_plan.hpp).
  PlanOptions plan;
  BlendMode mode = BlendMode::kDqs;
  unsigned formats = unsigned(BakeFormat::kGlb);
  // Where the glb frames' images go. Shared by default: a clip's frames are used together, from their
  // folder, and one copy of the images beside them keeps the folder at the size of its geometry
  // (docs/formats.md, "Bake outputs").
  GlbImages glb_images = GlbImages::kShared;
  TextureOptions textures;
  MorphOptions morph;
  // Shader kits written beside the bake, in OUTDIR/shader_kit/<engine>/ (docs/formats.md, "Shader kits"):
  // any of unity,unreal,godot,three, or all; empty: none. Written once per bake (by shard 0 when sharded);
  // an unknown name is an InputError when the bake starts.
  std::string shader_kit;
  MotionOptions motion;
  Backend backend = Backend::kAuto;  // a GL context, or cpu (the double-precision reference)
  size_t gpu_memory = size_t(512) << 20;
  unsigned jobs = 0;  // encoder threads; 0: one per core
  bool dry_run = false;  // plan and list, write nothing, start no GPU
  Overwrite overwrite = Overwrite::kRefuseDifferent;
  const std::atomic<bool>* cancel = nullptr;  // set from a signal handler: stop, leaving no partial files
};

// One file of the bake, its path relative to out_dir.
struct BakeOutput {
  std::string path;
  uint64_t size = 0;
  std::string sha256;
  bool unchanged = false;  // an equal file was already there (not part of the manifest)
};

// The decode-back check of one texture: what the written file decodes to, against the deformed meshes
// (scene units; normals in degrees).
struct TextureCheck {
  std::string input, clip;
  std::string texture;  // "vat", or "bones_skin<K>"
  double max_error = 0, p99_error = 0;                    // at the baked frames
  double max_midpoint_error = 0, p99_midpoint_error = 0;  // halfway between frames, interpolated linearly
  double max_normal_degrees = 0, max_midpoint_normal_degrees = 0;
  size_t samples = 0;  // vertex samples compared
  // A shard's slice of the texture (its frames only): the figures as a share that adds up over the
  // slices, as JSON, for `dqskin merge`; empty for a whole texture.
  std::string share;
};

// One clip's morph-target animation: how many keys it kept and what the file decodes to against the
// deformed meshes at every baked frame (interpolated between keys as a viewer does).
struct MorphCheck {
  std::string input, clip;
  size_t frames = 0, keyframes = 0;  // baked, and kept (the first is the mesh, each further one a target)
  double max_error = 0;              // scene units, largest over vertices and frames
  double max_normal_degrees = 0;     // between the interpolated normal and the deformed one
  uint64_t bytes = 0;                // the file's size
  size_t sparse_accessors = 0;       // accessors written sparse
  bool quantized = false;
};

// Thread-seconds per stage (encoding runs on several threads at once, so they may add up to more than
// the wall time).
struct BakeStageTimes {
  double load = 0, sample = 0, deform = 0, readback = 0, encode = 0, write = 0;
  double check = 0;  // textures' own passes: rest, planner, measuring, decode-back check (deforming included)
};

struct BakeReport {
  std::vector<InputResult> inputs;
  std::vector<BakeOutput> outputs;  // sorted by path; with dry_run, what would be written
  std::vector<TextureCheck> checks;  // sorted by input, clip and texture
  std::vector<MorphCheck> morphs;    // sorted by input and clip
  std::vector<std::string> plans;    // with dry_run and a texture budget: the planner's tables
  std::string manifest;             // path of the manifest written (empty for dry runs)
  GpuContextInfo gpu;               // what deformed: the GPU's context, or backend "fast-cpu" or "cpu"
  std::string deformer;             // describe(DeformPath): "gpu", "fast-cpu (avx2-fma)", "cpu-reference"
  size_t frames_total = 0;          // frames to deform over all inputs
  // The planned work, known before anything is written (with dry_run, what a bake would do): vertices ×
  // frames deformed, bytes of the files this shard writes (EXR at their uncompressed size, an upper bound),
  // and the bytes free on the output's file system.
  uint64_t vertex_frames = 0, planned_bytes = 0, free_bytes = 0;
  BakeStageTimes times;
  double wall_seconds = 0;
  bool any_failed() const;
};

// Bakes `inputs` (each on its own: a failing input is reported in BakeReport::inputs and the rest go on;
// the files it wrote are taken back). Throws NoGpuContext when a GPU backend is needed and none can be
// made, JobCancelled when options.cancel was set, InputError for options that cannot work (a bad
// --shard, two inputs whose outputs would collide) and, before writing anything, when the planned files
// cannot fit the free space of the output's file system. `progress` is called after every batch, from a
// worker thread.
BakeReport bake(const std::vector<std::string>& inputs, const BakeOptions& options,
                const std::function<void(const JobProgress&)>& progress = {});

}  // namespace dqskin
