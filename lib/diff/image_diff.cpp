// `dqskin diff`'s measuring: arguments paired (folders by relative path), idiff's verdict, and each pair
// compared by the image module (diff_images_oiio.cpp: OpenImageIO's ImageBufAlgo::compare, heat maps of
// failing pairs); include/dqskin/image_diff.hpp. The reports are diff_report.cpp's.
#include "dqskin/image_diff.hpp"
#include "diff_image_files.hpp"
#include "diff_numbers.hpp"
#include "../base/image_module.hpp"
#include "../base/parallel_for.hpp"

#include "dqskin/error.hpp"
#include "dqskin/job.hpp"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <map>
#include <system_error>
#include <utility>

namespace dqskin {
namespace {

namespace fs = std::filesystem;
using diff_detail::number;
using diff_detail::percent;

std::string pixels_text(uint64_t count) { return std::to_string(count) + (count == 1 ? " pixel" : " pixels"); }


}  // namespace

namespace diff_detail {

// idiff's rule (OpenImageIO 2.4 src/idiff/idiff.cpp) without its --allowfailures short cut, which in 2.4
// also skips the warning tests whenever no pixel is over --fail.
std::pair<DiffStatus, std::string> judge(const DiffThresholds& t, double max_error, uint64_t over_warn,
                                         uint64_t over_fail, uint64_t pixels, double mean_error) {
  const double n = double(std::max<uint64_t>(pixels, 1));
  if (!std::isfinite(max_error))
    return {DiffStatus::kFail, "max error " + number(max_error) + ": a NaN or infinity in one image only"};
  if (double(over_fail) > t.fail_percent / 100.0 * n)
    return {DiffStatus::kFail, pixels_text(over_fail) + " (" + percent(over_fail, pixels) + ") over --fail " +
                                   number(t.fail) + ", more than --failpercent " + number(t.fail_percent)};
  if (max_error > t.hard_fail)
    return {DiffStatus::kFail, "max error " + number(max_error) + " over --hardfail " + number(t.hard_fail)};
  if (mean_error > t.fail_mean)
    return {DiffStatus::kFail, "mean error " + number(mean_error) + " over --failmean " + number(t.fail_mean)};
  if (double(over_warn) > t.warn_percent / 100.0 * n)
    return {DiffStatus::kWarn, pixels_text(over_warn) + " (" + percent(over_warn, pixels) + ") over --warn " +
                                   number(t.warn) + ", more than --warnpercent " + number(t.warn_percent)};
  if (max_error > t.hard_warn)
    return {DiffStatus::kWarn, "max error " + number(max_error) + " over --hardwarn " + number(t.hard_warn)};
  if (mean_error > t.warn_mean)
    return {DiffStatus::kWarn, "mean error " + number(mean_error) + " over --warnmean " + number(t.warn_mean)};
  return {DiffStatus::kPass, ""};
}

const DiffImageFiles& diff_image_files() {
  static const DiffImageFiles& files = image_module_part<DiffImageFiles>("dqskin_diff_image_files");
  return files;
}

}  // namespace diff_detail

std::string check_thresholds(const DiffThresholds& t) {
  const std::pair<const char*, double> values[] = {{"--fail", t.fail},         {"--warn", t.warn},
                                                   {"--hardfail", t.hard_fail}, {"--hardwarn", t.hard_warn},
                                                   {"--failmean", t.fail_mean}, {"--warnmean", t.warn_mean}};
  for (const auto& [name, value] : values)
    if (!(value >= 0)) return std::string(name) + " must be at least 0, not " + number(value);
  const std::pair<const char*, double> percents[] = {{"--failpercent", t.fail_percent},
                                                     {"--warnpercent", t.warn_percent}};
  for (const auto& [name, value] : percents)
    if (!(value >= 0 && value <= 100)) return std::string(name) + " must be from 0 to 100, not " + number(value);
  return "";
}

DiffThresholds flip_thresholds(const DiffThresholds& values, const std::vector<std::string>& given) {
  constexpr double kOff = std::numeric_limits<double>::infinity();
  const auto has = [&given](const char* name) { return std::find(given.begin(), given.end(), name) != given.end(); };
  DiffThresholds t{kOff, 0, kOff, kOff, 0, kOff, kOff, kOff};
  if (given.empty()) {
    t.fail_mean = 0;
    return t;
  }
  if (has("--fail")) t.fail = values.fail;
  if (has("--failpercent")) t.fail_percent = values.fail_percent;
  if (has("--hardfail")) t.hard_fail = values.hard_fail;
  if (has("--warn")) t.warn = values.warn;
  if (has("--warnpercent")) t.warn_percent = values.warn_percent;
  if (has("--hardwarn")) t.hard_warn = values.hard_warn;
  if (has("--failmean")) t.fail_mean = values.fail_mean;
  if (has("--warnmean")) t.warn_mean = values.warn_mean;
  return t;
}

const char* metric_name(DiffMetric metric) { return metric == DiffMetric::kFlip ? "flip" : "idiff"; }

const char* status_name(DiffStatus status) {
  switch (status) {
    case DiffStatus::kPass: return "PASS";
    case DiffStatus::kWarn: return "WARN";
    case DiffStatus::kFail: return "FAIL";
  }
  return "FAIL";
}

DiffStatus diff_verdict(const DiffThresholds& thresholds, double max_error, uint64_t over_warn, uint64_t over_fail,
                        uint64_t pixels, double mean_error) {
  return diff_detail::judge(thresholds, max_error, over_warn, over_fail, pixels, mean_error).first;
}

DiffStatus DiffReport::status() const {
  DiffStatus worst = DiffStatus::kPass;
  for (const ImageDiff& p : pairs) worst = std::max(worst, p.status);
  return worst;
}

DiffStatus DiffReport::status_after_approval() const {
  if (!approval) return status();
  DiffStatus worst = DiffStatus::kPass;
  for (const ImageDiff& p : pairs)
    if (std::none_of(approved.begin(), approved.end(), [&p](const Approval& done) { return done.name == p.name; }))
      worst = std::max(worst, p.status);
  return worst;
}

size_t DiffReport::count(DiffStatus status) const {
  return size_t(std::count_if(pairs.begin(), pairs.end(), [status](const ImageDiff& p) { return p.status == status; }));
}

bool is_image_name(const std::string& path) {
  static const char* const kExtensions[] = {"exr", "png", "jpg", "jpeg", "tif", "tiff", "tx",   "gif", "hdr",
                                            "tga", "bmp", "dpx", "cin",  "webp", "ppm",  "pgm", "pbm", "pnm",
                                            "pfm", "jp2", "j2k", "dds",  "psd",  "sgi",  "heic", "avif"};
  const size_t dot = path.find_last_of("./");
  if (dot == std::string::npos || path[dot] != '.') return false;
  std::string extension = path.substr(dot + 1);
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return std::any_of(std::begin(kExtensions), std::end(kExtensions),
                     [&extension](const char* e) { return extension == e; });
}

std::vector<DiffPair> pair_inputs(const std::string& a, const std::string& b) {
  std::error_code error;
  const bool a_folder = fs::is_directory(a, error);
  const bool b_folder = fs::is_directory(b, error);
  if (a_folder && !b_folder) {
    if (!fs::exists(b, error)) throw InputError(b + ": no such folder (A, " + a + ", is a folder)");
    throw InputError(b + ": not a folder, but A (" + a + ") is one; give two images or two folders");
  }
  if (!a_folder) {
    const std::string name = fs::path(a).filename().string();
    DiffPair pair{a, a, b, name + ".diff.png", ""};
    if (b_folder) pair.b = (fs::path(b) / name).string();  // idiff: IMAGE FOLDER compares IMAGE with FOLDER/IMAGE
    return {pair};
  }

  // Both folders: image files under each, by '/'-separated relative path.
  auto list = [](const std::string& root) {
    std::map<std::string, std::string> files;
    try {
      for (const fs::directory_entry& e : fs::recursive_directory_iterator(root)) {
        std::error_code ignored;
        if (!e.is_regular_file(ignored) || !is_image_name(e.path().filename().string())) continue;
        files[e.path().lexically_relative(root).generic_string()] = e.path().string();
      }
    } catch (const fs::filesystem_error& e) {
      throw InputError((e.path1().empty() ? root : e.path1().string()) + ": " + e.code().message());
    }
    return files;
  };
  const std::map<std::string, std::string> in_a = list(a), in_b = list(b);
  std::vector<DiffPair> pairs;
  auto ia = in_a.begin();
  auto ib = in_b.begin();
  while (ia != in_a.end() || ib != in_b.end()) {
    const bool take_a = ib == in_b.end() || (ia != in_a.end() && ia->first <= ib->first);
    const bool take_b = ia == in_a.end() || (ib != in_b.end() && ib->first <= ia->first);
    const std::string& name = take_a ? ia->first : ib->first;
    DiffPair pair{name, take_a ? ia->second : "", take_b ? ib->second : "", name + ".diff.png", ""};
    pairs.push_back(std::move(pair));
    if (take_a) ++ia;
    if (take_b) ++ib;
  }
  if (pairs.empty()) throw InputError(a + ": no image files here or in " + b);
  return pairs;
}

ImageDiff diff_pair(const DiffPair& pair, const DiffOptions& options) {
  assert(!pair.a.empty() || !pair.b.empty());
  return diff_detail::diff_image_files().diff_pair(pair, options);
}

DiffReport diff_images(const std::string& a, const std::string& b, const DiffOptions& options) {
  DiffReport report;
  report.a = a;
  report.b = b;
  report.thresholds = options.thresholds;
  report.metric = options.metric;
  report.pixels_per_degree = options.pixels_per_degree;
  std::vector<DiffPair> pairs = pair_inputs(a, b);
  for (size_t i = 0; i < pairs.size(); ++i) {
    char stem[32];
    std::snprintf(stem, sizeof stem, "images/%04zu", i);
    pairs[i].page_stem = stem;  // by place in name order: the same names give the same files
  }
  // Pairs are compared side by side, each on its share of the threads: a folder of small renders keeps
  // every core busy, where one image's bands alone would not (a 512² image is a band or two), and one
  // large image still gets them all. They share --max-memory through a ledger. Pairs start in name order
  // and the first failure (an error, not a failing pair) stops new ones, so the error reported is the one
  // that comparing them one after the other would meet, and the report is in name order whatever finished
  // first.
  const size_t workers = std::clamp<size_t>(options.threads, 1, std::max<size_t>(pairs.size(), 1));
  diff_detail::MemoryLedger ledger(options.max_memory);
  DiffOptions shared = options;
  shared.threads = unsigned(std::max<size_t>(1, options.threads / workers));
  report.pairs.resize(pairs.size());
  std::vector<std::exception_ptr> errors(pairs.size());
  // The first pair (in name order) that failed so far: later ones are not started; earlier ones finish,
  // since one of them may fail too and is then the error to report.
  std::atomic<size_t> first_failed{pairs.size()};
  concurrency::parallel_for(pairs.size(), unsigned(workers), [&](size_t i) {
    if (i > first_failed) return;
    try {
      check_cancelled(options.cancel);
      const DiffRule* rule = nullptr;
      const DiffOptions pair_options = options_for(shared, pairs[i].name, &rule);
      ImageDiff d = pairs[i].a.empty() || pairs[i].b.empty() ? diff_pair(pairs[i], pair_options)
                                                             : diff_detail::diff_image_files().diff_pair(pairs[i], pair_options, &ledger);
      d.thresholds = pair_options.thresholds;
      d.metric = pair_options.metric;  // also for a pair that could not be measured
      if (rule) d.rule = rule->pattern;
      report.pairs[i] = std::move(d);
    } catch (...) {
      errors[i] = std::current_exception();
      for (size_t seen = first_failed; i < seen && !first_failed.compare_exchange_weak(seen, i);) {
      }
    }
  });
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  return report;
}

}  // namespace dqskin
