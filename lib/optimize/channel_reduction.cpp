#include "channel_reduction.hpp"

#include "../anim/keyframe_reduction.hpp"

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

ReducedChannel reduce_channel(const Channel& channel, const NodeLevers& levers, double budget, const float* rest,
                              bool may_drop, unsigned threads) {
  ReducedChannel out;
  out.channel = channel;
  const size_t keys = channel.times.size(), n = size_t(std::max(0, channel.components));
  if (keys == 0 || n == 0 || channel.interpolation == Interpolation::kCubicSpline) return out;
  const ChannelError error(channel, levers);
  const float* values = channel.values.data();
  auto key = [&](size_t k) { return values + k * n; };

  double from_first = 0, from_rest = 0;
  for (size_t k = 0; k < keys; ++k) {
    from_first = std::max(from_first, error(key(k), key(0)));
    if (rest) from_rest = std::max(from_rest, error(key(k), rest));
  }
  if (rest && may_drop && from_rest <= budget) {
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
    kept = reduce_keyframes(keys, budget, [&](size_t i, size_t a, size_t b) {
      const double u = (double(channel.times[i]) - double(channel.times[a])) /
                       (double(channel.times[b]) - double(channel.times[a]));
      std::vector<double> interpolated(std::max<size_t>(n, 4));
      std::vector<float> value(n);
      if (channel.path == TargetPath::kRotation) {
        slerp(key(a), key(b), u, interpolated.data());
      } else {
        for (size_t c = 0; c < n; ++c) interpolated[c] = (1 - u) * double(key(a)[c]) + u * double(key(b)[c]);
      }
      for (size_t c = 0; c < n; ++c) value[c] = float(interpolated[c]);
      return error(key(i), value.data());
    }, threads);
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

}  // namespace dqskin::optimize_detail
