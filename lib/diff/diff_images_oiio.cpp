// `dqskin diff`'s image side through OpenImageIO: images compared by ImageBufAlgo::compare with idiff's
// thresholds, heat maps of failing pairs, and the EXR textures of the geometric diff read as points. Part of
// the image module (base/image_module.hpp).
#include "diff_image_files.hpp"
#include "diff_numbers.hpp"
#include "flip_heat_map.hpp"
#include "flip_pair.hpp"
#include "image_bands_oiio.hpp"
#include "memory_ledger.hpp"
#include "../base/byte_size.hpp"
#include "../base/file_kind.hpp"
#include "../base/image_file_oiio.hpp"
#include "../base/oiio_message.hpp"
#include "../base/saturating.hpp"
#include "../base/srgb.hpp"
#include "../base/stderr_capture.hpp"

#include "dqskin/atomic_file.hpp"
#include "dqskin/error.hpp"
#include "dqskin/job.hpp"
#include "dqskin/memory_ceiling.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <sys/stat.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <new>
#include <system_error>
#include <utility>

namespace dqskin {
namespace {

namespace fs = std::filesystem;
using diff_detail::band_bytes;
using diff_detail::judge;
using diff_detail::number;
using diff_detail::pixel_count;
using diff_detail::read_float_bands;

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

// Floats of a file's type that hold linear light (half, float, double), not display values.
bool is_linear(const OIIO::ImageSpec& declared) {
  const OIIO::TypeDesc::BASETYPE t = OIIO::TypeDesc::BASETYPE(declared.format.basetype);
  return t == OIIO::TypeDesc::HALF || t == OIIO::TypeDesc::FLOAT || t == OIIO::TypeDesc::DOUBLE;
}

// The memory reading image `i` (0: A, 1: B) of a pair takes: A is read first, then B beside it, then the
// measuring (FLIP's) and the heat map (when one may be written) beside both. `a` and `b` are what the
// files declare; b is unused for A.
uint64_t bytes_needed(size_t i, const OIIO::ImageSpec& a, const OIIO::ImageSpec& b, const DiffOptions& options) {
  using saturating::add;
  using saturating::mul;
  const bool heat_map = !options.heat_map_dir.empty() || !options.page_dir.empty();
  const OIIO::ImageSpec& s = i == 0 ? a : b;
  const uint64_t other = i == 0 ? 0 : diff_detail::float_bytes(a);
  uint64_t beside = diff_detail::band_bytes(s);  // the most held beside the images: reading, measuring or the heat map
  if (i == 1 && options.metric == DiffMetric::kFlip) {
    const size_t w = size_t(std::max(a.width, 0)), h = size_t(std::max(a.height, 0)) * size_t(std::max(a.depth, 1));
    beside = std::max(beside, add(diff_detail::flip_pair_bytes(w, h, options, is_linear(a)),
                                  heat_map ? diff_detail::flip_heat_map_bytes(w, h) : 0));
  } else if (i == 1 && heat_map) {
    beside = std::max(beside, mul(diff_detail::pixel_count(a), kHeatMapBytesPerPixel));
  }
  return add(add(other, diff_detail::float_bytes(s)), beside);
}

// Why reading image `i` (0: A, 1: B) needs more than --max-memory (see bytes_needed), or "".
std::string over_budget(size_t i, const OIIO::ImageSpec& a, const OIIO::ImageSpec& b, const DiffOptions& options) {
  const OIIO::ImageSpec& s = i == 0 ? a : b;
  const uint64_t other = i == 0 ? 0 : diff_detail::float_bytes(a);
  const bool heat_map = !options.heat_map_dir.empty() || !options.page_dir.empty();
  const uint64_t need = bytes_needed(i, a, b, options);
  if (need <= options.max_memory) return "";
  std::string size = std::to_string(s.width) + "x" + std::to_string(s.height);
  if (s.depth > 1) size.append("x").append(std::to_string(s.depth));
  size += " pixels of " + std::to_string(s.nchannels) + (s.nchannels == 1 ? " channel" : " channels");
  const char* measuring = options.metric == DiffMetric::kFlip ? (heat_map ? ", FLIP and a heat map" : " and FLIP")
                                                              : (heat_map ? " and a heat map" : "");
  return "comparing it needs about " + byte_size(need) + " (its " + size + " as float" +
         (i == 0 ? std::string() : ", beside " + byte_size(other) + " for the other image" + measuring) +
         "), more than --max-memory " + byte_size(options.max_memory);
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

// The pixels `mask` leaves out of an image laid out as `spec` (1 where left out), or none when it leaves
// none. Throws InputError naming the mask image when it cannot be read or has another size.
std::vector<uint8_t> excluded_pixels(const DiffMask& mask, const OIIO::ImageSpec& spec) {
  const size_t width = size_t(spec.width), height = size_t(spec.height) * size_t(spec.depth);
  std::vector<uint8_t> excluded(width * height, 0);
  for (const std::string& image : mask.images) {
    std::unique_ptr<OIIO::ImageInput> in;
    std::string why = open_image(image, in);
    if (!why.empty()) throw InputError(image + ": cannot read the mask: " + why);
    const OIIO::ImageSpec& m = in->spec();
    if (m.width != spec.width || m.height != spec.height || m.depth != spec.depth)
      throw InputError(image + ": the mask is " + window_text(m) + ", the images " + window_text(spec));
    FloatImage pixels;
    why = read_pixels(*in, pixels);
    if (!why.empty()) throw InputError(image + ": cannot read the mask: " + why);
    const size_t channels = size_t(m.nchannels);
    for (size_t i = 0; i < excluded.size(); ++i) excluded[i] |= pixels.pixels[i * channels] >= 0.5f;
  }
  for (const PixelRect& r : mask.rects) {
    const long x0 = std::max(0L, long(r.x)), y0 = std::max(0L, long(r.y));
    const long x1 = std::min(long(width), long(r.x) + r.width), y1 = std::min(long(height), long(r.y) + r.height);
    for (long y = y0; y < y1; ++y)
      for (long x = x0; x < x1; ++x) excluded[size_t(y) * width + size_t(x)] = 1;
  }
  if (std::find(excluded.begin(), excluded.end(), 1) == excluded.end()) return {};
  return excluded;
}

// Left-out pixels take A's values in B: they differ nowhere, so compare and FLIP count nothing there and
// no difference under the mask spreads through FLIP's filters. Returns how many pixels were left out.
uint64_t apply_mask(const std::vector<uint8_t>& excluded, const FloatImage& a, FloatImage& b, size_t channels) {
  uint64_t count = 0;
  for (size_t i = 0; i < excluded.size(); ++i) {
    if (!excluded[i]) continue;
    std::copy_n(a.pixels.get() + i * channels, channels, b.pixels.get() + i * channels);
    ++count;
  }
  return count;
}

// An image as the page shows it: an 8-bit sRGB PNG of its first three channels (one or two: the first as
// grey), linear files encoded, display values as they are.
void write_preview(const std::string& path, const FloatImage& image, bool linear) {
  const OIIO::ImageSpec& spec = image.buffer.spec();
  const size_t count = size_t(spec.width) * size_t(spec.height) * size_t(spec.depth), channels = size_t(spec.nchannels);
  std::vector<uint8_t> rgb(count * 3);
  for (size_t i = 0; i < count; ++i)
    for (size_t c = 0; c < 3; ++c) {
      const float v = image.pixels[i * channels + (channels >= 3 ? c : 0)];
      const float shown = std::isnan(v) ? 0.0f : v;
      rgb[3 * i + c] = linear ? io::srgb8(shown) : io::unorm8(shown);
    }
  std::error_code error;
  fs::create_directories(fs::path(path).parent_path(), error);
  if (error) throw OutputError(fs::path(path).parent_path().string() + ": cannot create folder: " + error.message());
  AtomicFile file(path);
  OIIO::ImageSpec out(spec.width, spec.height * spec.depth, 3, OIIO::TypeDesc::UINT8);
  out.attribute("oiio:ColorSpace", "sRGB");
  io::write_image_file(file, "png", out, OIIO::TypeDesc::UINT8, rgb.data());
  file.commit(Overwrite::kReplace);
}

class OiioDiffImageFiles final : public diff_detail::DiffImageFiles {
public:
  ImageDiff diff_pair(const DiffPair& pair, const DiffOptions& options, diff_detail::MemoryLedger* ledger) const override {
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
      // allocated: a header of a few bytes may declare any size. Both headers come first, so that the pair
      // holds what it needs in the ledger of pairs compared at once before any pixel is read; a problem
      // is still reported as reading one file after the other would meet it (A's, then B's).
      FloatImage images[2];
      OIIO::ImageSpec declared[2];
      std::unique_ptr<OIIO::ImageInput> in[2];
      std::string why[2];
      const std::string* paths[2] = {&pair.a, &pair.b};
      size_t opened = 0;
      for (; opened < 2; ++opened) {
        why[opened] = open_image(*paths[opened], in[opened]);
        if (why[opened].empty()) {
          declared[opened] = in[opened]->spec();
          why[opened] = over_budget(opened, declared[0], declared[opened], options);
        }
        // A reader holds buffers of its own (OpenEXR's, as wide as a row): one file open at a time, each
        // opened again when its pixels are read.
        in[opened].reset();
        if (!why[opened].empty()) break;
      }
      diff_detail::MemoryLedger::Reservation held;
      if (ledger && opened > 0) {
        held = ledger->reserve(bytes_needed(opened - 1, declared[0], declared[opened - 1], options));
        check_cancelled(options.cancel);  // it may have waited for other pairs
      }
      for (size_t i = 0; i < 2; ++i) {
        try {
          if (why[i].empty()) {
            why[i] = open_image(*paths[i], in[i]);
            if (why[i].empty() && !mismatch(in[i]->spec(), declared[i]).empty()) why[i] = "the file changed while it was compared";
          }
          if (why[i].empty()) why[i] = read_pixels(*in[i], images[i]);
          in[i].reset();  // its buffers freed before the next file is read
        } catch (const std::bad_alloc&) {
          images[0] = {}, images[1] = {};  // freed before the message is made
          why[i] = out_of_memory_message();
        }
        if (!why[i].empty()) {
          d.unreadable = *paths[i];
          d.read_error = why[i];
          d.problem = "cannot read " + *paths[i] + ": " + why[i];
          d.reason = d.problem;
          return d;
        }
      }
      const OIIO::ImageBuf& a = images[0].buffer;
      const OIIO::ImageBuf& b = images[1].buffer;
      if (!options.page_dir.empty()) {
        // Before the mask, which changes B: the page shows the images as they are.
        d.page_a = pair.page_stem + ".a.png";
        d.page_b = pair.page_stem + ".b.png";
        write_preview((fs::path(options.page_dir) / d.page_a).string(), images[0], is_linear(declared[0]));
        write_preview((fs::path(options.page_dir) / d.page_b).string(), images[1], is_linear(declared[1]));
      }
      d.problem = mismatch(a.spec(), b.spec());
      if (!d.problem.empty()) {
        d.reason = d.problem;
        return d;
      }

      const std::vector<uint8_t> excluded = options.mask.empty() ? std::vector<uint8_t>() : excluded_pixels(options.mask, a.spec());
      d.masked = apply_mask(excluded, images[0], images[1], size_t(a.spec().nchannels));
      const DiffThresholds& t = options.thresholds;
      if (options.metric == DiffMetric::kFlip) return flip(pair, declared[0], declared[1], images, excluded, options, d);
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
      if (d.masked > 0) {
        // The figures over the pixels compared: left-out ones differ by 0, so the sums stand and the
        // count shrinks (PSNR as compare makes it, 20 log10(1 / RMS)).
        const double all = double(d.pixels), kept = double(d.pixels - d.masked);
        d.pixels -= d.masked;
        d.mean_error = kept > 0 ? d.mean_error * all / kept : 0;
        d.rms_error = kept > 0 ? std::sqrt(d.rms_error * d.rms_error * all / kept) : 0;
        d.psnr = d.rms_error > 0 ? 20 * std::log10(1 / d.rms_error) : std::numeric_limits<double>::infinity();
      }
      std::tie(d.status, d.reason) = judge(t, d.max_error, d.over_warn, d.over_fail, d.pixels, d.mean_error);
      if (d.status == DiffStatus::kFail && !options.heat_map_dir.empty()) {
        d.heat_map = (fs::path(options.heat_map_dir) / pair.heat_map_name).string();
        write_heat_map(d.heat_map, images[0], images[1], t.fail);
      }
      if (!options.page_dir.empty() && d.max_error != 0) {
        d.page_difference = pair.page_stem + ".diff.png";
        write_heat_map((fs::path(options.page_dir) / d.page_difference).string(), images[0], images[1], t.fail);
      }
      return d;
  }

  // The pair of same-sized images measured by FLIP (flip_pair.hpp), judged, and its heat map written.
  static ImageDiff flip(const DiffPair& pair, const OIIO::ImageSpec& declared, const OIIO::ImageSpec& declared_b,
                        const FloatImage (&images)[2],
                        const std::vector<uint8_t>& excluded, const DiffOptions& options, ImageDiff& d) {
    const OIIO::ImageSpec& spec = images[0].buffer.spec();
    if (spec.depth != 1) {
      d.problem = "FLIP compares flat images, not volumes (depth " + std::to_string(spec.depth) + ")";
      d.reason = d.problem;
      return d;
    }
    if (is_linear(declared) != is_linear(declared_b)) {
      d.problem = std::string("FLIP compares like with like: A holds ") + (is_linear(declared) ? "linear light (float)" : "display values (integer)") +
                  ", B " + (is_linear(declared_b) ? "linear light (float)" : "display values (integer)");
      d.reason = d.problem;
      return d;
    }
    const diff_detail::PixelLayout layout{size_t(spec.width), size_t(spec.height), size_t(spec.nchannels), is_linear(declared)};
    const std::vector<double> errors =
        diff_detail::flip_pair(images[0].pixels.get(), images[1].pixels.get(), layout, excluded, options, d);
    d.compared = true;
    std::tie(d.status, d.reason) = judge(options.thresholds, d.max_error, d.over_warn, d.over_fail, d.pixels, d.mean_error);
    if (d.status == DiffStatus::kFail && !options.heat_map_dir.empty()) {
      d.heat_map = (fs::path(options.heat_map_dir) / pair.heat_map_name).string();
      diff_detail::write_flip_heat_map(d.heat_map, errors, layout.width, layout.height);
    }
    if (!options.page_dir.empty() && d.max_error != 0) {
      d.page_difference = pair.page_stem + ".diff.png";
      diff_detail::write_flip_heat_map((fs::path(options.page_dir) / d.page_difference).string(), errors, layout.width,
                                       layout.height);
    }
    return d;
  }

  // An EXR texture: each texel's first three channels (a VAT's position, a bone texture's first values),
  // read a band of rows at a time.
  diff_detail::BakedPoints read_exr(const std::string& path) const override {
    using diff_detail::BakedPoints;
      auto in = OIIO::ImageInput::open(path);
      if (!in) throw InputError(oiio_message(OIIO::geterror()));
      const OIIO::ImageSpec& spec = in->spec();
      const size_t channels = size_t(std::max(0, spec.nchannels));
      if (channels < 1) throw InputError("texture has no channels");
      if (spec.deep) throw InputError("deep (multi-sample) textures are not compared");
      BakedPoints points;
      points.positions.assign(size_t(pixel_count(spec)), glm::vec3(0.0f));
      const std::string why = read_float_bands(*in, [&points, channels](const float* values, size_t first, size_t count) {
        for (size_t t = 0; t < count; ++t)
          for (size_t c = 0; c < std::min<size_t>(channels, 3); ++c) points.positions[first + t][int(c)] = values[t * channels + c];
      });
      if (!why.empty()) throw InputError(oiio_message(why));
      return points;
  }

  diff_detail::DeclaredSize exr_declared_size(const std::string& path) const override {
        auto in = OIIO::ImageInput::open(path);
      if (!in) {
        OIIO::geterror();  // forgotten: read_baked_file says why
        return {};
      }
      const OIIO::ImageSpec& spec = in->spec();
      const uint64_t texels = pixel_count(spec);
      return {saturating::add(saturating::mul(texels, sizeof(glm::vec3)), band_bytes(spec)), texels,
              std::to_string(spec.width) + "x" + std::to_string(spec.height) + " texels"};
  }
};

}  // namespace
}  // namespace dqskin

// The entry point base/image_module.hpp looks up: the address of this folder's DiffImageFiles.
extern "C" const void* dqskin_diff_image_files() {
  static const dqskin::OiioDiffImageFiles files;
  return static_cast<const dqskin::diff_detail::DiffImageFiles*>(&files);
}
