// `dqskin diff`'s measuring: arguments paired (folders by relative path), images compared by OpenImageIO's
// ImageBufAlgo::compare with idiff's thresholds, and heat maps of failing pairs
// (include/dqskin/image_diff.hpp). The reports are diff_report.cpp's.
#include "dqskin/image_diff.hpp"
#include "diff_numbers.hpp"
#include "image_bands.hpp"
#include "../base/file_kind.hpp"
#include "../base/oiio_message.hpp"
#include "../base/saturating.hpp"
#include "../base/image_file.hpp"
#include "../base/srgb.hpp"
#include "../base/stderr_capture.hpp"

#include "dqskin/atomic_file.hpp"
#include "../base/byte_size.hpp"
#include "dqskin/error.hpp"
#include "dqskin/job.hpp"
#include "dqskin/memory_ceiling.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <new>
#include <system_error>
#include <utility>

namespace dqskin {
namespace {

namespace fs = std::filesystem;
using diff_detail::number;
using diff_detail::percent;

std::string pixels_text(uint64_t count) { return std::to_string(count) + (count == 1 ? " pixel" : " pixels"); }

// The verdict and, unless it is PASS, the rule that decided it, in words. idiff's rule (OpenImageIO
// 2.4 src/idiff/idiff.cpp) without its --allowfailures short cut, which in 2.4 also skips the warning
// tests whenever no pixel is over --fail.
std::pair<DiffStatus, std::string> judge(const DiffThresholds& t, double max_error, uint64_t over_warn,
                                         uint64_t over_fail, uint64_t pixels) {
  const double n = double(std::max<uint64_t>(pixels, 1));
  if (!std::isfinite(max_error))
    return {DiffStatus::kFail, "max error " + number(max_error) + ": a NaN or infinity in one image only"};
  if (double(over_fail) > t.fail_percent / 100.0 * n)
    return {DiffStatus::kFail, pixels_text(over_fail) + " (" + percent(over_fail, pixels) + ") over --fail " +
                                   number(t.fail) + ", more than --failpercent " + number(t.fail_percent)};
  if (max_error > t.hard_fail)
    return {DiffStatus::kFail, "max error " + number(max_error) + " over --hardfail " + number(t.hard_fail)};
  if (double(over_warn) > t.warn_percent / 100.0 * n)
    return {DiffStatus::kWarn, pixels_text(over_warn) + " (" + percent(over_warn, pixels) + ") over --warn " +
                                   number(t.warn) + ", more than --warnpercent " + number(t.warn_percent)};
  if (max_error > t.hard_warn)
    return {DiffStatus::kWarn, "max error " + number(max_error) + " over --hardwarn " + number(t.hard_warn)};
  return {DiffStatus::kPass, ""};
}

// Opens `path` for reading its first subimage into `in`. Returns why it cannot, or "".
std::string open_image(const std::string& path, std::unique_ptr<OIIO::ImageInput>& in) {
  // Checked before OpenImageIO opens it: a FIFO would block the open until a writer comes, a device such
  // as /dev/zero would be read forever (symbolic links are followed to what they name).
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (error) return error.message();
  if (fs::is_directory(status)) return "is a folder";
  struct stat st {};
  if (!fs::is_regular_file(status))
    return std::string("is ") + (::stat(path.c_str(), &st) == 0 ? file_kind(st.st_mode) : "not a file") + ", not a regular file";
  OIIO::geterror();  // forget earlier messages
  CapturedStderr capture;  // libpng prints its own "libpng error: …" line; it becomes part of ours
  in = OIIO::ImageInput::open(path);
  if (!in) return with_library_text(oiio_message(OIIO::geterror()), capture.finish());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.deep) return "deep (multi-sample) images are not compared";
  if (spec.width <= 0 || spec.height <= 0 || spec.depth <= 0 || spec.nchannels <= 0) return "the image has no pixels";
  return "";
}

// One image as compared: its pixels as float in memory of our own, which the --max-memory ceiling counts
// (an ImageBuf's own allocation fails quietly, leaving no pixels), wrapped by an ImageBuf for
// ImageBufAlgo::compare.
struct FloatImage {
  std::unique_ptr<float[]> pixels;  // not zeroed first: every value is read
  OIIO::ImageBuf buffer;
};

// Reads the image `in` has open into `image`. Returns why it cannot, or "".
std::string read_pixels(OIIO::ImageInput& in, FloatImage& image) {
  OIIO::ImageSpec spec = in.spec();
  spec.set_format(OIIO::TypeDesc::FLOAT);
  spec.channelformats.clear();
  image.pixels.reset(new float[size_t(diff_detail::float_bytes(spec) / 4)]);
  CapturedStderr capture;
  const std::string why = diff_detail::read_float_image(in, image.pixels.get());
  if (!why.empty()) return with_library_text(oiio_message(why), capture.finish());
  image.buffer.reset(spec, image.pixels.get());
  return "";
}

// Bytes of a heat map's working images, per pixel: each pixel's largest difference and its place in the
// colormap (floats), its color (3 floats) and the 8-bit RGB written.
constexpr uint64_t kHeatMapBytesPerPixel = 4 + 4 + 12 + 3;

// Why reading image `i` (0: A, 1: B) of a pair needs more memory than `budget`, or "": A is read first,
// then B beside it, then the heat map (when one may be written) beside both. `a` and `b` are what the
// files declare; b is unused for A.
std::string over_budget(size_t i, const OIIO::ImageSpec& a, const OIIO::ImageSpec& b, bool heat_map, uint64_t budget) {
  using saturating::add;
  using saturating::mul;
  const OIIO::ImageSpec& s = i == 0 ? a : b;
  const uint64_t other = i == 0 ? 0 : diff_detail::float_bytes(a);
  uint64_t beside = diff_detail::band_bytes(s);  // the most held beside the images: reading, or the heat map
  if (i == 1 && heat_map) beside = std::max(beside, mul(diff_detail::pixel_count(a), kHeatMapBytesPerPixel));
  const uint64_t need = add(add(other, diff_detail::float_bytes(s)), beside);
  if (need <= budget) return "";
  std::string size = std::to_string(s.width) + "x" + std::to_string(s.height);
  if (s.depth > 1) size.append("x").append(std::to_string(s.depth));
  size += " pixels of " + std::to_string(s.nchannels) + (s.nchannels == 1 ? " channel" : " channels");
  return "comparing it needs about " + byte_size(need) + " (its " + size + " as float" +
         (i == 0 ? std::string() : ", beside " + byte_size(other) + " for the other image" + (heat_map ? " and a heat map" : "")) +
         "), more than --max-memory " + byte_size(budget);
}

std::string window_text(const OIIO::ImageSpec& s) {
  std::string text = std::to_string(s.width) + "x" + std::to_string(s.height);
  // append, not "x" + std::to_string(…): GCC 12 at -O3 warns a false -Wrestrict for that (its
  // char_traits::copy inlined), depending on what else this file holds.
  if (s.depth != 1) text.append("x").append(std::to_string(s.depth));
  if (s.x != 0 || s.y != 0 || s.z != 0)
    text += " at (" + std::to_string(s.x) + ", " + std::to_string(s.y) + (s.z ? ", " + std::to_string(s.z) : "") + ")";
  return text;
}

// Why two images cannot be compared pixel for pixel, or "".
std::string mismatch(const OIIO::ImageSpec& a, const OIIO::ImageSpec& b) {
  if (a.x != b.x || a.y != b.y || a.z != b.z || a.width != b.width || a.height != b.height || a.depth != b.depth)
    return "size " + window_text(a) + " vs " + window_text(b);
  if (a.nchannels != b.nchannels)
    return std::to_string(a.nchannels) + " channels vs " + std::to_string(b.nchannels);
  return "";
}

// The difference of one channel as ImageBufAlgo::compare counts it: NaN matches NaN and infinity matches
// infinity; any other non-finite pair differs infinitely.
float channel_difference(float a, float b) {
  if (!std::isfinite(a) || !std::isfinite(b)) {
    if (std::isnan(a) == std::isnan(b) && std::isinf(a) == std::isinf(b)) return 0.0f;
    return std::numeric_limits<float>::infinity();
  }
  return std::abs(a - b);
}

// Writes the heat map of two same-sized float images (see DiffOptions::heat_map_dir) to `path`.
void write_heat_map(const std::string& path, const FloatImage& a, const FloatImage& b, double fail) {
  const OIIO::ImageSpec& spec = a.buffer.spec();
  const size_t width = size_t(spec.width), rows = size_t(spec.height) * size_t(spec.depth);
  const size_t channels = size_t(spec.nchannels), count = width * rows;
  const float* pa = a.pixels.get();
  const float* pb = b.pixels.get();

  // Each pixel's largest channel difference, and the largest finite one over the threshold: the top of the
  // colormap. The threshold is compared as compare does: a double against the float it was given.
  const double threshold = double(float(fail));
  std::vector<float> largest(count, 0.0f);
  float top = 0.0f;
  for (size_t i = 0; i < count; ++i) {
    float d = 0.0f;
    for (size_t c = 0; c < channels; ++c) d = std::max(d, channel_difference(pa[i * channels + c], pb[i * channels + c]));
    largest[i] = d;
    if (std::isfinite(d) && double(d) > threshold) top = std::max(top, d);
  }

  // Position in the colormap: 0 just over the threshold, 1 at the top. It and the colors are images in
  // memory of our own, as the pixels compared are: the ceiling counts them.
  std::vector<float> level_pixels(count), color_pixels(count * 3);
  OIIO::ImageBuf level(OIIO::ImageSpec(int(width), int(rows), 1, OIIO::TypeDesc::FLOAT), level_pixels.data());
  const double low = threshold, span = double(top) - threshold;
  for (size_t i = 0; i < count; ++i)
    level_pixels[i] = span > 0 && std::isfinite(largest[i]) ? float((double(largest[i]) - low) / span) : 1.0f;
  OIIO::ImageBuf colors(OIIO::ImageSpec(int(width), int(rows), 3, OIIO::TypeDesc::FLOAT), color_pixels.data());
  if (!OIIO::ImageBufAlgo::color_map(colors, level, 0, "viridis", {}, 1))
    throw OutputError(path + ": OpenImageIO color_map: " + oiio_message(colors.geterror()));
  const float* cp = color_pixels.data();

  std::vector<uint8_t> rgb(count * 3);
  for (size_t i = 0; i < count; ++i) {
    const float d = largest[i];
    for (size_t c = 0; c < 3; ++c) {
      uint8_t v = 0;  // black: not over the threshold
      if (!std::isfinite(d)) v = 255;
      else if (double(d) > threshold) v = io::srgb8(cp[i * 3 + c]);  // OpenImageIO's colormaps are linear
      rgb[i * 3 + c] = v;
    }
  }

  std::error_code error;
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty()) fs::create_directories(parent, error);
  if (error) throw OutputError(parent.string() + ": cannot create folder: " + error.message());

  AtomicFile file(path);
  OIIO::ImageSpec out_spec(int(width), int(rows), 3, OIIO::TypeDesc::UINT8);
  out_spec.attribute("oiio:ColorSpace", "sRGB");  // an sRGB chunk: the bytes are sRGB-encoded
  // The only text in the file; no time stamp, so the same inputs give the same bytes.
  out_spec.attribute("ImageDescription", "dqskin diff heat map: largest channel difference per pixel; black at most "
                                         "--fail " + number(fail) + ", viridis from there to " + number(double(top)) +
                                         ", white not finite");
  io::write_image_file(file, "png", out_spec, OIIO::TypeDesc::UINT8, rgb.data());
  file.commit(Overwrite::kReplace);
}

}  // namespace

std::string check_thresholds(const DiffThresholds& t) {
  const std::pair<const char*, double> values[] = {
      {"--fail", t.fail}, {"--warn", t.warn}, {"--hardfail", t.hard_fail}, {"--hardwarn", t.hard_warn}};
  for (const auto& [name, value] : values)
    if (!(value >= 0)) return std::string(name) + " must be at least 0, not " + number(value);
  const std::pair<const char*, double> percents[] = {{"--failpercent", t.fail_percent},
                                                     {"--warnpercent", t.warn_percent}};
  for (const auto& [name, value] : percents)
    if (!(value >= 0 && value <= 100)) return std::string(name) + " must be from 0 to 100, not " + number(value);
  return "";
}

const char* status_name(DiffStatus status) {
  switch (status) {
    case DiffStatus::kPass: return "PASS";
    case DiffStatus::kWarn: return "WARN";
    case DiffStatus::kFail: return "FAIL";
  }
  return "FAIL";
}

DiffStatus diff_verdict(const DiffThresholds& thresholds, double max_error, uint64_t over_warn, uint64_t over_fail,
                        uint64_t pixels) {
  return judge(thresholds, max_error, over_warn, over_fail, pixels).first;
}

DiffStatus DiffReport::status() const {
  DiffStatus worst = DiffStatus::kPass;
  for (const ImageDiff& p : pairs) worst = std::max(worst, p.status);
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
    DiffPair pair{a, a, b, name + ".diff.png"};
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
    DiffPair pair{name, take_a ? ia->second : "", take_b ? ib->second : "", name + ".diff.png"};
    pairs.push_back(std::move(pair));
    if (take_a) ++ia;
    if (take_b) ++ib;
  }
  if (pairs.empty()) throw InputError(a + ": no image files here or in " + b);
  return pairs;
}

ImageDiff diff_pair(const DiffPair& pair, const DiffOptions& options) {
  assert(!pair.a.empty() || !pair.b.empty());
  ImageDiff d;
  d.name = pair.name;
  d.a = pair.a;
  d.b = pair.b;
  d.status = DiffStatus::kFail;  // until compared
  if (pair.a.empty() || pair.b.empty()) {
    d.problem = pair.a.empty() ? "missing in A, only in B" : "missing in B, only in A";
    d.reason = d.problem;
    return d;
  }

  // Each file is opened and its declared size checked against --max-memory before its pixels are
  // allocated: a header of a few bytes may declare any size.
  FloatImage images[2];
  OIIO::ImageSpec declared[2];
  const std::string* paths[2] = {&pair.a, &pair.b};
  for (size_t i = 0; i < 2; ++i) {
    std::unique_ptr<OIIO::ImageInput> in;
    std::string why = open_image(*paths[i], in);
    if (why.empty()) {
      declared[i] = in->spec();
      why = over_budget(i, declared[0], declared[i], !options.heat_map_dir.empty(), options.max_memory);
    }
    try {
      if (why.empty()) why = read_pixels(*in, images[i]);
    } catch (const std::bad_alloc&) {
      images[0] = {}, images[1] = {};  // freed before the message is made
      why = out_of_memory_message();
    }
    if (!why.empty()) {
      d.unreadable = *paths[i];
      d.read_error = why;
      d.problem = "cannot read " + *paths[i] + ": " + why;
      d.reason = d.problem;
      return d;
    }
  }
  const OIIO::ImageBuf& a = images[0].buffer;
  const OIIO::ImageBuf& b = images[1].buffer;
  d.problem = mismatch(a.spec(), b.spec());
  if (!d.problem.empty()) {
    d.reason = d.problem;
    return d;
  }

  const DiffThresholds& t = options.thresholds;
  const OIIO::ImageBufAlgo::CompareResults cr =
      OIIO::ImageBufAlgo::compare(a, b, float(t.fail), float(t.warn), 0.0f, 0.0f, {}, 1);
  // `error` is also set whenever a pixel is over `fail` (OpenImageIO 2.4); a real error leaves a message.
  if (cr.error && a.has_error()) {
    d.problem = "OpenImageIO cannot compare them: " + oiio_message(a.geterror());
    d.reason = d.problem;
    return d;
  }
  d.compared = true;
  d.max_error = cr.maxerror;
  d.mean_error = cr.meanerror;
  d.rms_error = cr.rms_error;
  d.psnr = cr.PSNR;
  d.max_x = cr.maxx;
  d.max_y = cr.maxy;
  const std::vector<std::string>& names = a.spec().channelnames;
  d.max_channel = cr.maxc >= 0 && size_t(cr.maxc) < names.size() && !names[size_t(cr.maxc)].empty()
                      ? names[size_t(cr.maxc)]
                      : std::to_string(cr.maxc);
  d.pixels = uint64_t(a.spec().width) * uint64_t(a.spec().height) * uint64_t(a.spec().depth);
  d.over_warn = cr.nwarn;
  d.over_fail = cr.nfail;
  std::tie(d.status, d.reason) = judge(t, d.max_error, d.over_warn, d.over_fail, d.pixels);
  if (d.status == DiffStatus::kFail && !options.heat_map_dir.empty()) {
    d.heat_map = (fs::path(options.heat_map_dir) / pair.heat_map_name).string();
    write_heat_map(d.heat_map, images[0], images[1], t.fail);
  }
  return d;
}

DiffReport diff_images(const std::string& a, const std::string& b, const DiffOptions& options) {
  DiffReport report;
  report.a = a;
  report.b = b;
  report.thresholds = options.thresholds;
  for (const DiffPair& pair : pair_inputs(a, b)) {
    check_cancelled(options.cancel);
    report.pairs.push_back(diff_pair(pair, options));
  }
  return report;
}

}  // namespace dqskin
