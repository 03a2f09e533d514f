// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/octree/octree.hpp"

#include <gtest/gtest.h>

#include <random>

#include "test_support.hpp"

using namespace ebgeom;

namespace {

template <class T> T sphere_sd(const Vec3<T>& p) { return norm(p) - T(0.7); }

// Refine cells the sphere's surface may cross; the payload records the centre value.
template <class T> struct SurfaceRefine {
  bool operator()(const Aabb<T>& box, int, T& payload) const {
    payload = sphere_sd(box.center());
    return std::abs(payload) <= T(0.5) * norm(box.extent());
  }
};

template <class T, class P>
void expect_same_tree(const Octree<T, P>& a, std::uint32_t ia, const Octree<T, P>& b,
                      std::uint32_t ib) {
  const auto& na = a.node(ia);
  const auto& nb = b.node(ib);
  ASSERT_EQ(na.box, nb.box);
  ASSERT_EQ(na.depth, nb.depth);
  ASSERT_TRUE(na.payload == nb.payload);
  ASSERT_EQ(na.is_leaf(), nb.is_leaf());
  if (na.is_leaf()) {
    const auto pa = a.primitives(na);
    const auto pb = b.primitives(nb);
    ASSERT_EQ(std::vector<std::uint32_t>(pa.begin(), pa.end()),
              std::vector<std::uint32_t>(pb.begin(), pb.end()));
    return;
  }
  for (int c = 0; c < 8; ++c) expect_same_tree(a, na.first_child + c, b, nb.first_child + c);
}

} // namespace

template <class T> class OctreeTest : public ::testing::Test {};
TYPED_TEST_SUITE(OctreeTest, test::FloatTypes);

TYPED_TEST(OctreeTest, DepthFirstAndBreadthFirstBuildTheSameTree) {
  using T = TypeParam;
  const Aabb<T> root = Aabb<T>::of({-1, -1, -1}, {1, 1, 1});
  OctreeOptions opt;
  opt.max_depth = 6;
  opt.order = OctreeOrder::depth_first;
  const auto df = Octree<T, T>::build(root, SurfaceRefine<T>{}, opt).value();
  opt.order = OctreeOrder::breadth_first;
  const auto bf = Octree<T, T>::build(root, SurfaceRefine<T>{}, opt).value();
  EXPECT_EQ(df.size(), bf.size());
  EXPECT_GT(df.size(), 1000u);
  expect_same_tree(df, 0, bf, 0);
  // storage orders really differ: breadth-first stores depths non-decreasing
  for (std::size_t i = 1; i < bf.size(); ++i)
    ASSERT_LE(bf.nodes()[i - 1].depth, bf.nodes()[i].depth);
  bool df_monotone = true;
  for (std::size_t i = 1; i < df.size(); ++i)
    df_monotone &= df.nodes()[i - 1].depth <= df.nodes()[i].depth;
  EXPECT_FALSE(df_monotone);
}

TYPED_TEST(OctreeTest, ChildrenTileTheParentAndDepthIsLimited) {
  using T = TypeParam;
  const Aabb<T> root = Aabb<T>::of({-1, -2, -1}, {1, 1, 3});
  OctreeOptions opt;
  opt.max_depth = 5;
  const auto tree = Octree<T, T>::build(root, SurfaceRefine<T>{}, opt).value();
  EXPECT_EQ(tree.depth(), 5);
  for (const auto& n : tree.nodes()) {
    ASSERT_LE(int(n.depth), opt.max_depth);
    if (n.is_leaf()) continue;
    Aabb<T> u;
    T vol = 0;
    for (int c = 0; c < 8; ++c) {
      const auto& ch = tree.node(n.first_child + c);
      ASSERT_EQ(int(ch.depth), int(n.depth) + 1);
      u.extend(ch.box);
      vol += ch.box.volume();
      for (int d = c + 1; d < 8; ++d) { // interiors are disjoint: overlap has zero volume
        const auto& o = tree.node(n.first_child + d).box;
        const Vec3<T> lo = max(ch.box.lo, o.lo), hi = min(ch.box.hi, o.hi);
        ASSERT_TRUE(lo.x >= hi.x || lo.y >= hi.y || lo.z >= hi.z);
      }
    }
    ASSERT_EQ(u, n.box);
    ASSERT_NEAR(vol, n.box.volume(), n.box.volume() * test::tol<T>());
  }
}

TYPED_TEST(OctreeTest, RefinementReachesEverySurfacePoint) {
  using T = TypeParam;
  OctreeOptions opt;
  opt.max_depth = 5;
  const auto tree =
      Octree<T, T>::build(Aabb<T>::of({-1, -1, -1}, {1, 1, 1}), SurfaceRefine<T>{}, opt).value();
  std::mt19937_64 rng(7);
  for (int i = 0; i < 2000; ++i) {
    const Vec3<T> p = test::random_unit<T>(rng) * T(0.7);
    const auto leaf = tree.find_leaf(p);
    ASSERT_NE(leaf, tree.no_child);
    ASSERT_TRUE(tree.node(leaf).box.contains(p));
    ASSERT_EQ(int(tree.node(leaf).depth), 5) << "surface point " << p << " in a coarse leaf";
  }
  EXPECT_EQ(tree.find_leaf({2, 0, 0}), tree.no_child);
}

TYPED_TEST(OctreeTest, LeavesListExactlyTheOverlappingPrimitives) {
  using T = TypeParam;
  std::vector<Aabb<T>> boxes;
  for (const auto& c : test::random_points(Aabb<T>::of({0, 0, 0}, {10, 10, 10}), 500, 3))
    boxes.push_back(Aabb<T>::of(c).grown(T(0.2)));
  for (auto order : {OctreeOrder::depth_first, OctreeOrder::breadth_first}) {
    OctreeOptions opt;
    opt.order = order;
    opt.max_leaf_size = 4;
    opt.max_depth = 8;
    const auto tree = Octree<T>::build_from_boxes(Span<const Aabb<T>>(boxes), opt).value();
    std::vector<int> seen(boxes.size(), 0);
    tree.traverse([&](std::uint32_t, const auto& n) {
      if (!n.is_leaf()) return true;
      const auto prims = tree.primitives(n);
      std::vector<std::uint32_t> expected;
      for (std::uint32_t k = 0; k < boxes.size(); ++k)
        if (boxes[k].overlaps(n.box)) expected.push_back(k);
      EXPECT_EQ(std::vector<std::uint32_t>(prims.begin(), prims.end()), expected);
      EXPECT_TRUE(prims.size() <= opt.max_leaf_size || int(n.depth) == opt.max_depth);
      for (auto k : prims) seen[k]++;
      return true;
    });
    for (int s : seen) ASSERT_GE(s, 1);
  }
}

TYPED_TEST(OctreeTest, OrderedTraversalFindsTheNearestPoint) {
  using T = TypeParam;
  const auto pts = test::random_points(Aabb<T>::of({-1, -1, -1}, {1, 1, 1}), 3000, 11);
  std::vector<Aabb<T>> boxes;
  for (const auto& p : pts) boxes.push_back(Aabb<T>::of(p));
  OctreeOptions opt;
  opt.max_leaf_size = 6;
  const auto tree = Octree<T>::build_from_boxes(Span<const Aabb<T>>(boxes), opt).value();
  std::size_t visited_total = 0;
  for (const auto& q :
       test::random_points(Aabb<T>::of({-1.5, -1.5, -1.5}, {1.5, 1.5, 1.5}), 300, 5)) {
    T best2 = std::numeric_limits<T>::infinity();
    std::uint32_t best = 0;
    tree.traverse_ordered([&](const auto& n) { return n.box.distance2(q); }, [&] { return best2; },
                          [&](std::uint32_t, const auto& n) {
                            ++visited_total;
                            for (auto k : tree.primitives(n)) {
                              const T d2 = norm2(pts[k] - q);
                              if (d2 < best2 || (d2 == best2 && k < best)) best2 = d2, best = k;
                            }
                          });
    T ref2 = std::numeric_limits<T>::infinity();
    std::uint32_t ref = 0;
    for (std::uint32_t k = 0; k < pts.size(); ++k)
      if (norm2(pts[k] - q) < ref2) ref2 = norm2(pts[k] - q), ref = k;
    ASSERT_EQ(best2, ref2);
    ASSERT_EQ(best, ref);
  }
  EXPECT_LT(visited_total, 300u * tree.size() / 4) << "ordered traversal should prune";
}

TEST(Octree, RejectsBadParameters) {
  EXPECT_EQ(
      Octree<double>::build(Aabb<double>::empty(), [](auto&&...) { return false; }).error().code,
      ErrorCode::invalid_argument);
  OctreeOptions opt;
  opt.max_depth = 40;
  EXPECT_EQ(Octree<double>::build(
                Aabb<double>::of({0, 0, 0}, {1, 1, 1}), [](auto&&...) { return true; }, opt)
                .error()
                .code,
            ErrorCode::invalid_argument);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Aabb<double>> bad{Aabb<double>({0, 0, 0}, {nan, 1, 1})};
  EXPECT_EQ(Octree<double>::build_from_boxes(Span<const Aabb<double>>(bad)).error().code,
            ErrorCode::non_finite);
  // a single point-sized root still builds (one leaf)
  std::vector<Aabb<double>> one{Aabb<double>::of({1, 1, 1})};
  const auto t = Octree<double>::build_from_boxes(Span<const Aabb<double>>(one)).value();
  EXPECT_EQ(t.size(), 1u);
  EXPECT_EQ(t.primitives(t.root()).size(), 1u);
}

TYPED_TEST(OctreeTest, ParallelBreadthFirstBuildsTheSameTree) {
  using T = TypeParam;
  const Aabb<T> root = Aabb<T>::of({-1, -1, -1}, {1, 1, 1});
  OctreeOptions opt;
  opt.max_depth = 6;
  opt.order = OctreeOrder::breadth_first;
  const auto serial = Octree<T, T>::build(root, SurfaceRefine<T>{}, opt).value();
  for (int threads : {2, 3, 0}) {
    opt.threads = threads;
    const auto par = Octree<T, T>::build(root, SurfaceRefine<T>{}, opt).value();
    ASSERT_EQ(par.size(), serial.size());
    for (std::size_t i = 0; i < serial.size(); ++i) {
      ASSERT_EQ(par.node(std::uint32_t(i)).box, serial.node(std::uint32_t(i)).box);
      ASSERT_EQ(par.node(std::uint32_t(i)).first_child, serial.node(std::uint32_t(i)).first_child);
      ASSERT_EQ(par.node(std::uint32_t(i)).payload, serial.node(std::uint32_t(i)).payload);
    }
  }
}
