// `dqskin diff A B`: one verb for every CI comparison, which recognizes its inputs. Two glTF files are
// compared by their deformed surfaces over the animation (dqskin/geometry_diff.hpp); two images or folders of
// images as OpenImageIO's idiff compares them. Both keep idiff's thresholds, exit statuses and reports
// (text or JSON, JUnit XML), so a CI job checks either with the same flags.
#include "commands.hpp"
#include "console.hpp"
#include "exit_codes.hpp"
#include "guarded_run.hpp"

#include "dqskin/atomic_file.hpp"
#include "dqskin/ci_annotations.hpp"
#include "dqskin/diff_page.hpp"
#include "../lib/base/byte_size.hpp"
#include "dqskin/diff_report.hpp"
#include "dqskin/error.hpp"
#include "dqskin/geometry_diff.hpp"
#include "dqskin/geometry_report.hpp"
#include "dqskin/golden_approval.hpp"
#include "dqskin/image_diff.hpp"
#include "interrupt.hpp"
#include "../lib/diff/flip.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <filesystem>
#include <limits>
#include <thread>
#include <vector>

#include <unistd.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <iostream>
#include <memory>

namespace dqskin::cli {
namespace {

struct DiffSettings {
  std::string a, b;
  DiffThresholds thresholds;  // idiff's defaults
  std::vector<CLI::Option*> threshold_options;  // which of them were given (FLIP takes those only)
  std::string metric = "idiff";
  double ppd = 0;                // FLIP's pixels per degree; 0: from --viewing, or the paper's default
  std::vector<double> viewing;   // distance, screen width (metres), screen pixels across
  unsigned threads = 0;          // 0: one per core
  std::string out_dir;        // heat maps of failing pairs; none when empty
  bool json = false;
  std::string junit;          // JUnit XML report; none when empty
  bool approve = false, dry_run = false;
  std::string mask;                 // a mask image for every pair
  std::vector<std::string> ignore;  // X,Y,W,H rectangles for every pair
  std::string preset;               // a preset file of rules
  std::string html;                 // the page's folder; none when empty
  std::string annotations;       // "github", "gitlab" or none
  std::string annotations_file;  // GitLab's report, GitHub's step summary; see add_diff_command
  // Geometry (two glTF files) only:
  bool relative = false;
  std::string mode = "dqs";
  std::string backend = "auto";
  FrameSelection selection;  // bake's flags; none given: key times of both files and the midpoints
  int image_size = 512;
  bool verbose = false;
  LoadSettings load;
};

int exit_status(DiffStatus status);

// The CI's annotations of a diff (dqskin/ci_annotations.hpp): GitHub's workflow commands on stdout after
// the report and its step summary appended to --annotations-file or $GITHUB_STEP_SUMMARY (a file each
// step appends to, so appending is its protocol); GitLab's Code Quality report written atomically.
void write_annotations(const DiffSettings& s, DiffStatus status, const std::vector<CiRow>& rows) {
  if (s.annotations == "github") {
    std::cout << github_annotations(rows) << std::flush;
    const char* env = std::getenv("GITHUB_STEP_SUMMARY");
    const std::string path = !s.annotations_file.empty() ? s.annotations_file : env ? env : "";
    if (path.empty()) return;
    std::ofstream summary(path, std::ios::binary | std::ios::app);
    summary << github_step_summary("dqskin diff " + s.a + " " + s.b, status, rows);
    summary.flush();
    if (!summary) throw OutputError(path + ": cannot append the step summary: " + std::strerror(errno));
  } else if (s.annotations == "gitlab") {
    AtomicFile report(s.annotations_file.empty() ? "gl-code-quality-report.json" : s.annotations_file);
    report.write(gitlab_code_quality(rows));
    report.commit(Overwrite::kReplace);
  }
}

void write_junit(const std::string& path, const std::string& text) {
  if (path.empty()) return;
  AtomicFile junit(path);
  junit.write(text);
  junit.commit(Overwrite::kReplace);
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

constexpr double kOff = std::numeric_limits<double>::infinity();

// The threshold options given on the command line, by their long name ("--failmean").
std::vector<std::string> given_thresholds(const DiffSettings& s) {
  std::vector<std::string> names;
  for (const CLI::Option* o : s.threshold_options)
    if (o->count() > 0) names.push_back("--" + o->get_lnames().front());
  // A percentage counts pixels over a value: with FLIP, whose value has no default, it needs that value.
  const auto has = [&names](const char* n) { return std::find(names.begin(), names.end(), n) != names.end(); };
  if (has("--failpercent") && !has("--fail")) throw InputError("--failpercent needs --fail with --metric flip (the FLIP value it counts pixels over)");
  if (has("--warnpercent") && !has("--warn")) throw InputError("--warnpercent needs --warn with --metric flip (the FLIP value it counts pixels over)");
  return names;
}

// FLIP's pixels per degree from --ppd or --viewing; the paper's viewing conditions when neither is given.
double viewing_ppd(const DiffSettings& s) {
  if (s.ppd != 0 && !s.viewing.empty()) throw InputError("give --ppd or --viewing, not both");
  if (!s.viewing.empty()) {
    const double distance = s.viewing[0], width = s.viewing[1], pixels = s.viewing[2];
    if (!(distance > 0 && distance <= 100)) throw InputError("--viewing: the distance must be above 0 and at most 100 m");
    if (!(width > 0 && width <= 100)) throw InputError("--viewing: the screen width must be above 0 and at most 100 m");
    if (!(pixels >= 1 && pixels <= 1e6)) throw InputError("--viewing: the pixels across must be from 1 to 1000000");
    const double ppd = pixels_per_degree(distance, pixels, width);
    if (!(ppd >= 1 && ppd <= 1000)) throw InputError("--viewing gives " + std::to_string(ppd) + " pixels per degree; FLIP takes 1 to 1000");
    return ppd;
  }
  if (s.ppd == 0) return kDefaultPixelsPerDegree;
  if (!(s.ppd >= 1 && s.ppd <= 1000)) throw InputError("--ppd must be from 1 to 1000 pixels per degree");
  return s.ppd;
}

// The folder of --html: its pictures are written into a hidden staging folder beside it, and the page
// with them replaces the folder at the end in one rename, so that a diff that stops half-way leaves the old
// page (or none), never a page whose pictures are missing. Removed unless committed.
class PageFolder {
public:
  explicit PageFolder(std::string dir) : dir_(std::move(dir)) {
    namespace fs = std::filesystem;
    std::error_code error;
    // "out/" names the folder out; ".", ".." and "/" name no folder of its own to replace.
    while (dir_.size() > 1 && dir_.back() == '/') dir_.pop_back();
    const std::string name = fs::path(dir_).filename().string();
    if (name.empty() || name == "." || name == ".." || dir_ == "/")
      throw InputError("--html '" + dir_ + "': give the page a folder of its own (not '.', '..' or '/')");
    if (fs::exists(dir_, error) && !fs::is_directory(dir_, error))
      throw OutputError(dir_ + ": --html needs a folder, and this is a file");
    // The folder is replaced whole: only an empty one or a page of ours (index.html and images/, nothing
    // else), never a folder of someone's files given by mistake.
    if (fs::is_directory(dir_, error) && !fs::is_empty(dir_, error) && !is_our_page(dir_))
      throw OutputError(dir_ + ": --html replaces its folder, and this one holds other files than a dqskin diff "
                        "page; give a new or empty folder");
    const fs::path parent = fs::absolute(dir_).parent_path();
    fs::create_directories(parent, error);
    if (error) throw OutputError(parent.string() + ": cannot create folder: " + error.message());
    staging_ = (parent / ("." + fs::path(dir_).filename().string() + ".page-" + std::to_string(::getpid()))).string();
    fs::remove_all(staging_, error);
    if (!fs::create_directory(staging_, error)) throw OutputError(staging_ + ": cannot create folder: " + error.message());
  }
  ~PageFolder() {
    std::error_code ignored;
    if (!staging_.empty()) std::filesystem::remove_all(staging_, ignored);
  }
  PageFolder(const PageFolder&) = delete;
  PageFolder& operator=(const PageFolder&) = delete;
  const std::string& staging() const { return staging_; }

  void commit(const std::string& html) {
    namespace fs = std::filesystem;
    {
      AtomicFile index((fs::path(staging_) / "index.html").string());
      index.write(html);
      index.commit(Overwrite::kReplace);
    }
    std::error_code error;
    const std::string old = staging_ + ".old";
    fs::remove_all(old, error);
    const bool had = fs::exists(dir_, error);
    if (had) fs::rename(dir_, old, error);
    if (error) throw OutputError(dir_ + ": cannot replace the page folder: " + error.message());
    // Checked again now that it is aside: something may have written into it while the diff ran.
    if (had && !fs::is_empty(old, error) && !is_our_page(old)) {
      std::error_code ignored;
      fs::rename(old, dir_, ignored);
      throw OutputError(dir_ + ": other files appeared in the page folder during the diff; it was left as it is");
    }
    fs::rename(staging_, dir_, error);
    if (error) {
      std::error_code ignored;
      if (had) fs::rename(old, dir_, ignored);
      throw OutputError(dir_ + ": cannot write the page folder: " + error.message());
    }
    staging_.clear();
    // The old page: its two entries, then the folder, which is empty unless something came meanwhile.
    if (had) {
      fs::remove(fs::path(old) / "index.html", error);
      fs::remove_all(fs::path(old) / "images", error);
      fs::remove(old, error);
    }
  }

private:
  static bool is_our_page(const std::string& dir) {
    namespace fs = std::filesystem;
    std::error_code error;
    for (const fs::directory_entry& e : fs::directory_iterator(dir, error)) {
      const std::string name = e.path().filename().string();
      if (name != "index.html" && name != "images") return false;
    }
    std::ifstream index(fs::path(dir) / "index.html", std::ios::binary);
    std::string head(128, '\0');
    index.read(head.data(), std::streamsize(head.size()));
    return !error && head.find("<title>dqskin diff ") != std::string::npos;
  }

  std::string dir_, staging_;
};

// The page's folder of --html, or none: its pictures go to a staging folder beside it, and the page and
// they appear together at the end. Refuses an --out inside it, which the page would replace.
std::unique_ptr<PageFolder> open_page(const DiffSettings& settings) {
  if (settings.html.empty()) return nullptr;
  if (!settings.out_dir.empty()) {
    namespace fs = std::filesystem;
    std::error_code e1, e2;
    const fs::path html = fs::weakly_canonical(fs::absolute(settings.html), e1);
    const fs::path out = fs::weakly_canonical(fs::absolute(settings.out_dir), e2);
    const auto [end, ignored] = std::mismatch(html.begin(), html.end(), out.begin(), out.end());
    if (end == html.end())
      throw InputError("--out " + settings.out_dir + " is inside --html " + settings.html +
                       ", which the page replaces: give the heat maps another folder");
  }
  return std::make_unique<PageFolder>(settings.html);
}

// Two glTF files: their animations deformed and compared surface to surface; two bakes: their files
// vertex by vertex.
int run_geometry_diff(const DiffSettings& s) {
  GeometryDiffOptions o;
  o.load = to_load_options(s.load);
  if (!parse_blend_mode(s.mode, o.mode)) throw InputError("--mode '" + s.mode + "' is not one of lbs, dqs, dib");
  if (!parse_backend(s.backend, o.backend)) throw InputError(unknown_backend(s.backend));
  const FrameSelection& frames = s.selection;
  o.clips = frames.anim;
  if (frames.fps && !(*frames.fps > 0 && *frames.fps <= 1000)) throw InputError("--fps must be above 0 and at most 1000");
  if (frames.chosen()) o.frames = to_frame_spec(frames);
  if (frames.fps && !frames.times.empty()) throw InputError("give --fps or --times, not both");
  if (s.image_size < 64 || s.image_size > 8192) throw InputError("--image-size must be from 64 to 8192 pixels");
  o.image_size = s.image_size;
  o.thresholds = s.thresholds;
  o.relative = s.relative;
  o.out_dir = s.out_dir;
  const std::unique_ptr<PageFolder> page = open_page(s);
  if (page) o.page_dir = page->staging();
  o.cancel = catch_interrupts("diff");
  const GeometryDiffReport report = is_gltf_file(s.a) ? diff_geometry(s.a, s.b, o) : diff_bakes(s.a, s.b, o);
  if (page) page->commit(geometry_page_html(report));
  std::cout << (s.json ? geometry_json(report) : geometry_text(report)) << std::flush;
  if (s.verbose)
    std::fprintf(stderr, "dqskin: diff: correspondence %.3g s, whole diff %.3g s\n", report.correspondence_seconds,
                 report.wall_seconds);
  write_junit(s.junit, geometry_junit(report));
  write_annotations(s, report.status(), ci_rows(report));
  return exit_status(report.status());
}

// A folder of images allocates and frees the same few buffers (two images as float, FLIP's maps) for every
// pair, each some megabytes: above glibc's mmap threshold, so each is fresh pages from the kernel, faulted
// in and zeroed again. Keeping them in the heap instead took a folder of 100 renders at 512² from 1.9 to
// 0.14 s of system time and 12% off its wall time (docs/PERFORMANCE.md "FLIP"), for some tens of
// megabytes more at the peak. The memory ceiling counts allocations, not the heap, so it is unchanged.
void keep_freed_memory() {
#ifdef __GLIBC__
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

// "X,Y,W,H" in pixels (--ignore).
PixelRect parse_rect(const std::string& text) {
  PixelRect r;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%d,%d,%d,%d%c", &r.x, &r.y, &r.width, &r.height, &tail) != 4 || r.x < 0 || r.y < 0 ||
      r.width < 1 || r.height < 1)
    throw InputError("--ignore '" + text + "' is not X,Y,WIDTH,HEIGHT in pixels (X, Y at least 0, sizes at least 1)");
  return r;
}

// Compares two images or two folders of images. Returns 0 (all pass), 1 (warnings only) or 2 (a failure,
// or a usage or input error).
int run_diff(const DiffSettings& settings) {
  return guarded_run("diff", [&] {
    const std::string bad = check_thresholds(settings.thresholds);
    if (!bad.empty()) throw InputError(bad);
    if (!settings.annotations.empty() && settings.annotations != "github" && settings.annotations != "gitlab")
      throw InputError("--annotations '" + settings.annotations + "' is not one of github, gitlab");
    if (settings.annotations == "github" && settings.json)
      throw InputError("--annotations github prints workflow commands after the report on stdout, which --json keeps "
                       "for one JSON document; give one of them");
    if (!settings.annotations_file.empty() && settings.annotations.empty())
      throw InputError("--annotations-file needs --annotations github or gitlab");
    if (is_gltf_file(settings.a) != is_gltf_file(settings.b))
      throw InputError("compare two glTF files (.gltf, .glb, .vrm) or two images or folders of images, not one of each");
    const bool geometry = is_gltf_file(settings.a) || (is_bake_folder(settings.a) && is_bake_folder(settings.b));
    if (geometry && settings.metric != "idiff")
      throw InputError("--metric " + settings.metric + " compares images; glTF files and bakes are compared by distance");
    if (geometry && (settings.thresholds.fail_mean != kOff || settings.thresholds.warn_mean != kOff))
      throw InputError("--failmean and --warnmean judge images; glTF files and bakes are judged by distance");
    if (geometry && (!settings.mask.empty() || !settings.ignore.empty() || !settings.preset.empty()))
      throw InputError("--mask, --ignore and --preset apply to images; glTF files and bakes are compared by distance");
    if (geometry && settings.approve)
      throw InputError("--approve replaces golden images; glTF files and bakes are not goldens it replaces");
    if (settings.dry_run && !settings.approve) throw InputError("--dry-run shows what --approve would do: give both");
    if (geometry) return run_geometry_diff(settings);
    DiffOptions options;
    options.thresholds = settings.thresholds;
    options.heat_map_dir = settings.out_dir;
    if (settings.metric == "flip") {
      options.metric = DiffMetric::kFlip;
      options.thresholds = flip_thresholds(settings.thresholds, given_thresholds(settings));
      options.pixels_per_degree = viewing_ppd(settings);
    } else if (settings.metric != "idiff") {
      throw InputError("--metric '" + settings.metric + "' is not one of idiff, flip");
    } else if (settings.ppd != 0 || !settings.viewing.empty()) {
      throw InputError("--ppd and --viewing are FLIP's viewing conditions: give them with --metric flip");
    }
    options.threads = settings.threads ? settings.threads : std::max(1u, std::thread::hardware_concurrency());
    if (!settings.mask.empty()) options.mask.images.push_back(settings.mask);
    const std::unique_ptr<PageFolder> page = open_page(settings);
    if (page) options.page_dir = page->staging();
    for (const std::string& r : settings.ignore) options.mask.rects.push_back(parse_rect(r));
    if (!settings.preset.empty()) options.rules = read_diff_rules(settings.preset);
    options.max_memory = parse_byte_size(settings.load.max_memory, "--max-memory");
    options.cancel = catch_interrupts("diff");
    keep_freed_memory();
    DiffReport report = diff_images(settings.a, settings.b, options);
    for (const ImageDiff& d : report.pairs)
      if (!d.unreadable.empty()) print_error(d.unreadable, d.read_error);
    if (settings.approve) {
      report.approval = true;
      report.approval_dry_run = settings.dry_run;
      report.approved = approvals(report);
    }
    // The page before the goldens change, so that a page that cannot be written changes nothing; the
    // approval before any report, so that one that cannot be made (a read-only folder) is the only line
    // printed.
    if (page) page->commit(diff_page_html(report));
    if (settings.approve && !settings.dry_run) approve(report.approved);
    std::cout << (settings.json ? diff_json(report) : diff_text(report)) << std::flush;
    write_junit(settings.junit, diff_junit(report));
    write_annotations(settings, report.status(), ci_rows(report));
    // Approved goldens are settled; a dry run changes nothing, so its status is the diff's.
    return exit_status(settings.approve && !settings.dry_run ? report.status_after_approval() : report.status());
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
  std::vector<CLI::Option*>& thresholds = diff.threshold_options;
  thresholds.push_back(diff_cmd->add_option("--fail", diff.thresholds.fail, "A pixel is over --fail when any channel differs by more (FLIP: its FLIP value)")
      ->type_name("VAL")
      ->capture_default_str());
  thresholds.push_back(diff_cmd->add_option("--failpercent", diff.thresholds.fail_percent,
                       "A pair fails when more than this percentage of its pixels are over --fail (a percentile: "
                       "--failpercent 1 fails a 99th percentile over --fail)")
      ->type_name("PERCENT")
      ->capture_default_str());
  thresholds.push_back(diff_cmd->add_option("--hardfail", diff.thresholds.hard_fail,
                       "A pair fails when any channel differs by more, whatever the percentage (FLIP: its max)")
      ->type_name("VAL")
      ->capture_default_str());
  thresholds.push_back(diff_cmd->add_option("--failmean", diff.thresholds.fail_mean, "A pair fails when its mean error is over this")
      ->type_name("VAL"));
  thresholds.push_back(diff_cmd->add_option("--warn", diff.thresholds.warn, "A pixel is over --warn when any channel differs by more")
      ->type_name("VAL")
      ->capture_default_str());
  thresholds.push_back(diff_cmd->add_option("--warnpercent", diff.thresholds.warn_percent,
                       "A pair warns when more than this percentage of its pixels are over --warn")
      ->type_name("PERCENT")
      ->capture_default_str());
  thresholds.push_back(diff_cmd->add_option("--hardwarn", diff.thresholds.hard_warn,
                       "A pair warns when any channel differs by more, whatever the percentage")
      ->type_name("VAL")
      ->capture_default_str());
  thresholds.push_back(diff_cmd->add_option("--warnmean", diff.thresholds.warn_mean, "A pair warns when its mean error is over this")
      ->type_name("VAL"));
  diff_cmd->add_option("--metric", diff.metric,
                       "Images: idiff (each pixel's largest channel difference) or flip (NVIDIA's FLIP: how visible the "
                       "difference is, 0 to 1)")
      ->type_name("idiff|flip")
      ->capture_default_str();
  diff_cmd->add_option("--ppd", diff.ppd, "FLIP: pixels per degree of visual angle (default 67.02: 0.7 m from a 0.7 m "
                                          "wide 3840-pixel monitor)")
      ->type_name("PPD");
  diff_cmd->add_option("--viewing", diff.viewing, "FLIP: the viewing conditions as the distance and the screen's width "
                                                  "in metres and its pixels across; sets --ppd")
      ->expected(3)
      ->option_text("DIST WIDTH PIXELS");  // not CLI11's "TYPE x 3"
  diff_cmd->add_option("-j,--threads", diff.threads, "Images: pairs compared at once, and FLIP's rows of an image (default: one per core)")
      ->type_name("N");
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
  // As bake's, on A's animations; without any of them, every key time of both files and the midpoints.
  add_frame_selection(*diff_cmd, diff.selection, "compare", false);
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
  diff_cmd->add_option("--mask", diff.mask,
                       "Images: leave out of every pair the pixels where this image (same size) is white (first channel "
                       "at least 0.5)")
      ->type_name("IMAGE");
  diff_cmd->add_option("--ignore", diff.ignore, "Images: leave out of every pair this rectangle of pixels (repeatable)")
      ->type_name("X,Y,W,H");
  diff_cmd->add_option("--preset", diff.preset,
                       "Images: rules by name pattern (metric, thresholds, mask) in one JSON file; the first rule matching "
                       "a pair decides it, the command line's flags the others")
      ->type_name("FILE");
  diff_cmd->add_option("--html", diff.html,
                       "Also write one page to look at, DIR/index.html with its pictures in DIR/images (replaces DIR): every "
                       "pair, failing first, reference, candidate and difference side by side, a toggle and a swipe; for "
                       "glTF files every clip, both surfaces at its worst frame shaded by their distance, its error over time")
      ->type_name("DIR");
  diff_cmd->add_flag("--approve", diff.approve,
                     "Images: make the candidates of failing pairs (B) the goldens (A), all or none, and say so in the "
                     "report; exit status then that of the pairs left as they were");
  diff_cmd->add_flag("--dry-run", diff.dry_run, "With --approve: list what it would replace, change nothing");
  diff_cmd->add_option("--annotations", diff.annotations,
                       "Also report to the CI: github (an ::error or ::warning workflow command per failing or warning "
                       "pair or clip on stdout, and a Markdown step summary) or gitlab (a Code Quality report)")
      ->type_name("github|gitlab");
  diff_cmd->add_option("--annotations-file", diff.annotations_file,
                       "github: append the step summary here (default $GITHUB_STEP_SUMMARY, none when unset); gitlab: "
                       "write the report here (default gl-code-quality-report.json)")
      ->type_name("FILE");
  diff_cmd->footer(
      "Verdict (idiff's): a pair FAILs when more than --failpercent % of its pixels are over --fail, or any channel\n"
      "differs by more than --hardfail, or a NaN or infinity meets another value; else it WARNs when more than\n"
      "--warnpercent % are over --warn, or any channel differs by more than --hardwarn; else it PASSes. The defaults\n"
      "are idiff's: any difference over 1e-6 fails. For warnings, set --fail above --warn or a --failpercent.\n"
      "Images of different sizes or channel counts, files missing from one folder and unreadable files FAIL.\n"
      "Pixels are read as float (8-bit 255 = 1.0); the first subimage is compared.\n"
      "--metric flip: each pixel's FLIP value (Andersson et al. 2020), 0 to 1, for an observer --ppd pixels per\n"
      "degree away, on the first three channels (one or two: the first as grey; colours with alpha seen over\n"
      "black). Integer files are display values (LDR-FLIP); float files (EXR, HDR) are linear light, measured by\n"
      "HDR-FLIP (ACES tone mapping at exposures from the reference's brightest to its median pixel).\n"
      "The thresholds given judge FLIP values and no others; with none given, any visible difference (a mean over\n"
      "0) fails. Heat maps: magma from black (0) to light yellow (1), with its colour bar.\n"
      "Folders: image files (exr, png, jpg, jpeg, tif, tiff, gif, hdr, tga, webp, ...) found recursively, paired\n"
      "by relative path; other files are ignored.\n"
      "Heat maps: each pixel's largest channel difference; black at most --fail, then viridis from dark purple (just\n"
      "over --fail) to yellow (the pair's max error, printed in the report); white where it is NaN or infinite.\n"
      "Two glTF files (.gltf, .glb): both are deformed with --mode at the same times, A's clips paired with B's\n"
      "by name, then by index. The times: every key time of both files and the midpoints between them, or those\n"
      "--fps (up to 1000), --frames, --keys or --times choose on A's clip, as bake samples it.\n"
      "Each vertex of A is followed through the animation at its closest point on B's\n"
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
      "  dqskin diff golden out --fail 0.02 --warn 0.004 --failpercent 0.1 --out diffs --junit diff.xml\n"
      "  dqskin diff golden out --metric flip --failmean 0.05 --fail 0.5 --failpercent 1 --out diffs");
  return {diff_cmd, [settings] { return run_diff(*settings); }};
}

}  // namespace dqskin::cli
