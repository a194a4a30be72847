// The nearest of a set of points to a query (internal to lib/lint: --fix binds a vertex without weight to
// the joint nearest to it in bind space). A k-d tree (Bentley 1975, "Multidimensional binary search trees
// used for associative searching"): O(n log n) to build, about O(log n) a query, where comparing every
// vertex with every joint was vertices × joints.
#pragma once

#include "dqskin/dual_quat.hpp"

#include <cstddef>
#include <vector>

namespace dqskin::lint {

class NearestPoint {
public:
  explicit NearestPoint(const std::vector<Vec3<double>>& points);

  // The index of the point nearest to `q` by glm::distance, the smallest index among equally near ones;
  // exactly what comparing every point in index order finds. Points that are not finite are never nearest;
  // 0 when the query is not finite, when point 0 is NaN (no distance compares below NaN) or when no point
  // is finite.
  size_t nearest(const Vec3<double>& q) const;

private:
  struct Item {
    Vec3<double> p;
    size_t index;
  };
  void build(size_t lo, size_t hi, int axis);
  void search(size_t lo, size_t hi, int axis, const Vec3<double>& q, double& best, size_t& best_index) const;

  std::vector<Item> items_;  // the tree in place: each range's median at its middle, split on x, y, z in turn
  bool first_is_nan_ = false;
};

}  // namespace dqskin::lint
