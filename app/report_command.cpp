// `dqskin report INPUT… -o OUTDIR`: every animation of the inputs deformed with lbs, dqs and dib, measured
// per joint, judged, and written as OUTDIR/<input name>/report.json with the contact sheets of each
// animation's worst frames (docs/commands/report.md).
#include "commands.hpp"
#include "console.hpp"
#include "exit_codes.hpp"
#include "guarded_run.hpp"
#include "interrupt.hpp"
#include "progress.hpp"

#include "dqskin/error.hpp"
#include "../lib/base/output_journal.hpp"
#include "dqskin/report.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

namespace dqskin::cli {
namespace {

struct ReportSettings {
  std::vector<std::string> inputs;
  std::string out_dir;
  LoadSettings load;
  FrameSelection selection;
  int scene = -1;
  std::string backend = "auto";
  std::string tolerance = "0.5%";
  double twist = 150, candy_wrapper = 0.3, bulge = 0.1;
  int worst_frames = 3, image_size = 320;
  bool fast_cpu = false;
  bool quiet = false, json_progress = false, verbose = false;
};

// --tolerance: a length in scene units, or a percentage of the rest pose's bounding-box diagonal (as
// bake's --max-error, but 0 allowed).
void parse_tolerance(const std::string& text, ReportThresholds& t) {
  const LengthOrPercent l = parse_length_or_percent(
      text, true, "--tolerance '" + text + "' is not a length or percentage (0.002, 0.5%)");
  t.tolerance = l.value;
  t.tolerance_relative = l.relative;
}

ReportOptions to_options(const ReportSettings& s) {
  ReportOptions o;
  o.out_dir = s.out_dir;
  o.load = to_load_options(s.load);
  o.clips = s.selection.anim;
  o.frames = to_frame_spec(s.selection);
  o.scene = s.scene;
  if (!parse_backend(s.backend, o.backend)) throw InputError(unknown_backend(s.backend));
  parse_tolerance(s.tolerance, o.thresholds);
  o.thresholds.twist_degrees = s.twist;
  o.thresholds.candy_wrapper = s.candy_wrapper;
  o.thresholds.dqs_bulge = s.bulge;
  o.worst_frames = s.worst_frames;
  o.image_size = s.image_size;
  o.fast_cpu = s.fast_cpu;
  return o;
}

int run_report(const ReportSettings& given) {
  ReportSettings settings = given;
  ProgressPrinter progress(settings.json_progress, settings.quiet);
  OutputJournal out_folder;  // the output folder, when this run creates it: removed again if nothing was reported
  return guarded_run("report", [&] {
    if (settings.inputs.empty()) throw InputError("no input given (dqskin report FILE... -o OUTDIR)");
    if (settings.out_dir.empty()) throw InputError("-o OUTDIR is required");
    ReportOptions options = to_options(settings);
    options.cancel = catch_interrupts("report");
    out_folder.make_folders(options.out_dir);
    const ReportResult result = report(settings.inputs, options, [&](const JobProgress& p) { progress(p); });
    progress.done();
    print_input_messages(result.inputs, settings.quiet, settings.verbose);
    const size_t failed = failed_inputs(result.inputs);
    if (failed < result.inputs.size()) out_folder.keep();
    if (settings.json_progress) {
      std::cout << json_text(nlohmann::json{{"event", "summary"}, {"frames", result.frames_total}, {"files", result.outputs},
                                            {"verdicts", result.verdicts}, {"failed_inputs", failed},
                                            {"wall_s", result.wall_seconds}})
                << std::endl;
    } else if (!settings.quiet) {
      for (const std::string& v : result.verdicts) std::fprintf(stderr, "%s\n", printable(v).c_str());
      // One verdict per input reported: an input without a skin is left out with a warning above.
      const size_t reported = result.verdicts.size();
      if (failed < result.inputs.size())
        std::fprintf(stderr, "reported %zu frames (lbs, dqs and dib each) of %zu input%s in %.2f s into %s\n",
                     result.frames_total, reported, reported == 1 ? "" : "s", result.wall_seconds,
                     printable(options.out_dir).c_str());
    }
    return job_exit_status(result.inputs, settings.quiet, "reported");
  }, [&] { progress.done(); }, &out_folder);
}

}  // namespace

Command add_report_command(CLI::App& app) {
  auto settings = std::make_shared<ReportSettings>();
  ReportSettings& s = *settings;
  CLI::App* cmd = app.add_subcommand(
      "report", "Compare lbs, dqs and dib (exact) over whole animations, per joint: displacement, cross-section "
                "area, volume, twist and bend, antipodal flips; a verdict per joint and per file, report.json and "
                "contact sheets of the worst frames");
  cmd->add_option("INPUT", s.inputs, ".gltf or .glb files")->required();
  cmd->add_option("-o,--out", s.out_dir, "Output folder (created when missing)")->type_name("OUTDIR");
  add_frame_selection(*cmd, s.selection, "report");
  add_load_settings(*cmd, s.load);
  add_max_influences(*cmd, s.load);
  cmd->add_option("--scene", s.scene, "Scene index (default: the file's default scene)")->type_name("INDEX");
  cmd->add_option("--backend", s.backend,
                  "Headless OpenGL backend that draws the contact sheets: auto (EGL, then OSMesa), egl or osmesa "
                  "(the measurements always run on the double-precision CPU reference)")
      ->type_name("NAME")
      ->capture_default_str();
  cmd->add_option("--tolerance", s.tolerance,
                  "lbs-fine when lbs is within this of dib: a length in scene units, or a percentage of the rest "
                  "pose's bounding-box diagonal")
      ->type_name("LENGTH|PCT%")
      ->capture_default_str();
  cmd->add_option("--twist", s.twist, "add-twist-joints when a joint twists at least this, degrees")
      ->type_name("DEG")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 180.0));
  cmd->add_option("--candy-wrapper", s.candy_wrapper, "use-dqs when the candy-wrapper index reaches this (0 to 1)")
      ->type_name("INDEX")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--bulge", s.bulge, "dqs-bulges when dqs's cross-section exceeds dib's by this fraction")
      ->type_name("FRACTION")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_option("--worst-frames", s.worst_frames, "Frames per contact sheet")
      ->type_name("N")
      ->capture_default_str()
      ->check(CLI::Range(1, 16));
  cmd->add_option("--image-size", s.image_size, "Contact-sheet cell size in pixels (square)")
      ->type_name("PIXELS")
      ->capture_default_str()
      ->check(CLI::Range(16, 4096));
  cmd->add_flag("--fast-cpu", s.fast_cpu,
                "Deform lbs and dqs on the fast float CPU deformer instead of the double-precision reference "
                "(dib always runs there): faster, figures move by float rounding");
  cmd->add_flag("-q,--quiet", s.quiet, "Print nothing but errors");
  cmd->add_flag("-v,--verbose", s.verbose,
                "Also print the inputs' notices (a skinned mesh node's transform, which glTF ignores)");
  cmd->add_flag("--json-progress", s.json_progress, "Print progress and the final summary as JSON lines on standard output");
  cmd->footer(
      "Outputs: OUTDIR/<input name>/report.json and worst_<animation>.png (README \"dqskin report\" defines every\n"
      "figure and verdict). Existing files of a report are replaced.\n"
      "Exit status: 0 success, 1 some inputs failed (the others reported), 2 usage or input error, 3 no OpenGL context.\n"
      "Examples:\n"
      "  dqskin report Fox.glb -o reports\n"
      "  dqskin report arm.gltf -o reports --anim Walk --tolerance 0.002");
  return {cmd, [settings] { return run_report(*settings); }};
}

}  // namespace dqskin::cli
