#include "vat_format.hpp"

#include "dqskin/error.hpp"

#include <algorithm>
#include <bit>
#include <cassert>
#include <climits>
#include <optional>

namespace dqskin::texture {

namespace {

// The widest row dqskin and houdini use when no --max-size is given: 8192 (docs/DESIGN.md §4.7).
constexpr size_t kDefaultWrap = 8192;

size_t ceil_div(size_t a, size_t b) { return (a + b - 1) / b; }

size_t pad(size_t n, bool pot) { return pot ? std::bit_ceil(n) : n; }

// OpenVAT's wrapped layout (utils.calculate_optimal_vat_resolution): a power-of-two width from 64 up,
// rows of F frames per wrap, the height the next power of two; the smallest area whose sides stay within
// a 2:1 ratio, else the smallest area.
void openvat_wrapped(VatLayout& l, size_t limit, bool packed) {
  size_t best_area = SIZE_MAX;
  bool best_square = false;
  for (size_t w = 64; w <= limit; w *= 2) {
    const size_t wraps = ceil_div(l.vertices, w);
    const size_t block = l.frames * wraps;
    const size_t h = std::bit_ceil(packed ? 2 * block : block);
    if (h > limit) continue;
    const size_t area = w * h;
    const bool square = std::max(w, h) <= 2 * std::min(w, h);
    if ((square && !best_square) || (square == best_square && area < best_area)) {
      best_area = area;
      best_square = square;
      l.wrap = std::min(w, l.vertices);
      l.wraps = wraps;
      l.width = w;
      l.height = h;
    }
  }
}

}  // namespace

bool parse_vat_profile(const std::string& text, VatProfile& profile) {
  if (text == "dqskin") profile = VatProfile::kDqskin;
  else if (text == "openvat") profile = VatProfile::kOpenVat;
  else if (text == "houdini") profile = VatProfile::kHoudini;
  else return false;
  return true;
}

const char* to_string(VatProfile profile) {
  switch (profile) {
    case VatProfile::kDqskin: return "dqskin";
    case VatProfile::kOpenVat: return "openvat";
    case VatProfile::kHoudini: return "houdini";
  }
  return "?";
}

bool parse_normal_mode(const std::string& text, NormalMode& mode) {
  if (text == "none") mode = NormalMode::kNone;
  else if (text == "separate") mode = NormalMode::kSeparate;
  else if (text == "packed") mode = NormalMode::kPacked;
  else if (text == "oct8") mode = NormalMode::kOct8;
  else if (text == "oct16") mode = NormalMode::kOct16;
  else return false;
  return true;
}

const char* to_string(NormalMode mode) {
  switch (mode) {
    case NormalMode::kNone: return "none";
    case NormalMode::kSeparate: return "separate";
    case NormalMode::kPacked: return "packed";
    case NormalMode::kOct8: return "oct8";
    case NormalMode::kOct16: return "oct16";
  }
  return "?";
}

VatFormat default_format(VatProfile profile) {
  switch (profile) {
    case VatProfile::kDqskin: return {profile, TexelType::kFloat32, NormalMode::kSeparate};
    case VatProfile::kOpenVat: return {profile, TexelType::kHalf, NormalMode::kPacked};
    case VatProfile::kHoudini: return {profile, TexelType::kFloat32, NormalMode::kSeparate};
  }
  return {};
}

std::string unsupported_reason(const VatFormat& f) {
  const std::string name = to_string(f.profile);
  const bool oct = f.normals == NormalMode::kOct8 || f.normals == NormalMode::kOct16;
  if (oct && f.profile != VatProfile::kDqskin)
    return "octahedral normals (" + std::string(to_string(f.normals)) + ") are dqskin's; the " + name +
           " profile stores normals separate or packed";
  if (f.normals == NormalMode::kPacked && f.profile == VatProfile::kDqskin)
    return "the dqskin profile packs no normals; use separate, oct8 or oct16";
  if (f.profile == VatProfile::kHoudini && f.normals == NormalMode::kPacked && is_png(f.type))
    return "houdini's packed normals are a 10-bit code in the position alpha, which needs float or half";
  return {};
}

size_t VatLayout::page_frames(size_t page) const {
  return std::min(frames_per_page, frames - page_first_frame(page));
}

size_t VatLayout::page_height(size_t page) const {
  if (pages == 1 || page + 1 < pages) return height;
  const size_t used = page_frames(page) * wraps;
  return format.profile == VatProfile::kOpenVat ? height : (height == used_height ? used : std::bit_ceil(used));
}

TexelAt VatLayout::position(size_t v, size_t f) const {
  assert(v < vertices && f < frames);
  if (format.profile == VatProfile::kOpenVat) return {v % wrap, (v / wrap) * frames + f, 0};
  return {v % wrap, (f % frames_per_page) * wraps + v / wrap, f / frames_per_page};
}

TexelAt VatLayout::packed_normal(size_t v, size_t f) const {
  TexelAt t = position(v, f);
  if (format.profile == VatProfile::kOpenVat && format.normals == NormalMode::kPacked) t.y += height / 2;
  return t;
}

glm::dvec2 VatLayout::lookup_uv(size_t v) const {
  const TexelAt t = position(v, 0);
  switch (format.profile) {
    case VatProfile::kDqskin: return {double(t.x), double(t.y)};
    case VatProfile::kOpenVat: return {(double(t.x) + 0.5) / double(width), (double(t.y) + 0.5) / double(height)};
    case VatProfile::kHoudini:
      return {(double(t.x) + 0.5) / double(used_width), (double(t.y) + 0.5) / double(used_height)};
  }
  return {};
}

VatLayout::Rows VatLayout::frame_rows(size_t f) const {
  if (frame_major()) return {(f % frames_per_page) * wraps, wraps};
  return {0, height};
}

int VatLayout::position_channels() const {
  if (format.profile == VatProfile::kDqskin) return is_png(format.type) ? 3 : 4;
  if (format.profile == VatProfile::kHoudini && format.normals == NormalMode::kPacked) return 4;
  return 3;
}

namespace {

// The layout within `max_size` (0: none), or nullopt with `why` saying what does not fit.
std::optional<VatLayout> fit_layout(const VatFormat& format, size_t vertices, size_t frames, size_t max_size, bool pot,
                                    std::string& why) {
  VatLayout l;
  l.format = format;
  l.vertices = vertices;
  l.frames = frames;
  const size_t limit = max_size ? max_size : size_t(INT_MAX);
  const bool packed = format.profile == VatProfile::kOpenVat && format.normals == NormalMode::kPacked;
  if (format.profile == VatProfile::kOpenVat) {
    const size_t single_height = pad(packed ? 2 * frames : frames, pot);
    if (max_size == 0 || (vertices <= limit && single_height <= limit && pad(vertices, pot) <= limit)) {
      l.wrap = vertices;  // use_single_row
      l.wraps = 1;
      l.width = pad(vertices, pot);
      l.height = single_height;
    } else {
      openvat_wrapped(l, limit, packed);
      if (l.wrap == 0) {
        why = "OpenVAT's layout within " + std::to_string(max_size) + " texels a side";
        return std::nullopt;
      }
    }
    l.used_width = l.wrap;
    l.used_height = l.frames * l.wraps;
  } else {
    l.wrap = std::min(vertices, max_size ? max_size : kDefaultWrap);
    l.wraps = ceil_div(vertices, l.wrap);
    l.used_width = l.wrap;
    l.width = pad(l.used_width, pot);
    // The frames one image holds: all of them, unless it would be higher than the limit (dqskin pages;
    // the runtimes of the other profiles read one image).
    size_t fit = l.wraps > limit ? 0 : limit / l.wraps;
    if (pot)
      while (fit > 0 && pad(fit * l.wraps, true) > limit) --fit;
    if (fit == 0 || l.width > limit) {
      why = "an image within " + std::to_string(limit) + " texels a side: one frame takes " + std::to_string(l.wraps) +
            " rows of " + std::to_string(l.width) + " texels";
      return std::nullopt;
    }
    if (fit < frames && format.profile != VatProfile::kDqskin) {
      why = "an image " + std::to_string(limit) + " texels high (at most " + std::to_string(fit) +
            " frames do); lower --fps, or use the dqskin profile, which splits frames over pages";
      return std::nullopt;
    }
    l.frames_per_page = std::min(frames, fit);
    l.pages = ceil_div(frames, l.frames_per_page);
    l.used_height = l.frames_per_page * l.wraps;
    l.height = pad(l.used_height, pot);
  }
  if (l.frames_per_page == 0) l.frames_per_page = frames;
  if (l.height > size_t(INT_MAX) || l.width > size_t(INT_MAX) / 16) {
    why = "an image file (" + std::to_string(l.width) + " × " + std::to_string(l.height) + " texels)";
    return std::nullopt;
  }
  return l;
}

}  // namespace

VatLayout plan_vat_layout(const VatFormat& format, size_t vertices, size_t frames, size_t max_size, bool pot,
                          const std::string& what) {
  assert(vertices > 0 && frames > 0);
  std::string why;
  if (std::optional<VatLayout> l = fit_layout(format, vertices, frames, max_size, pot, why)) return *l;
  std::string message = what + ": " + std::to_string(vertices) + " vertices × " + std::to_string(frames) +
                        " frames do not fit " + why;
  // The nearest size that fits: the smallest larger --max-size with a layout. Every profile's layout only
  // gains room as the limit grows (wider rows, more rows, more candidate widths), so a bisection finds it.
  std::string ignored;
  if (max_size > 0 && max_size < kLargestMaxSize && fit_layout(format, vertices, frames, kLargestMaxSize, pot, ignored)) {
    size_t lo = max_size, hi = kLargestMaxSize;  // lo does not fit, hi does
    while (hi - lo > 1) {
      const size_t mid = lo + (hi - lo) / 2;
      (fit_layout(format, vertices, frames, mid, pot, ignored) ? hi : lo) = mid;
    }
    const VatLayout l = *fit_layout(format, vertices, frames, hi, pot, ignored);
    message += "; it needs " + std::to_string(l.width) + " × " + std::to_string(l.height) + " texels: --max-size " +
               std::to_string(hi) + " would fit";
  }
  throw InputError(message);
}

std::string page_file_name(const std::string& name, size_t page, size_t pages) {
  if (pages == 1) return name;
  const size_t dot = name.rfind('.');
  std::string out = name.substr(0, dot);
  out += "_page";
  out += std::to_string(page);
  if (dot != std::string::npos) out += name.substr(dot);
  return out;
}

}  // namespace dqskin::texture
