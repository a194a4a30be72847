// `dqskin bake INPUT… -o OUTDIR`: the command asset builds run. Reports progress as a bar on a terminal
// or as JSON lines, and a summary at the end; SIGINT and SIGTERM stop it cleanly.
#include "commands.hpp"
#include "console.hpp"
#include "default_input.hpp"
#include "exit_codes.hpp"
#include "guarded_run.hpp"
#include "interrupt.hpp"
#include "progress.hpp"

#include "dqskin/bake.hpp"
#include "../lib/base/byte_size.hpp"
#include "dqskin/error.hpp"
#include "dqskin/version.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>

namespace dqskin::cli {
namespace {

struct BakeSettings {
  std::vector<std::string> inputs;  // empty: the bundled default input
  PlanSettings plan;
  std::string mode = "dqs";
  std::string formats = "glb";
  std::string backend = "auto";
  unsigned jobs = 0;
  size_t gpu_memory_mb = 512;
  bool dry_run = false, quiet = false, json_progress = false, force = false, verbose = false;
  TextureOptions textures;
  std::string shader_kit;
  std::string max_error;  // "0.001" (scene units) or "0.1%" (of the clip's bounding-box diagonal)
  std::string max_bytes;  // "64M"
  bool no_check = false;
  bool morph_quantize = false;
  std::string glb_images = "shared";
  std::string sockets;              // "Hand_L,Hand_R"
  std::string root_motion = "none";  // none, in-place
  std::string root_joint;
};

// --sockets, --root-motion, --root-joint (docs/DESIGN.md §3.11).
MotionOptions to_motion_options(const BakeSettings& s) {
  MotionOptions m;
  for (size_t start = 0; !s.sockets.empty() && start <= s.sockets.size();) {
    const size_t comma = std::min(s.sockets.find(',', start), s.sockets.size());
    m.sockets.push_back(s.sockets.substr(start, comma - start));
    start = comma + 1;
  }
  if (s.root_motion != "none" && s.root_motion != "in-place")
    throw InputError("--root-motion '" + s.root_motion + "' is not one of none, in-place");
  m.in_place = s.root_motion == "in-place";
  if (!s.root_joint.empty() && !m.in_place) throw InputError("--root-joint is for --root-motion in-place");
  m.root_joint = s.root_joint;
  return m;
}

// --max-error: a length in scene units, or a percentage of the clip's bounding-box diagonal.
void parse_max_error(const std::string& text, TextureOptions& t) {
  if (text.empty()) return;
  const LengthOrPercent e = parse_length_or_percent(
      text, false, "--max-error '" + text + "' is not a positive length or percentage (0.001, 0.1%)");
  t.max_error = e.value;
  t.max_error_relative = e.relative;
}

BakeOptions to_options(const BakeSettings& s) {
  BakeOptions o;
  o.plan = to_plan_options(s.plan);
  if (!parse_blend_mode(s.mode, o.mode)) throw InputError("--mode '" + s.mode + "' is not one of lbs, dqs, dib");
  o.formats = parse_bake_formats(s.formats);
  if (!parse_backend(s.backend, o.backend)) throw InputError(unknown_backend(s.backend));
  o.gpu_memory = s.gpu_memory_mb << 20;
  o.jobs = s.jobs;
  o.dry_run = s.dry_run;
  o.overwrite = s.force ? Overwrite::kReplace : Overwrite::kRefuseDifferent;
  o.textures = s.textures;
  o.shader_kit = s.shader_kit;
  o.textures.check = !s.no_check;
  o.morph.quantize = s.morph_quantize;
  o.glb_images = parse_glb_images(s.glb_images);
  o.motion = to_motion_options(s);
  parse_max_error(s.max_error, o.textures);
  if (!s.max_bytes.empty()) o.textures.max_bytes = parse_byte_size(s.max_bytes, "--max-bytes");
  return o;
}

void print_summary(const BakeSettings& s, const BakeReport& r) {
  size_t written = 0, unchanged = 0;
  uint64_t bytes = 0;
  for (const BakeOutput& o : r.outputs) {
    (o.unchanged ? unchanged : written) += 1;
    bytes += o.size;
  }
  if (s.json_progress) {
    nlohmann::json failures = nlohmann::json::array();
    for (const InputResult& in : r.inputs)
      if (!in.error.empty()) failures.push_back({{"input", in.path}, {"error", in.error}});
    const BakeStageTimes& t = r.times;
    std::cout << json_text(nlohmann::json{{"event", "summary"},
                                {"frames", r.frames_total},
                                {"files_written", written},
                                {"files_unchanged", unchanged},
                                {"bytes", bytes},
                                {"manifest", r.manifest},
                                {"deformer", r.deformer},
                                {"backend", r.gpu.backend},
                                {"renderer", r.gpu.renderer},
                                {"wall_s", r.wall_seconds},
                                {"stage_s", {{"load", t.load}, {"sample", t.sample}, {"deform", t.deform},
                                             {"readback", t.readback}, {"encode", t.encode}, {"write", t.write},
                                             {"check", t.check}}},
                                {"failures", failures}})
              << std::endl;
  }
  print_input_messages(r.inputs, s.quiet, s.verbose);
  const bool all_failed = std::all_of(r.inputs.begin(), r.inputs.end(), [](const InputResult& in) { return !in.error.empty(); });
  if (s.quiet || s.json_progress || all_failed) return;  // then the errors above are the whole story
  const BakeStageTimes& t = r.times;
  const size_t baked = size_t(std::count_if(r.inputs.begin(), r.inputs.end(), [](const InputResult& in) { return in.error.empty(); }));
  std::fprintf(stderr, "baked %zu of %zu input%s in %.2f s: %zu frames deformed on %s at %.1f frames/s; %zu files written, %zu unchanged, %.1f MB\n",
               baked, r.inputs.size(), r.inputs.size() == 1 ? "" : "s", r.wall_seconds, r.frames_total,
               r.deformer.empty() ? "nothing" : r.deformer.c_str(),
               r.wall_seconds > 0 ? double(r.frames_total) / r.wall_seconds : 0.0, written, unchanged, double(bytes) / 1e6);
  std::fprintf(stderr,
               "stages (thread-seconds): load %.2f, sample %.2f, deform %.2f, readback %.2f, encode %.2f, write %.2f, "
               "check %.2f\n",
               t.load, t.sample, t.deform, t.readback, t.encode, t.write, t.check);
  if (s.verbose)
    std::fprintf(stderr, "deformer: %s; backend: %s, %s\n", r.deformer.c_str(), r.gpu.backend.c_str(), r.gpu.renderer.c_str());
  std::fprintf(stderr, "manifest: %s\n", printable(r.manifest).c_str());
}

// Bakes every input's animations into the asked formats. Returns an ExitCode.
int run_bake(const BakeSettings& given) {
  BakeSettings settings = given;
  ProgressPrinter progress(settings.json_progress, settings.quiet);
  return guarded_run("bake", [&] {
    if (settings.inputs.empty()) settings.inputs.push_back(unpack_default_input("bake", settings.plan.out_dir, settings.quiet));
    if (settings.plan.out_dir.empty()) throw InputError("-o OUTDIR is required when inputs are given");
    BakeOptions options = to_options(settings);
    options.cancel = catch_interrupts("bake");

    const BakeReport report = bake(settings.inputs, options, [&](const JobProgress& p) { progress(p); });
    progress.done();
    if (options.dry_run) {
      for (const BakeOutput& o : report.outputs) std::cout << printable(options.plan.out_dir + '/' + o.path) << '\n';
      if (!settings.quiet)
        for (const std::string& line : report.plans) std::fprintf(stderr, "%s\n", printable(line).c_str());
      print_input_messages(report.inputs, settings.quiet, settings.verbose);
      const bool any_planned = std::any_of(report.inputs.begin(), report.inputs.end(),
                                           [](const InputResult& in) { return in.error.empty(); });
      if (!settings.quiet && any_planned)
        std::fprintf(stderr, "dry run: %zu frames to deform (%.4g vertex-frames), up to %s in %zu files; %s free on the output's file system\n",
                     report.frames_total, double(report.vertex_frames), byte_size(report.planned_bytes).c_str(),
                     report.outputs.size(), byte_size(report.free_bytes).c_str());
    } else {
      print_summary(settings, report);
    }
    return job_exit_status(report.inputs, settings.quiet, "baked");
  }, [&] { progress.done(); });
}

}  // namespace

Command add_bake_command(CLI::App& app) {
  auto settings = std::make_shared<BakeSettings>();
  BakeSettings& bake = *settings;
  CLI::App* bake_cmd = app.add_subcommand(
      "bake", "Deform whole animations and write per-frame meshes (glb, ply, obj), vertex-animation textures "
              "(vat), bone textures (bones) and morph-target animations (morph), with a manifest of every file's "
              "SHA-256");
  bake_cmd->add_option("INPUT", bake.inputs,
                       ".gltf or .glb files. Without any, the bundled textured_cylinder rig is baked into a new "
                       "temporary folder, which is printed");
  add_plan_settings(*bake_cmd, bake.plan, "bake");
  bake_cmd->add_option("--mode", bake.mode, "Blending: lbs (linear), dqs (dual quaternion DLB), dib (iterative, CPU)")
      ->type_name("lbs|dqs|dib")
      ->capture_default_str();
  bake_cmd->add_option("--format", bake.formats, "Outputs, any of glb,ply,obj,vat,bones,morph (comma-separated)")
      ->type_name("LIST")
      ->capture_default_str();
  bake_cmd->add_option("--glb-images", bake.glb_images,
                       "glb: where the frames' images go: shared (written once into each animation's folder, "
                       "referenced by every frame), embed (in every frame: each file stands alone) or none "
                       "(materials keep their factors)")
      ->type_name("embed|shared|none")
      ->capture_default_str();
  bake_cmd->add_option("--vat-profile", bake.textures.vat_profile,
                       "Vertex-animation texture layout: dqskin (absolute positions, docs/DESIGN.md §4.3), openvat "
                       "(OpenVAT's Blender add-on and engine kits), houdini (SideFX Labs VAT 3, soft body)")
      ->type_name("NAME")
      ->capture_default_str();
  bake_cmd->add_option("--bones-profile", bake.textures.bones_profile,
                       "Bone texture layout: dq (docs/DESIGN.md §4.1), dq-cocos (Cocos Creator), mat3x4 (rows of the "
                       "joint matrix, PlayCanvas), mat4 (columns, Babylon.js and three.js)")
      ->type_name("NAME")
      ->capture_default_str();
  bake_cmd->add_option("--encoding", bake.textures.encoding,
                       "Texel type: float or half (EXR), png16 or png8 (remapped to recorded bounds). Default: the "
                       "profile's")
      ->type_name("TYPE");
  bake_cmd->add_option("--exr-compression", bake.textures.exr_compression,
                       "Lossless EXR compression: zip (the default: smallest), piz (faster to write, usually "
                       "larger), rle, zips or none")
      ->type_name("NAME");
  bake_cmd->add_option("--normals", bake.textures.normals,
                       "VAT normals: none, separate (an image of their own), packed (as the profile packs them), "
                       "oct8 or oct16 (dqskin: octahedral in a PNG). Default: the profile's")
      ->type_name("MODE");
  bake_cmd->add_option("--max-size", bake.textures.max_size,
                       "Largest side of a texture, in texels (default 8192: desktop and recent mobile GPUs; 4096 fits "
                       "every WebGL2 device, 16384 mostly desktops). Layouts wrap rows and pages to fit; one that "
                       "cannot fit is refused with the size that would")
      ->type_name("TEXELS")
      ->check(CLI::Range(size_t(1), size_t(1) << 20));
  bake_cmd->add_flag("--pot", bake.textures.pot, "Pad textures to power-of-two sizes");
  bake_cmd->add_flag("--combine-clips", bake.textures.combine_clips,
                     "vat, bones: one texture of every clip of an input (in OUTDIR/<input>/, the clips' frames one "
                     "after another, a clip table in the side file) instead of one per clip; not for the houdini "
                     "and dq-cocos profiles, whose runtimes play one clip per texture");
  bake_cmd->add_option("--shader-kit", bake.shader_kit,
                       "Write the reading shaders of the bake's layouts for these engines into OUTDIR/shader_kit/: "
                       "any of unity,unreal,godot,three (comma-separated), or all")
      ->type_name("LIST");
  bake_cmd->add_option("--max-error", bake.max_error,
                       "Fail a clip whose textures decode further than this from the deformed mesh, at a frame or "
                       "between two: a length in scene units, or a percentage of the clip's bounding-box diagonal. "
                       "For morph, the keyframe reduction's budget: keep only the frames that interpolating the kept "
                       "ones cannot reproduce within it, at every baked frame")
      ->type_name("LENGTH|P%");
  bake_cmd->add_option("--max-bytes", bake.max_bytes,
                       "GPU memory a clip's vertex-animation textures may take (uncompressed: 64M, 1.5G). With "
                       "--max-error or --max-bytes the texel type (unless --encoding) and a frame decimation are "
                       "chosen to fit; --dry-run prints the choices")
      ->type_name("BYTES");
  bake_cmd->add_flag("--morph-quantize", bake.morph_quantize,
                     "morph: KHR_mesh_quantization, positions on a 15-bit grid that the node's transform decodes "
                     "(the grid's error counts against --max-error), normals as normalized 16-bit integers");
  bake_cmd->add_option("--sockets", bake.sockets,
                       "Record these nodes' world transforms (joints that hold props: hands, weapons) at every frame, "
                       "as matrices and dual quaternions, in each animation's sockets.json and sockets.exr. Node "
                       "names, comma-separated, or #N for node N")
      ->type_name("NODE,...");
  bake_cmd->add_option("--root-motion", bake.root_motion,
                       "in-place: take the root's motion on the ground (x, z and the turn about +Y) out of every "
                       "frame of every output, and write it per frame to each animation's root_motion.json")
      ->type_name("none|in-place")
      ->capture_default_str();
  bake_cmd->add_option("--root-joint", bake.root_joint,
                       "The root for --root-motion in-place (a node name or #N). Default: the skin's skeleton node, "
                       "else its topmost joint that is an ancestor of all the others")
      ->type_name("NODE");
  bake_cmd->add_flag("--no-check", bake.no_check,
                     "Skip the decode-back check (every texture read back from its file and decoded as its shader "
                     "does, against the deformed meshes)");
  bake_cmd->add_option("--backend", bake.backend,
                       "Deformer: auto (a hardware GPU through EGL when there is one, else fast-cpu), egl, osmesa, "
                       "fast-cpu (vectorized float, every core), or cpu (the double-precision reference)")
      ->type_name("NAME")
      ->capture_default_str();
  add_scene_and_shard(*bake_cmd, bake.plan,
                      "Bake only shard I of N of the (input, animation, frame) work; the N shards' outputs "
                      "together equal the whole bake");
  bake_cmd->add_option("-j,--jobs", bake.jobs, "Encoder threads (default: one per core)")
      ->type_name("N")
      ->check(CLI::Range(1u, 1024u));
  bake_cmd->add_option("--gpu-memory", bake.gpu_memory_mb, "GPU output buffer budget, in MiB")
      ->type_name("MIB")
      ->capture_default_str()
      ->check(CLI::Range(size_t(1), size_t(1) << 20));
  bake_cmd->add_flag("-n,--dry-run", bake.dry_run, "List the files that would be written; write nothing");
  bake_cmd->add_flag("-q,--quiet", bake.quiet, "Print nothing but errors");
  bake_cmd->add_flag("--json-progress", bake.json_progress,
                     "Print progress and the final summary as JSON lines on standard output");
  bake_cmd->add_flag("-f,--force", bake.force,
                     "Overwrite existing outputs that differ (without it they are an error; equal ones are kept)");
  bake_cmd->add_flag("-v,--verbose", bake.verbose,
                     "Also print the OpenGL backend and renderer, and the inputs' notices (a skinned mesh node's "
                     "transform, which glTF ignores)");
  bake_cmd->footer(
      "Outputs: OUTDIR/<input name>/<animation>/frame_NNNN.{glb,ply,obj} (frame numbers zero-padded, so name order is\n"
      "frame order), materials.mtl, vat_positions.exr, vat_normals.exr, vat.json, bones_skinK.{exr,json},\n"
      "animation.glb (morph), sockets.{json,exr} (--sockets), root_motion.json (--root-motion); with\n"
      "--combine-clips the textures of every animation in OUTDIR/<input name>/; OUTDIR/shader_kit/<engine>/\n"
      "(--shader-kit); and OUTDIR/manifest.json (manifest.shard-I-of-N.json for a shard). Files appear complete\n"
      "or not at all.\n"
      "Exit status: 0 success, 1 some inputs failed (the others baked), 2 usage or input error, 3 no OpenGL context.\n"
      "Examples:\n"
      "  dqskin bake Fox.glb -o out --format glb,vat\n"
      "  dqskin bake *.glb -o out --fps 24 --frames 0:47 --mode lbs\n"
      "  dqskin bake *.glb -o out --shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT");
  return {bake_cmd, [settings] { return run_bake(*settings); }};
}

}  // namespace dqskin::cli
