#include "channel_reduction.hpp"

#include "../anim/keyframe_reduction.hpp"

#include "dqskin/animation.hpp"

#include <algorithm>
#include <cmath>

namespace dqskin::optimize_detail {
namespace {

// The unit quaternion between a and b at u by the shortest-path slerp (glTF 2.0 Appendix C), as doubles.
void slerp(const float* a, const float* b, double u, double* out) {
  double d = 0;
  for (int i = 0; i < 4; ++i) d += double(a[i]) * double(b[i]);
  const double sign = d < 0 ? -1.0 : 1.0;
  d = std::abs(d);
  double wa = 1 - u, wb = u;
  if (d < 1 - 1e-9) {
    const double angle = std::acos(std::min(1.0, d)), s = std::sin(angle);
    wa = std::sin((1 - u) * angle) / s;
    wb = std::sin(u * angle) / s;
  }
  double length = 0;
  for (int i = 0; i < 4; ++i) {
    out[i] = wa * double(a[i]) + sign * wb * double(b[i]);
    length += out[i] * out[i];
  }
  length = std::sqrt(length);
  for (int i = 0; i < 4; ++i) out[i] /= length > 0 ? length : 1;
}

}  // namespace

ChannelError::ChannelError(const Channel& channel, const NodeLevers& levers) : path_(channel.path), lever_(0) {
  switch (channel.path) {
    case TargetPath::kRotation: lever_ = levers.rotation; break;
    case TargetPath::kTranslation: lever_ = levers.translation; break;
    case TargetPath::kScale: lever_ = levers.scale; break;
    case TargetPath::kWeights: lever_ = 1; break;
  }
  if (!levers.moves_vertices) lever_ = 0;
  if (channel.path == TargetPath::kWeights) {
    weight_levers_.assign(size_t(std::max(0, channel.components)), 0.0);
    for (size_t t = 0; t < weight_levers_.size() && t < levers.weights.size(); ++t) weight_levers_[t] = levers.weights[t];
  }
}

double ChannelError::operator()(const float* a, const float* b) const {
  switch (path_) {
    case TargetPath::kRotation: {
      // The rotation between two unit quaternions, 4·asin(|a − b| / 2) with b on a's side: stable for the
      // small angles that matter here, where 2·acos(a · b) loses half its digits.
      double da = 0, db = 0, dot = 0;
      for (int i = 0; i < 4; ++i) {
        da += double(a[i]) * double(a[i]);
        db += double(b[i]) * double(b[i]);
        dot += double(a[i]) * double(b[i]);
      }
      const double la = std::sqrt(std::max(da, 1e-300)), lb = std::sqrt(std::max(db, 1e-300)) * (dot < 0 ? -1 : 1);
      double chord = 0;
      for (int i = 0; i < 4; ++i) {
        const double d = double(a[i]) / la - double(b[i]) / lb;
        chord += d * d;
      }
      return 4 * std::asin(std::min(1.0, std::sqrt(chord) / 2)) * lever_;
    }
    case TargetPath::kTranslation: {
      double s = 0;
      for (int i = 0; i < 3; ++i) s += (double(a[i]) - double(b[i])) * (double(a[i]) - double(b[i]));
      return std::sqrt(s) * lever_;
    }
    case TargetPath::kScale: {
      double m = 0;
      for (int i = 0; i < 3; ++i) m = std::max(m, std::abs(double(a[i]) - double(b[i])));
      return m * lever_;
    }
    case TargetPath::kWeights: {
      // Targets add up: a vertex may move by every target's share at once.
      double s = 0;
      for (size_t t = 0; t < weight_levers_.size(); ++t) s += std::abs(double(a[t]) - double(b[t])) * weight_levers_[t];
      return s;
    }
  }
  return 0;
}

namespace {

// The keys a viewer needs of a LINEAR channel (times and values of n components a key), by the
// Douglas–Peucker split of reduce_keyframes, judged through `error`.
std::vector<size_t> linear_keys(const Channel& channel, const ChannelError& error, double budget, unsigned threads) {
  const size_t n = size_t(channel.components);
  const float* values = channel.values.data();
  return reduce_keyframes(channel.times.size(), budget, [&](size_t i, size_t a, size_t b) {
    const double u = (double(channel.times[i]) - double(channel.times[a])) /
                     (double(channel.times[b]) - double(channel.times[a]));
    std::vector<double> interpolated(std::max<size_t>(n, 4));
    std::vector<float> value(n);
    if (channel.path == TargetPath::kRotation) {
      slerp(values + a * n, values + b * n, u, interpolated.data());
    } else {
      for (size_t c = 0; c < n; ++c) interpolated[c] = (1 - u) * double(values[a * n + c]) + u * double(values[b * n + c]);
    }
    for (size_t c = 0; c < n; ++c) value[c] = float(interpolated[c]);
    return error(values + i * n, value.data());
  }, threads);
}

// The keys of a LINEAR channel as STEP, exact to the budget at every time: a run holds its first value
// h until the next run starts, while the linear curve goes through the run's keys and on to the next
// run's first; the distance of a linear segment to a fixed value is largest at one of its ends, so every
// key of the run and the next run's first within the budget of h keeps all of it within. Each run
// extends as far as it can (it ends at the key before the first one out of reach, which starts the
// next). Empty when one segment alone changes by more than the budget.
std::vector<size_t> step_keys(const Channel& channel, const ChannelError& error, double budget) {
  const size_t n = size_t(channel.components), keys = channel.times.size();
  auto key = [&](size_t k) { return channel.values.data() + k * n; };
  std::vector<size_t> starts = {0};
  for (size_t k = 1; k < keys; ++k) {
    if (error(key(k), key(starts.back())) <= budget) continue;
    if (k - 1 == starts.back() || error(key(k), key(k - 1)) > budget) return {};
    starts.push_back(k - 1);
  }
  return starts;
}

// A LINEAR or STEP channel reduced (see reduce_channel).
ReducedChannel reduce_piecewise(const Channel& channel, const ChannelError& error, double budget, const float* rest,
                                ReductionLevers allowed, unsigned threads) {
  ReducedChannel out;
  out.channel = channel;
  const size_t keys = channel.times.size(), n = size_t(channel.components);
  auto key = [&](size_t k) { return channel.values.data() + k * n; };

  double from_first = 0, from_rest = 0;
  for (size_t k = 0; k < keys; ++k) {
    from_first = std::max(from_first, error(key(k), key(0)));
    if (rest) from_rest = std::max(from_rest, error(key(k), rest));
  }
  if (rest && allowed.drop && from_rest <= budget) {
    out.dropped = true;
    return out;
  }
  std::vector<size_t> kept;
  if (from_first <= budget) {
    kept = {0};
  } else if (channel.interpolation == Interpolation::kStep) {
    for (size_t k = 0; k < keys; ++k)
      if (k == 0 || !std::equal(key(k), key(k) + n, key(kept.back()))) kept.push_back(k);
  } else {
    kept = linear_keys(channel, error, budget, threads);
    if (allowed.interpolation) {
      const std::vector<size_t> steps = step_keys(channel, error, budget);
      if (!steps.empty() && steps.size() < kept.size()) {
        kept = steps;
        out.channel.interpolation = Interpolation::kStep;
      }
    }
  }
  if (kept.size() == keys) return out;
  out.channel.times.clear();
  out.channel.values.clear();
  for (size_t k : kept) {
    out.channel.times.push_back(channel.times[k]);
    out.channel.values.insert(out.channel.values.end(), key(k), key(k) + n);
  }
  return out;
}

constexpr int kCubicSamples = 8;   // a CUBICSPLINE segment's samples for its linear equivalent
constexpr int kCubicChecks = 32;   // the points of each segment where the equivalent is checked

// Whether `reduced` stays within `budget` of the CUBICSPLINE `channel` at kCubicChecks points of each
// of its segments (the dropped channel as the node's rest value).
bool follows_curve(const Channel& channel, const ReducedChannel& reduced, const float* rest, const ChannelError& error,
                   double budget) {
  const size_t n = size_t(channel.components);
  std::vector<float> a(n), b(n);
  for (size_t k = 0; k + 1 < channel.times.size(); ++k)
    for (int j = 0; j < kCubicChecks; ++j) {
      const double t = double(channel.times[k]) + (double(channel.times[k + 1]) - double(channel.times[k])) * j / kCubicChecks;
      const std::vector<double> curve = sample_channel(channel, t);
      for (size_t c = 0; c < n; ++c) a[c] = float(curve[c]);
      if (reduced.dropped) {
        std::copy(rest, rest + n, b.begin());
      } else {
        const std::vector<double> line = sample_channel(reduced.channel, t);
        for (size_t c = 0; c < n; ++c) b[c] = float(line[c]);
      }
      if (error(a.data(), b.data()) > budget) return false;
    }
  return true;
}

// Bytes of a channel's keys as floats: its time and one value (three for CUBICSPLINE).
size_t float_bytes(const Channel& channel) {
  const size_t per_key = size_t(channel.components) * (channel.interpolation == Interpolation::kCubicSpline ? 3 : 1);
  return channel.times.size() * 4 * (1 + per_key);
}

}  // namespace

Channel sampled_at(const Channel& channel, const std::vector<float>& times) {
  Channel out = channel;
  out.interpolation = Interpolation::kLinear;
  out.times = times;
  out.values.clear();
  for (float t : times)
    for (double v : sample_channel(channel, double(t))) out.values.push_back(float(v));
  return out;
}

std::vector<float> cubic_sample_times(const Channel& channel) {
  std::vector<float> times;
  auto add = [&](float t) {
    if (times.empty() || t > times.back()) times.push_back(t);  // float time resolution may merge two
  };
  for (size_t k = 0; k + 1 < channel.times.size(); ++k) {
    const double a = double(channel.times[k]), b = double(channel.times[k + 1]);
    for (int j = 0; j < kCubicSamples; ++j) add(float(a + (b - a) * j / kCubicSamples));
  }
  if (!channel.times.empty()) add(channel.times.back());
  return times;
}

ReducedChannel reduce_channel(const Channel& channel, const NodeLevers& levers, double budget, const float* rest,
                              ReductionLevers allowed, unsigned threads) {
  const size_t keys = channel.times.size(), n = size_t(std::max(0, channel.components));
  const ChannelError error(channel, levers);
  if (keys == 0 || n == 0) return ReducedChannel{false, channel};
  if (channel.interpolation != Interpolation::kCubicSpline)
    return reduce_piecewise(channel, error, budget, rest, allowed, threads);
  if (!allowed.interpolation || keys < 2) return ReducedChannel{false, channel};
  ReducedChannel linear = reduce_piecewise(sampled_at(channel, cubic_sample_times(channel)), error, budget / 2, rest, allowed, threads);
  const bool smaller = linear.dropped || float_bytes(linear.channel) < float_bytes(channel);
  if (!smaller || !follows_curve(channel, linear, rest, error, budget)) return ReducedChannel{false, channel};
  return linear;
}

}  // namespace dqskin::optimize_detail
