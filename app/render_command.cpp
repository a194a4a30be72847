// `dqskin render INPUT… -o OUTDIR`: every frame of the inputs' animations drawn offscreen into PNG or EXR
// images, with bake's frame, animation, mode, backend and shard flags and its exit statuses.
#include "commands.hpp"
#include "console.hpp"
#include "default_input.hpp"
#include "exit_codes.hpp"
#include "guarded_run.hpp"
#include "interrupt.hpp"
#include "progress.hpp"

#include "dqskin/error.hpp"
#include "../lib/base/output_journal.hpp"
#include "dqskin/render.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

namespace dqskin::cli {
namespace {

struct RenderSettings {
  std::vector<std::string> inputs;
  std::string out_dir;
  LoadSettings load;
  FrameSelection selection;
  std::string shard;
  std::string mode = "dqs";
  std::string backend = "auto";
  int scene = -1;
  std::string size;  // WxH; empty: 512x512, or 512 high in a --camera's aspect ratio
  std::string background = "0.2,0.2,0.2";  // sRGB
  int samples = 4;
  std::string shade = "lit";
  std::string joint;  // --shade weights
  std::optional<double> yaw, pitch, distance, fov;
  bool ortho = false;
  std::string camera;  // a node with a glTF camera
  std::string format = "png";
  bool sheet = false, gif = false;
  int sheet_cell = 256;
  bool quiet = false, json_progress = false, force = false, verbose = false;
};

// "WxH", each side 1 to 16384.
void parse_size(const std::string& text, RendererOptions& o) {
  const size_t x = text.find('x');
  auto side = [&](const std::string& s) {
    if (s.empty() || s.size() > 5 || s.find_first_not_of("0123456789") != std::string::npos)
      throw InputError("--size '" + text + "' is not WxH (e.g. 512x512)");
    const int n = std::stoi(s);
    if (n < 1 || n > 16384) throw InputError("--size '" + text + "': each side must be 1 to 16384 pixels");
    return n;
  };
  if (x == std::string::npos) throw InputError("--size '" + text + "' is not WxH (e.g. 512x512)");
  o.width = side(text.substr(0, x));
  o.height = side(text.substr(x + 1));
}

// sRGB 8-bit code to linear, so that "--background #336699" looks like that color in the PNG.
float srgb_to_linear(double s) { return float(s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4)); }

// "R,G,B" or "R,G,B,A" in sRGB 0..1 (alpha linear), or "#RRGGBB" / "#RRGGBBAA".
glm::vec4 parse_background(const std::string& text) {
  const std::string problem = "--background '" + text + "' is not R,G,B[,A] (0 to 1, sRGB) or #RRGGBB[AA]";
  std::vector<double> c;
  if (!text.empty() && text[0] == '#') {
    const std::string hex = text.substr(1);
    if ((hex.size() != 6 && hex.size() != 8) || hex.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos)
      throw InputError(problem);
    for (size_t i = 0; i < hex.size(); i += 2) c.push_back(double(std::stoi(hex.substr(i, 2), nullptr, 16)) / 255.0);
  } else {
    std::stringstream in(text);
    std::string part;
    while (std::getline(in, part, ',')) {
      size_t used = 0;
      double v = 0;
      try {
        v = std::stod(part, &used);
      } catch (const std::exception&) {
        throw InputError(problem);
      }
      if (used != part.size() || !(v >= 0 && v <= 1)) throw InputError(problem);
      c.push_back(v);
    }
    if (c.size() != 3 && c.size() != 4) throw InputError(problem);
  }
  return {srgb_to_linear(c[0]), srgb_to_linear(c[1]), srgb_to_linear(c[2]), float(c.size() == 4 ? c[3] : 1.0)};
}

RenderOptions to_options(const RenderSettings& s) {
  RenderOptions o;
  o.out_dir = s.out_dir;
  o.load = to_load_options(s.load);
  o.clips = s.selection.anim;
  o.frames = to_frame_spec(s.selection);
  if (!parse_blend_mode(s.mode, o.mode)) throw InputError("--mode '" + s.mode + "' is not one of lbs, dqs, dib");
  if (!parse_backend(s.backend, o.backend)) throw InputError(unknown_backend(s.backend));
  o.scene = s.scene;
  if (!s.shard.empty()) o.shard = parse_shard(s.shard);
  parse_size(s.size.empty() ? "512x512" : s.size, o.renderer);
  o.size_from_camera = s.size.empty();
  o.renderer.samples = s.samples;
  o.renderer.background = parse_background(s.background);
  if (!parse_shade(s.shade, o.renderer.shade)) throw InputError("--shade '" + s.shade + "' is not one of lit, normals, weights, mode-diff");
  if (o.renderer.shade == Shade::kWeights && s.joint.empty()) throw InputError("--shade weights needs --joint NAME");
  o.joint = s.joint;
  if (!parse_image_format(s.format, o.format)) throw InputError("--format '" + s.format + "' is not one of png, exr");
  if (s.yaw) o.camera.yaw = *s.yaw;
  if (s.pitch) o.camera.pitch = *s.pitch;
  if (s.fov) o.camera.fov = *s.fov;
  o.camera.distance = s.distance;
  o.camera.ortho = s.ortho;
  if (!s.camera.empty() && (s.yaw || s.pitch || s.distance || s.fov || s.ortho))
    throw InputError("--camera sets the view; it cannot be combined with --yaw, --pitch, --distance, --fov or --ortho");
  o.camera_node = s.camera;
  if (s.sheet_cell < 1 || s.sheet_cell > 4096) throw InputError("--sheet-cell " + std::to_string(s.sheet_cell) + ": must be 1 to 4096 pixels");
  o.sheet = s.sheet;
  o.sheet_cell = s.sheet_cell;
  o.gif = s.gif;
  o.overwrite = s.force ? Overwrite::kReplace : Overwrite::kRefuseDifferent;
  return o;
}

// Renders every frame of every input's animations into images. Returns an ExitCode.
int run_render(const RenderSettings& given) {
  RenderSettings settings = given;
  ProgressPrinter progress(settings.json_progress, settings.quiet);
  OutputJournal out_folder;  // the output folder, when this run creates it: removed again if nothing rendered
  return guarded_run("render", [&] {
    if (settings.inputs.empty()) settings.inputs.push_back(unpack_default_input("render", settings.out_dir, settings.quiet));
    if (settings.out_dir.empty()) throw InputError("-o OUTDIR is required when inputs are given");
    RenderOptions options = to_options(settings);
    options.cancel = catch_interrupts("render");
    out_folder.make_folders(options.out_dir);
    const RenderReport report =
        render(settings.inputs, options, [&](const JobProgress& p) { progress(p); });
    progress.done();
    print_input_messages(report.inputs, settings.quiet, settings.verbose);
    const size_t failed = failed_inputs(report.inputs);
    if (failed < report.inputs.size()) out_folder.keep();
    // mode-diff: what the heat map's top color stands for, per animation.
    nlohmann::json scales = nlohmann::json::array();
    for (const ModeDiffScale& m : report.mode_diff) {
      scales.push_back({{"input", m.input}, {"animation", m.clip}, {"max_distance", m.max_distance}});
      if (!settings.quiet && !settings.json_progress)
        std::fprintf(stderr, "mode-diff %s %s: red = %.6g (largest |lbs - %s| position distance), dark blue = 0\n",
                     printable(m.input).c_str(), printable(m.clip).c_str(), m.max_distance, settings.mode == "lbs" ? "dqs" : settings.mode.c_str());
    }
    if (settings.json_progress) {
      std::cout << json_text(nlohmann::json{{"event", "summary"},           {"mode_diff", scales},          {"frames", report.frames_total},
                                  {"files", report.outputs.size()}, {"deformer", report.deformer}, {"backend", report.gpu.backend},
                                  {"renderer", report.gpu.renderer}, {"failed_inputs", failed},
                                  {"wall_s", report.wall_seconds}})
                << std::endl;
    } else if (!settings.quiet && failed < report.inputs.size()) {
      size_t frames = 0;  // not report.outputs: --sheet and --gif add files that are not frames
      for (const InputResult& in : report.inputs) frames += in.frames;
      std::fprintf(stderr, "rendered %zu frames of %zu input%s in %.2f s into %s\ndeformed on %s, drawn by %s\n", frames,
                   report.inputs.size() - failed, report.inputs.size() - failed == 1 ? "" : "s", report.wall_seconds,
                   printable(options.out_dir).c_str(), report.deformer.c_str(), report.gpu.renderer.c_str());
    }
    return job_exit_status(report.inputs, settings.quiet, "rendered");
  }, [&] { progress.done(); }, &out_folder);
}

}  // namespace

Command add_render_command(CLI::App& app) {
  auto settings = std::make_shared<RenderSettings>();
  RenderSettings& render = *settings;
  CLI::App* render_cmd = app.add_subcommand(
      "render", "Draw the deformed meshes of every frame offscreen into PNG (8-bit sRGB) or EXR (linear) images, "
                "through the same headless OpenGL context as bake");
  render_cmd->add_option("INPUT", render.inputs,
                         ".gltf or .glb files. Without any, the bundled textured_cylinder rig is rendered into a new "
                         "temporary folder (printed)");
  render_cmd->add_option("-o,--out", render.out_dir, "Output folder (created when missing)")->type_name("OUTDIR");
  add_frame_selection(*render_cmd, render.selection, "render");
  add_load_settings(*render_cmd, render.load);
  add_max_influences(*render_cmd, render.load);
  render_cmd->add_option("--mode", render.mode,
                         "Blending: lbs (linear), dqs (dual quaternion DLB) or dib (iterative, deformed on the CPU)")
      ->type_name("lbs|dqs|dib")
      ->capture_default_str();
  render_cmd->add_option("--backend", render.backend,
                         "Deformer, and the headless OpenGL backend that draws: auto (deform on a hardware GPU when "
                         "there is one, else fast-cpu; draw with EGL, then OSMesa), egl, osmesa (deform and draw there), "
                         "fast-cpu or cpu (deform with the vectorized float or the double-precision CPU deformer, "
                         "draw as auto)")
      ->type_name("NAME")
      ->capture_default_str();
  render_cmd->add_option("--scene", render.scene, "Scene index (default: the file's default scene)")->type_name("INDEX");
  render_cmd->add_option("--shard", render.shard, "Render only shard I of N of the (input, animation, frame) work")
      ->type_name("I/N");
  render_cmd->add_option("--size", render.size,
                         "Image size in pixels (default 512x512; with --camera, 512 high in the camera's aspect ratio)")
      ->type_name("WxH");
  render_cmd->add_option("--background", render.background, "Background color: R,G,B[,A] (0 to 1, sRGB) or #RRGGBB[AA]")
      ->type_name("COLOR")
      ->capture_default_str();
  render_cmd->add_option("--samples", render.samples, "Multisample anti-aliasing samples per pixel")
      ->type_name("N")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  render_cmd->add_option("--shade", render.shade,
                         "lit (material base color factor, texture and COLOR_0; key light and ambient), normals (world normal as color), "
                         "weights (influence of --joint as a heat map), mode-diff (distance between the lbs positions and "
                         "those of --mode, dqs by default, as a heat map, its scale printed)")
      ->type_name("lit|normals|weights|mode-diff")
      ->capture_default_str();
  render_cmd->add_option("--joint", render.joint, "Joint node shown by --shade weights")->type_name("NAME");
  render_cmd->add_option("--yaw", render.yaw, "Camera turn about +Y from the front (+Z), degrees (default 35)")
      ->type_name("DEG");
  render_cmd->add_option("--pitch", render.pitch, "Camera elevation, degrees (default 20)")
      ->type_name("DEG")
      ->check(CLI::Range(-90.0, 90.0));
  render_cmd->add_option("--distance", render.distance,
                         "Camera distance from the center of the animation's bounding box (default: fit the box)")
      ->type_name("UNITS")
      ->check(CLI::PositiveNumber);
  render_cmd->add_option("--fov", render.fov, "Vertical field of view, degrees (default 35)")
      ->type_name("DEG")
      ->check(CLI::Range(1.0, 170.0));
  render_cmd->add_flag("--ortho", render.ortho, "Orthographic projection fitted to the bounding box");
  render_cmd->add_option("--camera", render.camera,
                         "See the frames through the glTF camera of the node named NODE, following its animation, instead "
                         "of the automatic camera (not with --yaw/--pitch/--distance/--fov/--ortho)")
      ->type_name("NODE");
  render_cmd->add_option("--format", render.format, "Image format: png (8-bit sRGB) or exr (32-bit linear float)")
      ->type_name("png|exr")
      ->capture_default_str();
  render_cmd->add_flag("--sheet", render.sheet,
                       "Also write a contact sheet per animation: OUTDIR/<input name>/<animation>/sheet.png");
  render_cmd->add_option("--sheet-cell", render.sheet_cell, "Width of a contact sheet cell in pixels (aspect kept)")
      ->type_name("PIXELS")
      ->capture_default_str();
  render_cmd->add_flag("--gif", render.gif,
                       "Also write an animated GIF per animation: OUTDIR/<input name>/<animation>/animation.gif");
  render_cmd->add_flag("-q,--quiet", render.quiet, "Print nothing but errors");
  render_cmd->add_flag("-v,--verbose", render.verbose,
                       "Also print the inputs' notices (a skinned mesh node's transform, which glTF ignores)");
  render_cmd->add_flag("--json-progress", render.json_progress,
                       "Print progress and the final summary as JSON lines on standard output");
  render_cmd->add_flag("-f,--force", render.force,
                       "Overwrite existing images that differ (without it they are an error; equal ones are kept)");
  render_cmd->footer(
      "Outputs: OUTDIR/<input name>/<animation>/frame_NNNN.{png,exr}, frame numbers as bake names them. The\n"
      "automatic camera is framed once on the bounding box of the whole animation, so the frames of an animation\n"
      "are comparable; --camera follows its node's animation, and the image keeps the camera's yfov (ymag) in the\n"
      "image's aspect ratio, never stretched.\n"
      "Surfaces are drawn from both sides (open meshes and mirrored instances stay visible); alphaMode MASK cuts\n"
      "out, BLEND is blended after the opaque surfaces in file order.\n"
      "--sheet and --gif show the frames this run renders; with --shard I/N only the shard's own frames, in\n"
      "sheet_shardIofN.png and animation_shardIofN.gif.\n"
      "Exit status: 0 success, 1 some inputs failed (the others rendered), 2 usage or input error, 3 no OpenGL context.\n"
      "Examples:\n"
      "  dqskin render Fox.glb -o frames\n"
      "  dqskin render arm.gltf -o frames --mode lbs --shade normals --size 256x256 --yaw 90 --ortho\n"
      "  dqskin render shot.glb -o frames --camera ShotCam --anim Walk --sheet");
  return {render_cmd, [settings] { return run_render(*settings); }};
}

}  // namespace dqskin::cli
