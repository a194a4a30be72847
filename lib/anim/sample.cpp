// Keyframe sampling and the node hierarchy (glTF 2.0 §3.5.3, §3.11, Appendix C "Interpolation").
#include "dqskin/animation.hpp"

#include <algorithm>
#include <cmath>

namespace dqskin {
namespace {

// Appendix C's slerp: the shorter arc (sign of the dot), linear where the arc vanishes.
Quat<double> key_slerp(const Quat<double>& a, Quat<double> b, double t) {
  double d = glm::dot(a, b);
  if (d < 0) b = -b, d = -d;
  if (d > 1 - 1e-12) return glm::normalize(a * (1 - t) + b * t);
  const double angle = std::acos(d), s = std::sin(angle);
  return a * (std::sin((1 - t) * angle) / s) + b * (std::sin(t * angle) / s);
}

Quat<double> as_quat(const double* v) { return Quat<double>(v[3], v[0], v[1], v[2]); }

}  // namespace

std::vector<double> sample_channel(const Channel& ch, double time) {
  const size_t n = size_t(ch.components);
  const size_t keys = ch.times.size();
  const bool cubic = ch.interpolation == Interpolation::kCubicSpline;
  const size_t stride = cubic ? 3 * n : n;
  // Value of key k: for CUBICSPLINE the middle of (in-tangent, value, out-tangent).
  auto value = [&](size_t k, size_t c) { return double(ch.values[k * stride + (cubic ? n : 0) + c]); };
  std::vector<double> out(n);

  const double first = double(ch.times.front()), last = double(ch.times.back());
  size_t k = 0;
  double u = 0;  // position within [t_k, t_k+1]
  if (keys == 1 || time <= first) {
    k = 0;
  } else if (time >= last) {
    k = keys - 1;
  } else {
    k = size_t(std::upper_bound(ch.times.begin(), ch.times.end(), time,
                                [](double t, float key) { return t < double(key); }) - ch.times.begin()) - 1;
    u = (time - double(ch.times[k])) / (double(ch.times[k + 1]) - double(ch.times[k]));
  }

  if (u == 0 || ch.interpolation == Interpolation::kStep) {
    for (size_t c = 0; c < n; ++c) out[c] = value(k, c);
  } else if (ch.interpolation == Interpolation::kLinear) {
    if (ch.path == TargetPath::kRotation) {
      double a[4], b[4];
      for (size_t c = 0; c < 4; ++c) a[c] = value(k, c), b[c] = value(k + 1, c);
      const Quat<double> q = key_slerp(glm::normalize(as_quat(a)), glm::normalize(as_quat(b)), u);
      out = {q.x, q.y, q.z, q.w};
    } else {
      for (size_t c = 0; c < n; ++c) out[c] = value(k, c) * (1 - u) + value(k + 1, c) * u;
    }
  } else {
    // Hermite spline: p = (2u³−3u²+1) v_k + Δ(u³−2u²+u) b_k + (−2u³+3u²) v_k+1 + Δ(u³−u²) a_k+1, with
    // b_k the out-tangent of key k, a_k+1 the in-tangent of key k+1, Δ the key interval (Appendix C).
    const double delta = double(ch.times[k + 1]) - double(ch.times[k]);
    const double u2 = u * u, u3 = u2 * u;
    const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
    for (size_t c = 0; c < n; ++c) {
      const double out_tangent = double(ch.values[k * stride + 2 * n + c]);
      const double in_tangent = double(ch.values[(k + 1) * stride + c]);
      out[c] = h00 * value(k, c) + delta * h10 * out_tangent + h01 * value(k + 1, c) + delta * h11 * in_tangent;
    }
  }
  if (ch.path == TargetPath::kRotation) {
    const Quat<double> q = as_quat(out.data());
    const double length = glm::length(q);
    const Quat<double> unit = length > 0 ? q / length : Quat<double>(1, 0, 0, 0);
    out = {unit.x, unit.y, unit.z, unit.w};
  }
  return out;
}

Pose sample_pose(const Asset& asset, const Clip* clip, double time) {
  const size_t count = asset.nodes.size();
  std::vector<LocalTransform> local(count);
  Pose pose;
  pose.weights.resize(count);
  for (size_t i = 0; i < count; ++i) {
    local[i] = asset.nodes[i].local;
    const int mesh = asset.nodes[i].mesh;
    if (mesh < 0) continue;
    const std::vector<float>& w = asset.nodes[i].weights.empty() ? asset.meshes[size_t(mesh)].weights : asset.nodes[i].weights;
    pose.weights[i].assign(w.begin(), w.end());
  }

  if (clip) {
    for (const Channel& ch : clip->channels) {
      const std::vector<double> v = sample_channel(ch, time);
      LocalTransform& t = local[size_t(ch.node)];
      switch (ch.path) {
        case TargetPath::kTranslation: t.translation = {v[0], v[1], v[2]}; break;
        case TargetPath::kRotation: t.rotation = as_quat(v.data()); break;
        case TargetPath::kScale: t.scale = {v[0], v[1], v[2]}; break;
        case TargetPath::kWeights: pose.weights[size_t(ch.node)] = v; break;
      }
    }
  }

  // World matrices parent first. The loader guarantees a forest, so following parents terminates.
  pose.world.assign(count, Mat4<double>(1.0));
  std::vector<char> done(count, 0);
  std::vector<size_t> chain;
  for (size_t i = 0; i < count; ++i) {
    chain.clear();
    for (int n = int(i); n >= 0 && !done[size_t(n)]; n = asset.nodes[size_t(n)].parent) chain.push_back(size_t(n));
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const int parent = asset.nodes[*it].parent;
      const Mat4<double> m = local[*it].to_matrix();
      pose.world[*it] = parent >= 0 ? pose.world[size_t(parent)] * m : m;
      done[*it] = 1;
    }
  }
  // In place (docs/DESIGN.md §3.11): one rigid left-multiplication of every world matrix, which LBS and DQS
  // both carry through unchanged to the deformed vertices.
  if (clip && clip->in_place_root >= 0 && size_t(clip->in_place_root) < count) {
    pose.removed = ground_motion(pose.world[size_t(clip->in_place_root)]);
    const Mat4<double> to_place = ground_matrix_inverse(*pose.removed);
    for (Mat4<double>& w : pose.world) w = to_place * w;
  }
  return pose;
}

}  // namespace dqskin
