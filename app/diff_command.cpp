// `dqskin diff A B`: one verb for every CI comparison, which recognizes its inputs. Two glTF files are
// compared by their deformed surfaces over the animation (dqskin/geometry_diff.hpp); two images or folders of
// images as OpenImageIO's idiff compares them. Both keep idiff's thresholds, exit statuses and reports
// (text or JSON, JUnit XML), so a CI job checks either with the same flags.
#include "commands.hpp"
#include "console.hpp"
#include "exit_codes.hpp"
#include "guarded_run.hpp"

#include "dqskin/atomic_file.hpp"
#include "../lib/base/byte_size.hpp"
#include "dqskin/diff_report.hpp"
#include "dqskin/error.hpp"
#include "dqskin/geometry_diff.hpp"
#include "dqskin/geometry_report.hpp"
#include "dqskin/image_diff.hpp"
#include "interrupt.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

namespace dqskin::cli {
namespace {

struct DiffSettings {
  std::string a, b;
  DiffThresholds thresholds;  // idiff's defaults
  std::string out_dir;        // heat maps of failing pairs; none when empty
  bool json = false;
  std::string junit;          // JUnit XML report; none when empty
  // Geometry (two glTF files) only:
  bool relative = false;
  std::string mode = "dqs";
  std::string backend = "auto";
  std::string anim = "all";
  double fps = 0;  // 0: key times and midpoints
  std::string times;
  int image_size = 512;
  bool verbose = false;
  LoadSettings load;
};

int exit_status(DiffStatus status);

void write_junit(const std::string& path, const std::string& text) {
  if (path.empty()) return;
  AtomicFile junit(path);
  junit.write(text);
  junit.commit(Overwrite::kReplace);
}

// Two glTF files: their animations deformed and compared surface to surface; two bakes: their files
// vertex by vertex.
int run_geometry_diff(const DiffSettings& s) {
  GeometryDiffOptions o;
  o.load = to_load_options(s.load);
  if (!parse_blend_mode(s.mode, o.mode)) throw InputError("--mode '" + s.mode + "' is not one of lbs, dqs, dib");
  if (!parse_backend(s.backend, o.backend)) throw InputError(unknown_backend(s.backend));
  o.clips = s.anim;
  if (s.fps != 0) {
    if (!(s.fps > 0 && s.fps <= 1000)) throw InputError("--fps must be above 0 and at most 1000");
    o.fps = s.fps;
  }
  if (!s.times.empty()) o.times = parse_times(s.times);
  if (o.fps && !o.times.empty()) throw InputError("give --fps or --times, not both");
  if (s.image_size < 64 || s.image_size > 8192) throw InputError("--image-size must be from 64 to 8192 pixels");
  o.image_size = s.image_size;
  o.thresholds = s.thresholds;
  o.relative = s.relative;
  o.out_dir = s.out_dir;
  o.cancel = catch_interrupts("diff");
  const GeometryDiffReport report = is_gltf_file(s.a) ? diff_geometry(s.a, s.b, o) : diff_bakes(s.a, s.b, o);
  std::cout << (s.json ? geometry_json(report) : geometry_text(report)) << std::flush;
  if (s.verbose)
    std::fprintf(stderr, "dqskin: diff: correspondence %.3g s, whole diff %.3g s\n", report.correspondence_seconds,
                 report.wall_seconds);
  write_junit(s.junit, geometry_junit(report));
  return exit_status(report.status());
}

// diff's statuses are idiff's order of severity: 0 all pass, 1 warnings only, 2 a failure. A usage or
// input error is 2 as everywhere in dqskin (README "Exit status"), so CI treats it as a failure.
constexpr int kDiffWarn = 1;
constexpr int kDiffFail = 2;
static_assert(kDiffFail == kUsageOrInputError);

int exit_status(DiffStatus status) {
  switch (status) {
    case DiffStatus::kPass: return kSuccess;
    case DiffStatus::kWarn: return kDiffWarn;
    case DiffStatus::kFail: return kDiffFail;
  }
  return kDiffFail;
}

// Compares two images or two folders of images. Returns 0 (all pass), 1 (warnings only) or 2 (a failure,
// or a usage or input error).
int run_diff(const DiffSettings& settings) {
  return guarded_run("diff", [&] {
    const std::string bad = check_thresholds(settings.thresholds);
    if (!bad.empty()) throw InputError(bad);
    if (is_gltf_file(settings.a) != is_gltf_file(settings.b))
      throw InputError("compare two glTF files (.gltf, .glb, .vrm) or two images or folders of images, not one of each");
    if (is_gltf_file(settings.a)) return run_geometry_diff(settings);
    if (is_bake_folder(settings.a) && is_bake_folder(settings.b)) return run_geometry_diff(settings);
    DiffOptions options{settings.thresholds, settings.out_dir};
    options.max_memory = parse_byte_size(settings.load.max_memory, "--max-memory");
    options.cancel = catch_interrupts("diff");
    const DiffReport report = diff_images(settings.a, settings.b, options);
    for (const ImageDiff& d : report.pairs)
      if (!d.unreadable.empty()) print_error(d.unreadable, d.read_error);
    std::cout << (settings.json ? diff_json(report) : diff_text(report)) << std::flush;
    write_junit(settings.junit, diff_junit(report));
    return exit_status(report.status());
  });
}

}  // namespace

Command add_diff_command(CLI::App& app) {
  auto settings = std::make_shared<DiffSettings>();
  DiffSettings& diff = *settings;
  CLI::App* diff_cmd = app.add_subcommand(
      "diff", "Compare two glTF files by their deformed surfaces over every animation (an optimized or re-exported "
              "file against its source), or two images, or two folders of images paired by relative path, as "
              "OpenImageIO's idiff does");
  diff_cmd->add_option("A", diff.a, "Reference glTF file, image or folder")->required();
  diff_cmd->add_option("B", diff.b,
                       "glTF file, image or folder to check (for an image A and a folder B: B/<name of A>)")
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
                       "Write a heat map DIR/<name>.diff.png of every failing pair, or for glTF files of every failing clip "
                       "(folders created when missing)")
      ->type_name("DIR");
  diff_cmd->add_flag("--relative", diff.relative,
                     "glTF: thresholds are fractions of each clip's bounding-box diagonal, not scene units");
  diff_cmd->add_option("--mode", diff.mode, "glTF: skinning both files are deformed with")
      ->type_name("lbs|dqs|dib")
      ->capture_default_str();
  diff_cmd->add_option("--backend", diff.backend, "glTF: deformer, as bake's --backend")
      ->type_name("auto|egl|osmesa|fast-cpu|cpu")
      ->capture_default_str();
  diff_cmd->add_option("--anim", diff.anim, "glTF: A's animations to compare: all, a name or an index")
      ->type_name("NAME")
      ->capture_default_str();
  diff_cmd->add_option("--fps", diff.fps,
                       "glTF: compare every 1/FPS s from 0 to A's last key, instead of every key time of both "
                       "files and the midpoints between them")
      ->type_name("FPS");
  diff_cmd->add_option("--times", diff.times, "glTF: compare at these times in seconds (comma-separated)")
      ->type_name("T,...");
  diff_cmd->add_option("--image-size", diff.image_size, "glTF: pixels of the heat maps --out writes")
      ->type_name("PX")
      ->capture_default_str();
  diff_cmd->add_flag("-v,--verbose", diff.verbose,
                     "glTF and bakes: also print, on stderr, how long the correspondence and the whole diff took");
  add_load_settings(*diff_cmd, diff.load);
  add_max_influences(*diff_cmd, diff.load);
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
      "Two glTF files (.gltf, .glb): both are deformed with --mode at the same times, A's clips paired with B's\n"
      "by name, then by index. Each vertex of A is followed through the animation at its closest point on B's\n"
      "surface at the rest pose (or, where the rest pose crumples the mesh, at the first clip's first time or the\n"
      "bind pose), and each vertex of B on A's (the identity when both have the same vertices in the same order);\n"
      "vertices on no triangle are left out. Normals: vertex normals where both files have one smooth normal,\n"
      "face normals elsewhere. The thresholds apply to those distances, in scene units or with --relative as fractions\n"
      "of the clip's bounding-box diagonal, and percentages count vertex samples. A clip of A missing in B\n"
      "fails; a clip only in B warns; dropped or resampled channels are listed as notes. --out writes\n"
      "DIR/<clip>.error.png for each failing clip (its worst frame shaded by error, with a color bar in scene\n"
      "units) and DIR/worst_frames.png.\n"
      "Two bake folders (each with the manifest.json that bake writes): PLY, OBJ and glb frames paired by relative\n"
      "path and compared vertex by vertex, EXR textures texel by texel (distance of the first three channels);\n"
      "--relative uses each file's diagonal. Other folders are compared as images.\n"
      "Exit status: 0 all pass, 1 warnings but no failure, 2 a failure, or a usage or input error.\n"
      "Examples:\n"
      "  dqskin diff Fox.glb Fox.optimized.glb --fail 1e-3 --relative --out diffs --junit diff.xml\n"
      "  dqskin diff golden/frame_0000.png out/frame_0000.png\n"
      "  dqskin diff golden out --fail 0.02 --warn 0.004 --failpercent 0.1 --out diffs --junit diff.xml");
  return {diff_cmd, [settings] { return run_diff(*settings); }};
}

}  // namespace dqskin::cli
