// A k-d tree over points in place (nearest_point.hpp). Equal points are kept once, with their smallest
// index, so that a skeleton whose joints all rest at one place (a chain without translations) makes no
// query visit every joint.
#include "nearest_point.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dqskin::lint {
namespace {

bool finite(const Vec3<double>& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

}  // namespace

NearestPoint::NearestPoint(const std::vector<Vec3<double>>& points) {
  first_is_nan_ = !points.empty() && (std::isnan(points[0].x) || std::isnan(points[0].y) || std::isnan(points[0].z));
  for (size_t i = 0; i < points.size(); ++i)
    if (finite(points[i])) items_.push_back({points[i], i});
  std::sort(items_.begin(), items_.end(), [](const Item& a, const Item& b) {
    if (a.p.x != b.p.x) return a.p.x < b.p.x;
    if (a.p.y != b.p.y) return a.p.y < b.p.y;
    if (a.p.z != b.p.z) return a.p.z < b.p.z;
    return a.index < b.index;
  });
  items_.erase(std::unique(items_.begin(), items_.end(), [](const Item& a, const Item& b) { return a.p == b.p; }),
               items_.end());
  build(0, items_.size(), 0);
}

void NearestPoint::build(size_t lo, size_t hi, int axis) {
  if (hi - lo < 2) return;
  const size_t mid = lo + (hi - lo) / 2;
  std::nth_element(items_.begin() + std::ptrdiff_t(lo), items_.begin() + std::ptrdiff_t(mid),
                   items_.begin() + std::ptrdiff_t(hi),
                   [axis](const Item& a, const Item& b) { return a.p[axis] < b.p[axis]; });
  build(lo, mid, (axis + 1) % 3);
  build(mid + 1, hi, (axis + 1) % 3);
}

void NearestPoint::search(size_t lo, size_t hi, int axis, const Vec3<double>& q, double& best,
                          size_t& best_index) const {
  if (lo >= hi) return;
  const size_t mid = lo + (hi - lo) / 2;
  const Item& item = items_[mid];
  const double d = glm::distance(item.p, q);
  if (d < best || (d == best && item.index < best_index)) best = d, best_index = item.index;
  const double off = q[axis] - item.p[axis];
  const int next = (axis + 1) % 3;
  const bool left_first = off < 0;
  search(left_first ? lo : mid + 1, left_first ? mid : hi, next, q, best, best_index);
  // Every point across the plane is at least |off| away. The margin keeps a point whose rounded distance
  // ties with (or, by an ulp, undercuts) the best from being passed over.
  if (std::abs(off) <= best * (1 + 1e-9) + std::numeric_limits<double>::min())
    search(left_first ? mid + 1 : lo, left_first ? hi : mid, next, q, best, best_index);
}

size_t NearestPoint::nearest(const Vec3<double>& q) const {
  if (first_is_nan_ || !finite(q) || items_.empty()) return 0;
  double best = std::numeric_limits<double>::infinity();
  size_t best_index = 0;
  search(0, items_.size(), 0, q, best, best_index);
  return best_index;
}

}  // namespace dqskin::lint
