// Comparing images the way OpenImageIO's idiff does, for renders checked in CI: two images, or two folders
// paired by relative path. The numbers are ImageBufAlgo::compare's (max, mean and RMS error, PSNR, pixels
// over the warn and fail thresholds); the verdict applies idiff's thresholds to them. Also writes heat maps
// of failing pairs. The reports of the result (text, JSON, JUnit XML) are dqskin/diff_report.hpp's.
// OpenImageIO stays out of this header.
#pragma once

#include "dqskin/load.hpp"  // kDefaultMaxMemory

#include <atomic>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace dqskin {

// idiff's thresholds and defaults (idiff --help, OpenImageIO 2.4). A pixel is "over" a threshold when any
// of its channels differs by more than it. A pair fails when more than fail_percent % of its pixels are
// over `fail`, or when any channel differs by more than hard_fail; otherwise it warns when more than
// warn_percent % are over `warn`, or any channel differs by more than hard_warn; otherwise it passes.
// With the defaults (warn = fail) any difference over 1e-6 fails: warnings need a `fail` above `warn`
// or a nonzero fail_percent.
// Beyond idiff: fail_mean and warn_mean judge the mean error (off by default).
struct DiffThresholds {
  double fail = 1e-6;
  double fail_percent = 0;
  double hard_fail = std::numeric_limits<double>::infinity();
  double warn = 1e-6;
  double warn_percent = 0;
  double hard_warn = std::numeric_limits<double>::infinity();
  double fail_mean = std::numeric_limits<double>::infinity();
  double warn_mean = std::numeric_limits<double>::infinity();
};

// What a pixel's error is. kIdiff: its largest channel difference, as idiff. kFlip: FLIP's perceptual
// difference (Andersson et al. 2020), from 0 (none seen) to 1, under the viewing conditions of
// DiffOptions::pixels_per_degree; the thresholds then apply to FLIP values.
enum class DiffMetric { kIdiff, kFlip };

// "idiff" or "flip".
const char* metric_name(DiffMetric metric);

// Empty when the thresholds are usable; otherwise what is wrong, naming the option ("--fail must be at
// least 0"). Thresholds are at least 0 (hard ones may be infinite), percentages from 0 to 100, none NaN.
std::string check_thresholds(const DiffThresholds& thresholds);

// Thresholds for FLIP: the rules given (named by their option, "--failmean", in `given`) and none of the
// others; when none is given, any visible difference fails (a mean above 0). idiff's defaults do not fit
// FLIP: every pixel near a change has a FLIP value, so "no pixel over 1e-6" is the same as "identical".
DiffThresholds flip_thresholds(const DiffThresholds& values, const std::vector<std::string>& given);

enum class DiffStatus { kPass, kWarn, kFail };

// "PASS", "WARN" or "FAIL".
const char* status_name(DiffStatus status);

// The verdict of `thresholds` for ImageBufAlgo::compare's numbers of one pair (`pixels` of them, at least
// 1). A max error that is not finite (a NaN or infinity where the other image has something else) fails
// whatever the thresholds: idiff would let it pass unless --hardfail is finite.
DiffStatus diff_verdict(const DiffThresholds& thresholds, double max_error, uint64_t over_warn, uint64_t over_fail,
                        uint64_t pixels, double mean_error = 0);

// Two files to compare; in folder mode `name` is their relative path, and a side that is missing is empty.
struct DiffPair {
  DiffPair() = default;
  DiffPair(std::string name_, std::string a_, std::string b_, std::string heat_map_name_, std::string page_stem_ = "")
      : name(std::move(name_)), a(std::move(a_)), b(std::move(b_)), heat_map_name(std::move(heat_map_name_)),
        page_stem(std::move(page_stem_)) {}
  std::string name;  // what the reports call the pair
  std::string a, b;  // the files; one may be empty (missing from its folder), not both
  std::string heat_map_name;  // relative path of the heat map under DiffOptions::heat_map_dir
  std::string page_stem;      // the page's pictures of this pair: page_dir/page_stem.{a,b,diff}.png
};

// The outcome for one pair. Metrics are valid only when `compared`; otherwise `problem` says why the pair
// failed without being compared.
struct ImageDiff {
  std::string name, a, b;
  DiffStatus status = DiffStatus::kPass;
  bool compared = false;
  std::string problem;     // "missing in B", "size 8x8 vs 4x4", "cannot read FILE: reason"; empty if compared
  std::string unreadable;  // the file that could not be read, when that was the problem,
  std::string read_error;  // and why (one line: "No such file or directory", OpenImageIO's message)
  std::string reason;      // why it failed or warned, in words ("3 pixels (18.8%) over --fail 1e-06"); empty on PASS

  // ImageBufAlgo::compare's results (first subimage, MIP level 0; pixels read as float), or FLIP's: its
  // max, mean and RMS over the pixels, no PSNR (NaN), no channel.
  DiffMetric metric = DiffMetric::kIdiff;
  double max_error = 0, mean_error = 0, rms_error = 0;
  double psnr = 0;                   // +infinity for identical images
  int max_x = 0, max_y = 0;          // where max_error was found (0, 0 when it is 0)
  std::string max_channel;           // the channel's name there ("R"), or its index when unnamed; empty for FLIP
  // FLIP only: its weighted quartiles, each pixel weighted by its own error (FLIP's pooling).
  double flip_q1 = 0, flip_median = 0, flip_q3 = 0;
  // HDR-FLIP (float files): how many exposures, from 2^start to 2^stop; 0 for LDR-FLIP.
  int hdr_exposures = 0;
  double hdr_start = 0, hdr_stop = 0;
  uint64_t masked = 0;  // pixels left out (DiffMask); `pixels` counts the others
  std::string rule;     // the pattern of the preset rule that judged the pair, or empty
  DiffThresholds thresholds;  // what judged it
  uint64_t pixels = 0;               // width × height × depth
  uint64_t over_warn = 0, over_fail = 0;

  std::string heat_map;  // the heat map written for this pair, or empty
  // The page's pictures (DiffOptions::page_dir), relative to it: A and B as 8-bit sRGB PNGs and the
  // difference (the heat map of the metric, for any pair that differs); empty where there is none.
  std::string page_a, page_b, page_difference;
};

// Pixels left out of a comparison: those of a mask image (same size as the images; where its first
// channel is at least 0.5, white, the pixel is left out) and of rectangles. Left-out pixels take the
// reference's values in the candidate, so that they neither count nor spread into FLIP's filters, and the
// figures are over the other pixels.
struct PixelRect {
  int x = 0, y = 0, width = 0, height = 0;
};
struct DiffMask {
  std::vector<std::string> images;  // mask images (each leaves out its white pixels)
  std::vector<PixelRect> rects;     // parts beyond the image are ignored
  bool empty() const { return images.empty() && rects.empty(); }
};

// A preset's rule for the pairs whose name matches `pattern` (a glob on the '/'-separated relative path:
// `*` any characters but '/', `**` any, `?` one): the metric and thresholds of those pairs, in place of the
// command line's. Thresholds it does not give take the metric's defaults (idiff's; for FLIP, the given
// rules only, as flip_thresholds).
struct DiffRule {
  std::string pattern;
  DiffMetric metric = DiffMetric::kIdiff;
  DiffThresholds thresholds;  // as judged (flip_thresholds already applied)
  double pixels_per_degree = 0;  // FLIP; 0: the command line's
  DiffMask mask;                  // added to the command line's
};

// The rules of a preset file (JSON: {"rules": [{"match": PATTERN, "metric": "idiff"|"flip", "fail": V,
// "failpercent": P, "hardfail": V, "failmean": V, "warn": V, "warnpercent": P, "hardwarn": V,
// "warnmean": V, "ppd": PPD, "mask": IMAGE, "ignore": [[X, Y, W, H], ...]}, ...]}; a mask's path is
// relative to the preset file's folder). Throws InputError naming the file and what is wrong: JSON that
// does not parse, an unknown key, a value of the wrong type or out of range.
std::vector<DiffRule> read_diff_rules(const std::string& path);

// True when the relative path `name` matches the glob `pattern` (DiffRule).
bool glob_match(const std::string& pattern, const std::string& name);

struct DiffOptions {
  DiffThresholds thresholds;
  DiffMask mask;                // left out of every pair
  std::vector<DiffRule> rules;  // the first whose pattern matches a pair's name decides its metric and thresholds
  DiffMetric metric = DiffMetric::kIdiff;
  // FLIP's viewing conditions: pixels per degree of visual angle; the FLIP paper's 0.7 m from a 0.7 m
  // wide 4K monitor by default (67.02).
  double pixels_per_degree = 67.02064327658226;
  // Threads: pairs of a folder compared at once (up to this many), each with its share for FLIP's bands
  // (a single pair gets them all). The report is the same for any number.
  unsigned threads = 1;
  // When set, a heat map is written for every failing pair that could be compared, to
  // heat_map_dir/heat_map_name (folders created as needed): an 8-bit RGB PNG of each pixel's largest
  // channel difference, black where it is at most `fail`, else the viridis colormap from dark (just over
  // `fail`) to yellow (the pair's max error); white where the difference is not finite. For FLIP, each
  // pixel's FLIP value in the magma colormap from black (0) to light yellow (1), with its colour bar and
  // labels in a panel on the right. Written atomically (a complete file or none) and the same bytes for
  // the same inputs.
  std::string heat_map_dir;
  // Most memory comparing one pair may take (--max-memory): both images as float, what reading takes and
  // the heat map; for FLIP also its error map and the bands being computed. Checked against what each
  // file declares before its pixels are allocated; a file that needs more is unreadable ("comparing it
  // needs about …"). Pairs compared at once share it: a pair waits while it does not fit beside the others.
  uint64_t max_memory = kDefaultMaxMemory;
  // When set, the pictures of the HTML page (diff_page.hpp) are written under it for every pair that
  // could be read: page_dir/DiffPair::page_stem.{a,b,diff}.png.
  std::string page_dir;
  // Checked before each pair: once set, diff_images throws JobCancelled (dqskin/job.hpp). May be null.
  const std::atomic<bool>* cancel = nullptr;
};

// One golden replaced (or added, for a candidate with no golden yet) by its candidate: `diff --approve`
// (golden_approval.hpp).
struct Approval {
  std::string name;       // the pair's name
  std::string golden;     // the file that holds (or will hold) the candidate's bytes
  std::string candidate;  // the file they come from
  bool added = false;     // no golden existed
};

struct DiffReport {
  std::string a, b;  // the command's two arguments
  DiffThresholds thresholds;
  DiffMetric metric = DiffMetric::kIdiff;
  double pixels_per_degree = 0;  // FLIP's viewing conditions (reported for FLIP only)
  std::vector<ImageDiff> pairs;  // in name order

  // --approve: whether it was asked for, as a dry run, and the goldens replaced (or, in a dry run, those
  // that would be).
  bool approval = false, approval_dry_run = false;
  std::vector<Approval> approved;

  // FAIL when any pair failed, else WARN when any warned, else PASS (also when there are no pairs).
  DiffStatus status() const;
  // The same over the pairs an approval leaves (or, in a dry run, would leave) as they were: an approved
  // pair's golden is its candidate.
  DiffStatus status_after_approval() const;
  size_t count(DiffStatus status) const;
};

// True when `path` ends in an image extension diff looks for in folders (case-insensitive): exr, png, jpg,
// jpeg, tif, tiff, tx, gif, hdr, tga, bmp, dpx, cin, webp, ppm, pgm, pbm, pnm, pfm, jp2, j2k, dds, psd, sgi,
// heic, avif.
bool is_image_name(const std::string& path);

// The pairs to compare for the arguments A and B: two files give one pair (named A); a file and a folder
// give A and B/filename(A), as idiff does; two folders give one pair per image file (is_image_name) found
// under either, recursively, matched by relative path ('/'-separated, in byte order), with the side that
// lacks it left empty. Other files are ignored. Throws InputError for a folder A with a file B, a folder
// that cannot be listed, and two folders without any image file. A path that does not exist is a file
// (the comparison reports it as unreadable).
std::vector<DiffPair> pair_inputs(const std::string& a, const std::string& b);

// Compares one pair: reads both files (first subimage, as float), checks that their sizes (data windows)
// and channel counts match, runs ImageBufAlgo::compare with the thresholds and applies diff_verdict.
// Missing, unreadable, deep or mismatched images give a failing ImageDiff with a `problem`, not an
// exception. Writes the heat map of a failing pair when options.heat_map_dir is set; throws OutputError
// naming the file when it cannot be written.
ImageDiff diff_pair(const DiffPair& pair, const DiffOptions& options);

// The options a pair is compared with: `options`, or for the first rule whose pattern matches `name`, its
// metric, thresholds and viewing conditions, and its mask added.
// `rule`, when given, is set to the matching rule (null when none matches).
DiffOptions options_for(const DiffOptions& options, const std::string& name, const DiffRule** rule = nullptr);

// pair_inputs, then diff_pair for every pair (with options_for its name), in order. Throws as they do, and JobCancelled once
// options.cancel is set.
DiffReport diff_images(const std::string& a, const std::string& b, const DiffOptions& options);

}  // namespace dqskin
