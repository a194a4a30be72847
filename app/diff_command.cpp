// `dqskin diff A B`: two images or two folders of images compared as OpenImageIO's idiff compares them, for
// CI checks of rendered frames. Prints a text or JSON report, writes heat maps and a JUnit XML report.
#include "commands.hpp"
#include "console.hpp"
#include "exit_codes.hpp"
#include "guarded_run.hpp"

#include "dqskin/atomic_file.hpp"
#include "dqskin/diff_report.hpp"
#include "dqskin/error.hpp"
#include "dqskin/image_diff.hpp"

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
};

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
    const DiffReport report = diff_images(settings.a, settings.b, {settings.thresholds, settings.out_dir});
    for (const ImageDiff& d : report.pairs)
      if (!d.unreadable.empty()) print_error(d.unreadable, d.read_error);
    std::cout << (settings.json ? diff_json(report) : diff_text(report)) << std::flush;
    if (!settings.junit.empty()) {
      AtomicFile junit(settings.junit);
      junit.write(diff_junit(report));
      junit.commit(Overwrite::kReplace);
    }
    return exit_status(report.status());
  });
}

}  // namespace

Command add_diff_command(CLI::App& app) {
  auto settings = std::make_shared<DiffSettings>();
  DiffSettings& diff = *settings;
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
  return {diff_cmd, [settings] { return run_diff(*settings); }};
}

}  // namespace dqskin::cli
