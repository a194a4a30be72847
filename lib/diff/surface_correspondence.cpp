#include "surface_correspondence.hpp"

#include <glm/geometric.hpp>
#include <nanoflann.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace dqskin::diff_detail {

glm::dvec3 closest_point_weights(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  // The regions are tested in Ericson's order; each test uses only dot products, so a thin triangle
  // falls into a vertex or edge region instead of dividing by its tiny area.
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = 1 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1 - v - w, v, w};
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();


// Points this close to the closest (as a fraction of the surface's diagonal) are ties, decided by normals:
// a vertex on a crease or seam is as close to the faces on either side, and positions quantized to 14
// bits (KHR_mesh_quantization, gltfpack's default) move by up to 3e-5 of the extent per axis, enough to
// put the other side of a thin part, or a coincident inner surface, nearest.
constexpr double kTieWindow = 1e-4;

// nanoflann's dataset interface over the sample points.
struct SampleCloud {
  std::vector<glm::dvec3> points;
  size_t kdtree_get_point_count() const { return points.size(); }
  double kdtree_get_pt(size_t i, size_t dim) const { return points[i][int(dim)]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const { return false; }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, SampleCloud>, SampleCloud, 3, uint32_t>;

// Samples of a triangle with edges split into n: a + (i/n)(b − a) + (j/n)(c − a), i + j ≤ n.
size_t sample_count(size_t n) { return (n + 1) * (n + 2) / 2; }

}  // namespace

struct SurfaceIndex::Impl {
  std::vector<glm::dvec3> positions, normals;
  double tie = 0;                   // distances closer than this to the best are ties
  std::vector<uint32_t> triangles;  // non-degenerate ones, three vertices each
  SampleCloud cloud;
  std::vector<uint32_t> sample_triangle;  // which triangle each sample lies on
  double reach = 0;                        // h: no point of the surface is farther from its nearest sample
  std::unique_ptr<Tree> tree;

  glm::dvec3 corner(uint32_t t, int k) const { return positions[triangles[3 * size_t(t) + size_t(k)]]; }

  // The closest point of triangle t to p, and its squared distance.
  std::pair<glm::dvec3, double> closest_on(uint32_t t, const glm::dvec3& p) const {
    const glm::dvec3 a = corner(t, 0), b = corner(t, 1), c = corner(t, 2);
    const glm::dvec3 w = closest_point_weights(p, a, b, c);
    const glm::dvec3 d = w.x * a + w.y * b + w.z * c - p;
    return {w, glm::dot(d, d)};
  }
};

SurfaceIndex::SurfaceIndex(std::span<const glm::dvec3> positions, std::span<const uint32_t> triangles,
                           std::span<const glm::dvec3> normals)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.positions.assign(positions.begin(), positions.end());
  if (normals.size() == positions.size()) m.normals.assign(normals.begin(), normals.end());
  glm::dvec3 low(kInf), high(-kInf);
  for (const glm::dvec3& p : m.positions) low = glm::min(low, p), high = glm::max(high, p);
  m.tie = m.positions.empty() ? 0 : kTieWindow * glm::length(high - low);
  // Triangles without area have no face of their own: their edges belong to their neighbours, and the
  // face region of the closest-point test would divide by zero.
  std::vector<double> longest;
  for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const glm::dvec3 a = m.positions[triangles[t]], b = m.positions[triangles[t + 1]], c = m.positions[triangles[t + 2]];
    if (glm::length(glm::cross(b - a, c - a)) == 0) continue;
    m.triangles.insert(m.triangles.end(), triangles.begin() + std::ptrdiff_t(t), triangles.begin() + std::ptrdiff_t(t) + 3);
    longest.push_back(std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)}));
  }
  const size_t count = longest.size();
  if (count == 0) return;

  // The grid spacing: the median longest edge, doubled until the samples number at most 16 per triangle,
  // so that one huge triangle among small ones cannot make the index large.
  std::vector<double> sorted = longest;
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(count / 2), sorted.end());
  double spacing = std::max(sorted[count / 2], std::numeric_limits<double>::min());
  auto splits = [&](size_t t) { return size_t(std::max(1.0, std::min(4096.0, std::ceil(longest[t] / spacing)))); };
  for (;;) {
    size_t total = 0;
    for (size_t t = 0; t < count; ++t) total += sample_count(splits(t));
    if (total <= 16 * count) break;
    spacing *= 2;
  }

  for (size_t t = 0; t < count; ++t) {
    const size_t n = splits(t);
    const glm::dvec3 a = m.corner(uint32_t(t), 0), ab = m.corner(uint32_t(t), 1) - a, ac = m.corner(uint32_t(t), 2) - a;
    for (size_t i = 0; i <= n; ++i)
      for (size_t j = 0; i + j <= n; ++j) {
        m.cloud.points.push_back(a + (double(i) / double(n)) * ab + (double(j) / double(n)) * ac);
        m.sample_triangle.push_back(uint32_t(t));
      }
    // Every point of the triangle lies in a sub-triangle of the grid whose edges are at most longest / n,
    // so it is within that distance of the sub-triangle's corners.
    m.reach = std::max(m.reach, longest[t] / double(n));
  }
  m.tree = std::make_unique<Tree>(3, m.cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
}

SurfaceIndex::~SurfaceIndex() = default;

bool SurfaceIndex::empty() const { return !impl_->tree; }

SurfacePoint SurfaceIndex::closest(const glm::dvec3& query, const glm::dvec3& normal) const {
  const Impl& m = *impl_;
  const double q[3] = {query.x, query.y, query.z};
  uint32_t nearest = 0;
  double nearest_sq = 0;
  m.tree->knnSearch(q, 1, &nearest, &nearest_sq);

  // The nearest sample's triangle bounds the distance; every triangle with a closer point (or a tie) has a
  // sample within that bound plus the tie and the reach. The margin covers rounding in squared distances.
  const auto [first_weights, first_sq] = m.closest_on(m.sample_triangle[nearest], query);
  const double radius = (std::sqrt(first_sq) + m.tie + m.reach) * (1 + 1e-9) + 1e-300;
  std::vector<std::pair<uint32_t, double>> found;
  m.tree->radiusSearch(q, radius * radius, found, nanoflann::SearchParams(32, 0, false));
  std::vector<uint32_t> candidates;
  candidates.reserve(found.size() + 1);
  candidates.push_back(m.sample_triangle[nearest]);
  for (const auto& [sample, unused] : found) candidates.push_back(m.sample_triangle[sample]);
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());

  struct Candidate {
    uint32_t triangle;
    glm::dvec3 weights;
    double distance;
  };
  std::vector<Candidate> near;
  near.reserve(candidates.size());
  double best_distance = kInf;
  for (uint32_t t : candidates) {
    const auto [weights, sq] = m.closest_on(t, query);
    near.push_back({t, weights, std::sqrt(sq)});
    best_distance = std::min(best_distance, near.back().distance);
  }
  // Within the window, the point whose normal agrees best with the query's; among agreements equal to
  // within 1e-3 (flat regions, or no normals), the nearest, then the triangle listed first.
  const bool by_normal = !m.normals.empty() && glm::length(normal) > 0;
  std::vector<double> agreement(near.size(), 0.0);
  double best_agreement = -kInf;
  for (size_t i = 0; i < near.size(); ++i) {
    const Candidate& c = near[i];
    if (c.distance > best_distance + m.tie) continue;
    if (by_normal) {
      glm::dvec3 n(0);
      for (int k = 0; k < 3; ++k) n += c.weights[k] * m.normals[m.triangles[3 * size_t(c.triangle) + size_t(k)]];
      agreement[i] = glm::length(n) > 0 ? glm::dot(glm::normalize(n), glm::normalize(normal)) : -2;
    }
    best_agreement = std::max(best_agreement, agreement[i]);
  }
  const Candidate* best = nullptr;
  for (size_t i = 0; i < near.size(); ++i) {  // in triangle order, so the first of equals wins
    const Candidate& c = near[i];
    if (c.distance > best_distance + m.tie || agreement[i] < best_agreement - 1e-3) continue;
    if (!best || c.distance < best->distance) best = &c;
  }
  const uint32_t best_triangle = best->triangle;
  const glm::dvec3 best_weights = best->weights;
  const double best_sq = best->distance * best->distance;

  SurfacePoint point;
  for (int k = 0; k < 3; ++k) {
    point.vertex[k] = m.triangles[3 * size_t(best_triangle) + size_t(k)];
    point.weight[k] = float(best_weights[k]);
  }
  point.distance = float(std::sqrt(best_sq));
  return point;
}

}  // namespace dqskin::diff_detail
