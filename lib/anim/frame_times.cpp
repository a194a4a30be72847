// Frame times of a bake (docs/DESIGN.md §2.2: frame i samples start + i / fps).
#include "dqskin/animation.hpp"

#include "dqskin/error.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>

namespace dqskin {
namespace {

[[noreturn]] void fail(const std::string& message) { throw InputError(message); }

constexpr int kMaxFrames = 10000000;  // 92 hours at 30 fps; far more is a mistake, not an animation

int parse_int(const std::string& text, const std::string& what) {
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno != 0 || v < 0 || v > 100000000)
    fail(what + " '" + text + "' is not a frame number");
  return int(v);
}

}  // namespace

void parse_frame_range(const std::string& text, FrameSpec& spec) {
  const size_t a = text.find(':');
  if (a == std::string::npos) fail("--frames '" + text + "' is not A:B or A:B:step");
  const size_t b = text.find(':', a + 1);
  spec.first = parse_int(text.substr(0, a), "--frames start");
  spec.last = parse_int(text.substr(a + 1, b == std::string::npos ? std::string::npos : b - a - 1), "--frames end");
  spec.step = b == std::string::npos ? 1 : parse_int(text.substr(b + 1), "--frames step");
  if (spec.step < 1) fail("--frames step must be at least 1");
  if (*spec.last < *spec.first) fail("--frames '" + text + "' ends before it starts");
}

std::vector<double> parse_times(const std::string& text) {
  std::vector<double> times;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    char* end = nullptr;
    const double t = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !std::isfinite(t) || t < 0)
      fail("--times item '" + item + "' is not a non-negative number of seconds");
    times.push_back(t);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return times;
}

std::vector<size_t> select_clips(const Asset& asset, const std::string& which) {
  std::vector<size_t> out;
  if (which == "all") {
    for (size_t i = 0; i < asset.clips.size(); ++i) out.push_back(i);
    return out;
  }
  for (size_t i = 0; i < asset.clips.size(); ++i)  // a name first: clips may be named "1"
    if (asset.clips[i].name == which) return {i};
  if (!which.empty() && which.find_first_not_of("0123456789") == std::string::npos && which.size() < 9) {
    const size_t index = size_t(std::stoul(which));
    if (index < asset.clips.size()) return {index};
  }
  std::string names;
  for (const Clip& c : asset.clips) names += (names.empty() ? "" : ", ") + c.name;
  fail("no animation '" + which + "' (the file has " + (names.empty() ? std::string("none") : names) + ")");
}

int grid_frame_count(const Clip& clip, const FrameSpec& spec) {
  if (!(spec.fps > 0) || !std::isfinite(spec.fps)) fail("--fps must be a positive number");
  const double start = spec.from_first_key ? clip.first_key : 0.0;
  // Frames whose time start + i/fps is at most the last key; the 1e-9 absorbs rounding of durations
  // that are whole frames (2 s at 30 fps is 61 frames, not 60).
  const double span = std::max(0.0, clip.last_key - start);
  const double frames = std::floor(span * spec.fps + 1e-9) + 1;  // +inf for --fps 1e300 and a clip of 1 s
  // Compared as doubles: converting one above the integers' range would be undefined.
  if (!(frames <= kMaxFrames)) {
    char text[96];
    std::snprintf(text, sizeof text, "the clip would have %.3g frames (%.6g s at %.6g fps), more than %d", frames, span,
                  spec.fps, kMaxFrames);
    fail(text);
  }
  return int(frames);
}

std::vector<double> frame_times(const Clip& clip, const FrameSpec& spec) {
  if (!spec.times.empty()) return spec.times;
  if (spec.keys) {
    std::set<float> keys;
    for (const Channel& ch : clip.channels) keys.insert(ch.times.begin(), ch.times.end());
    return std::vector<double>(keys.begin(), keys.end());
  }
  const int count = grid_frame_count(clip, spec);
  const double start = spec.from_first_key ? clip.first_key : 0.0;
  const int first = spec.first.value_or(0);
  const int last = spec.last.value_or(count - 1);
  if (first >= count || last >= count)
    fail("--frames asks for frame " + std::to_string(std::max(first, last)) + ", but the clip has frames 0.." +
         std::to_string(count - 1));
  std::vector<double> times;
  for (int i = first; i <= last; i += spec.step) times.push_back(start + double(i) / spec.fps);
  return times;
}

}  // namespace dqskin
