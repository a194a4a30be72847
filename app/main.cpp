// dqskin command line: CLI11 fills one settings struct per command, one function runs it.
#include "commands.hpp"
#include "console.hpp"
#include "exit_codes.hpp"

#include "dqskin/error.hpp"
#include "dqskin/version.hpp"

#include <CLI/CLI.hpp>

#include <iostream>
#include <string>

int main(int argc, char** argv) {
  using namespace dqskin::cli;

  CLI::App app{
      "dqskin: deforms the skinned meshes of glTF 2.0 animations with dual quaternions (Kavan et al.), "
      "headless, for asset builds and CI.",
      "dqskin"};
  app.set_version_flag("--version", std::string("dqskin ") + dqskin::kVersion, "Print the version and exit");
  app.footer("Exit status: 0 success, 1 some inputs failed, 2 usage or input error, 3 no OpenGL context.\n"
             "Run 'dqskin COMMAND --help' for the options of a command.\n"
             "Examples:\n"
             "  dqskin info Fox.glb\n"
             "  dqskin bake Fox.glb -o out --format glb,vat\n"
             "  dqskin bench --quick");

  InfoSettings info;
  CLI::App* info_cmd = app.add_subcommand(
      "info", "Print scenes, skinned meshes, skins, animations, morph targets and warnings of glTF files");
  info_cmd->add_option("FILE", info.inputs, ".gltf or .glb files")->required();
  info_cmd->add_flag("--json", info.json, "Print one JSON document instead of text");
  add_load_settings(*info_cmd, info.load);

  BenchSettings bench;
  CLI::App* bench_cmd = app.add_subcommand(
      "bench", "Measure vertex-frames per second of lbs, dqs and dqs with scale on the GPU path and the CPU "
               "reference, for synthetic characters of 10k, 100k and 1M vertices");
  bench_cmd->add_flag("--json", bench.json, "Print one JSON document: one entry per measurement");
  bench_cmd->add_flag("--quick", bench.quick, "A run under a minute: 10k and 100k vertices, 1 and 64 frames per batch");
  bench_cmd->add_option("--backend", bench.backend, "Headless OpenGL backend: auto (EGL, then OSMesa), egl or osmesa")
      ->capture_default_str();
  bench_cmd->add_option("--gpu-memory", bench.gpu_memory_mb, "GPU output buffer budget per batch, in MiB")
      ->capture_default_str()
      ->check(CLI::Range(size_t(1), size_t(1) << 20));

  BakeSettings bake;
  CLI::App* bake_cmd = app.add_subcommand(
      "bake", "Deform whole animations and write per-frame meshes (glb, ply, obj), vertex-animation textures "
              "(vat) and bone textures (bones), with a manifest of every file's SHA-256");
  bake_cmd->add_option("INPUT", bake.inputs,
                       ".gltf or .glb files. Without any, the bundled textured_cylinder rig is baked into a new "
                       "temporary folder, which is printed");
  bake_cmd->add_option("-o,--out", bake.out_dir, "Output folder (created when missing)")->type_name("OUTDIR");
  add_frame_selection(*bake_cmd, bake.selection, "bake");
  add_load_settings(*bake_cmd, bake.load);
  bake_cmd->add_option("--mode", bake.mode, "Blending: lbs (linear), dqs (dual quaternion DLB), dib (iterative, CPU)")
      ->type_name("lbs|dqs|dib")
      ->capture_default_str();
  bake_cmd->add_option("--format", bake.formats, "Outputs, any of glb,ply,obj,vat,bones (comma-separated)")
      ->type_name("LIST")
      ->capture_default_str();
  bake_cmd->add_option("--backend", bake.backend,
                       "Deformer: auto (EGL, then OSMesa), egl, osmesa, or cpu (the double-precision reference)")
      ->type_name("NAME")
      ->capture_default_str();
  bake_cmd->add_option("--scene", bake.scene, "Scene index (default: the file's default scene)")->type_name("INDEX");
  bake_cmd->add_option("--shard", bake.shard,
                       "Bake only shard I of N of the (input, animation, frame) work; the N shards' outputs "
                       "together equal the whole bake")
      ->type_name("I/N");
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
  bake_cmd->add_flag("-v,--verbose", bake.verbose, "Also print the OpenGL backend and renderer");
  bake_cmd->footer(
      "Outputs: OUTDIR/<input name>/<animation>/frame_NNNN.{glb,ply,obj} (frame numbers zero-padded, so name order is\n"
      "frame order), materials.mtl, vat_positions.exr, vat_normals.exr, vat.json, bones_skinK.{exr,json}, and\n"
      "OUTDIR/manifest.json (manifest.shard-I-of-N.json for a shard). Files appear complete or not at all.\n"
      "Exit status: 0 success, 1 some inputs failed (the others baked), 2 usage or input error, 3 no OpenGL context.\n"
      "Examples:\n"
      "  dqskin bake Fox.glb -o out --format glb,vat\n"
      "  dqskin bake *.glb -o out --fps 24 --frames 0:47 --mode lbs\n"
      "  dqskin bake *.glb -o out --shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT");

  RenderSettings render;
  CLI::App* render_cmd = app.add_subcommand(
      "render", "Draw the deformed meshes of every frame offscreen into PNG (8-bit sRGB) or EXR (linear) images, "
                "through the same headless OpenGL context as bake");
  render_cmd->add_option("INPUT", render.inputs,
                         ".gltf or .glb files. Without any, the bundled textured_cylinder rig is rendered into a new "
                         "temporary folder (printed)");
  render_cmd->add_option("-o,--out", render.out_dir, "Output folder (created when missing)")->type_name("OUTDIR");
  add_frame_selection(*render_cmd, render.selection, "render");
  add_load_settings(*render_cmd, render.load);
  render_cmd->add_option("--mode", render.mode,
                         "Blending: lbs (linear), dqs (dual quaternion DLB) or dib (iterative, deformed on the CPU)")
      ->type_name("lbs|dqs|dib")
      ->capture_default_str();
  render_cmd->add_option("--backend", render.backend,
                         "Headless OpenGL backend that draws (and deforms): auto (EGL, then OSMesa), egl, osmesa, or "
                         "cpu (deform with the double-precision CPU reference, draw with auto)")
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

  DiffSettings diff;
  CLI::App* diff_cmd = app.add_subcommand(
      "diff", "Compare two images, or two folders of images paired by relative path, as OpenImageIO's idiff does: "
              "max, mean and RMS error, PSNR and pixels over the thresholds, from ImageBufAlgo::compare");
  diff_cmd->add_option("A", diff.a, "Reference image or folder")->required();
  diff_cmd->add_option("B", diff.b, "Image or folder to check (for an image A and a folder B: B/<name of A>)")
      ->required();
  diff_cmd->add_option("--fail", diff.thresholds.fail, "A pixel is over --fail when any channel differs by more")
      ->type_name("VAL")
      ->capture_default_str();
  diff_cmd->add_option("--failpercent", diff.thresholds.fail_percent,
                       "A pair fails when more than this percentage of its pixels are over --fail")
      ->type_name("PERCENT")
      ->capture_default_str();
  diff_cmd->add_option("--hardfail", diff.thresholds.hard_fail,
                       "A pair fails when any channel differs by more, whatever the percentage")
      ->type_name("VAL")
      ->capture_default_str();
  diff_cmd->add_option("--warn", diff.thresholds.warn, "A pixel is over --warn when any channel differs by more")
      ->type_name("VAL")
      ->capture_default_str();
  diff_cmd->add_option("--warnpercent", diff.thresholds.warn_percent,
                       "A pair warns when more than this percentage of its pixels are over --warn")
      ->type_name("PERCENT")
      ->capture_default_str();
  diff_cmd->add_option("--hardwarn", diff.thresholds.hard_warn,
                       "A pair warns when any channel differs by more, whatever the percentage")
      ->type_name("VAL")
      ->capture_default_str();
  diff_cmd->add_option("-o,--out", diff.out_dir,
                       "Write a heat map DIR/<name>.diff.png of every failing pair (folders created when missing)")
      ->type_name("DIR");
  diff_cmd->add_flag("--json", diff.json, "Print one JSON document instead of text");
  diff_cmd->add_option("--junit", diff.junit, "Also write a JUnit XML report, one testcase per pair, to FILE")
      ->type_name("FILE");
  diff_cmd->footer(
      "Verdict (idiff's): a pair FAILs when more than --failpercent % of its pixels are over --fail, or any channel\n"
      "differs by more than --hardfail, or a NaN or infinity meets another value; else it WARNs when more than\n"
      "--warnpercent % are over --warn, or any channel differs by more than --hardwarn; else it PASSes. The defaults\n"
      "are idiff's: any difference over 1e-6 fails. For warnings, set --fail above --warn or a --failpercent.\n"
      "Images of different sizes or channel counts, files missing from one folder and unreadable files FAIL.\n"
      "Pixels are read as float (8-bit 255 = 1.0); the first subimage is compared.\n"
      "Folders: image files (exr, png, jpg, jpeg, tif, tiff, gif, hdr, tga, webp, ...) found recursively, paired\n"
      "by relative path; other files are ignored.\n"
      "Heat maps: each pixel's largest channel difference; black at most --fail, then viridis from dark purple (just\n"
      "over --fail) to yellow (the pair's max error, printed in the report); white where it is NaN or infinite.\n"
      "Exit status: 0 all pass, 1 warnings but no failure, 2 a failure, or a usage or input error.\n"
      "Examples:\n"
      "  dqskin diff golden/frame_0000.png out/frame_0000.png\n"
      "  dqskin diff golden out --fail 0.02 --warn 0.004 --failpercent 0.1 --out diffs --junit diff.xml");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return kSuccess;
  } catch (const CLI::CallForVersion& e) {
    std::cout << e.what() << '\n';
    return kSuccess;
  } catch (const CLI::ParseError& e) {
    print_error(std::string(e.what()) + " (see dqskin --help)");
    return kUsageOrInputError;
  }

  // The commands turn what goes wrong with an input into a line naming it; what escapes them (a usage error
  // found late, memory running out outside any input) still ends in one line and a status, never an abort.
  try {
    if (info_cmd->parsed()) return run_info(info);
    if (bench_cmd->parsed()) return run_bench(bench);
    if (bake_cmd->parsed()) return run_bake(bake);
    if (diff_cmd->parsed()) return run_diff(diff);
    if (render_cmd->parsed()) return run_render(render);
  } catch (const std::bad_alloc&) {
    print_error("ran out of memory");
    return kUsageOrInputError;
  } catch (const std::exception& e) {
    print_error(e.what());
    return kUsageOrInputError;
  }

  // No command given: show what there is to run.
  std::cout << app.help();
  return kSuccess;
}
