// The structures that keep `dqskin lint` linear in the skeleton's size: NodeTree (roots and ancestors in
// O(1) a query) and NearestPoint (a k-d tree for --fix's nearest joint) give exactly what walking the
// parents and comparing every point give, ties and degenerate sets included.
#include "nearest_point.hpp"
#include "node_tree.hpp"

#include <gtest/gtest.h>

#include <random>

namespace dqskin::lint {
namespace {

// A random forest of `count` nodes: each node's parent is an earlier node or none.
std::vector<Node> random_forest(size_t count, std::mt19937& rng) {
  std::vector<Node> nodes(count);
  for (size_t i = 1; i < count; ++i) {
    if (rng() % 5 == 0) continue;  // a root
    const int parent = int(rng() % i);
    nodes[i].parent = parent;
    nodes[size_t(parent)].children.push_back(int(i));
  }
  return nodes;
}

TEST(NodeTree, AnswersAsWalkingTheParentsDoes) {
  std::mt19937 rng(7);
  const std::vector<Node> nodes = random_forest(300, rng);
  const NodeTree tree(nodes);
  for (size_t n = 0; n < nodes.size(); ++n) {
    int root = int(n);
    while (nodes[size_t(root)].parent >= 0) root = nodes[size_t(root)].parent;
    EXPECT_EQ(tree.root(int(n)), root) << "node " << n;
    for (size_t a = 0; a < nodes.size(); ++a) {
      bool above = false;
      for (int p = int(n); p >= 0 && !above; p = nodes[size_t(p)].parent) above = p == int(a);
      EXPECT_EQ(tree.is_ancestor_or_self(int(a), int(n)), above) << a << " above " << n;
    }
  }
}

TEST(NodeTree, ChainOfAMillionNodesNeedsNoDeepStack) {
  std::vector<Node> nodes(1'000'000);
  for (size_t i = 1; i < nodes.size(); ++i) {
    nodes[i].parent = int(i - 1);
    nodes[i - 1].children.push_back(int(i));
  }
  const NodeTree tree(nodes);
  EXPECT_EQ(tree.root(999'999), 0);
  EXPECT_TRUE(tree.is_ancestor_or_self(10, 999'999));
  EXPECT_FALSE(tree.is_ancestor_or_self(999'999, 10));
}

// What --fix did before the tree: every point compared, the first of equally near ones kept.
size_t brute_nearest(const std::vector<Vec3<double>>& points, const Vec3<double>& q) {
  size_t nearest = 0;
  for (size_t j = 1; j < points.size(); ++j)
    if (glm::distance(points[j], q) < glm::distance(points[nearest], q)) nearest = j;
  return nearest;
}

TEST(NearestPoint, FindsWhatComparingEveryPointFinds) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coordinate(-10, 10);
  std::vector<Vec3<double>> scattered(2000);
  for (Vec3<double>& p : scattered) p = {coordinate(rng), coordinate(rng), coordinate(rng)};
  // An integer grid with every point twice: many equally near points, and equal points.
  std::vector<Vec3<double>> grid;
  for (int copy = 0; copy < 2; ++copy)
    for (int x = -3; x <= 3; ++x)
      for (int y = -3; y <= 3; ++y)
        for (int z = -3; z <= 3; ++z) grid.push_back({x, y, z});
  std::uniform_int_distribution<int> half(-8, 8);
  for (const std::vector<Vec3<double>>* points : {&scattered, &grid}) {
    const NearestPoint tree(*points);
    for (int i = 0; i < 2000; ++i) {
      const Vec3<double> q = i % 2 ? Vec3<double>(coordinate(rng), coordinate(rng), coordinate(rng))
                                   : Vec3<double>(half(rng), half(rng), half(rng)) * 0.5;  // on grid ties
      EXPECT_EQ(tree.nearest(q), brute_nearest(*points, q)) << q.x << " " << q.y << " " << q.z;
    }
  }
}

TEST(NearestPoint, PointsThatAreNotFiniteAreNeverNearest) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Vec3<double>> points = {{inf, 0, 0}, {nan, 0, 0}, {5, 0, 0}, {1, 0, 0}};
  EXPECT_EQ(NearestPoint(points).nearest({0, 0, 0}), 3u);
  EXPECT_EQ(NearestPoint(points).nearest({0, 0, 0}), brute_nearest(points, {0, 0, 0}));
  const std::vector<Vec3<double>> nan_first = {{nan, 0, 0}, {1, 0, 0}};
  EXPECT_EQ(NearestPoint(nan_first).nearest({1, 0, 0}), brute_nearest(nan_first, {1, 0, 0}));
  EXPECT_EQ(NearestPoint(points).nearest({nan, 0, 0}), 0u);
  EXPECT_EQ(NearestPoint({}).nearest({0, 0, 0}), 0u);
}

}  // namespace
}  // namespace dqskin::lint
