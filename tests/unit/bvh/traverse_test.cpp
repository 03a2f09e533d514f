// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/bvh/traverse.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "ebgeom/bvh/experimental/nearest_variants.hpp"
#include "ebgeom/bvh/point_cloud.hpp"
#include "ebgeom/core/isa.hpp"
#include "test_support.hpp"

using namespace ebgeom;
using namespace ebgeom::bvh;

template <class T> class TraverseTest : public ::testing::Test {};
TYPED_TEST_SUITE(TraverseTest, test::FloatTypes);

namespace {
template <class T> std::vector<Vec3<T>> cloud(std::size_t n, std::uint64_t seed) {
  auto p = test::random_points(Aabb<T>::of({-1, -1, -1}, {1, 1, 1}), n, seed);
  // Clusters and exact duplicates make ties.
  for (std::size_t i = 0; i + 10 < n; i += 10) p[i + 1] = p[i];
  return p;
}

/// Nearest over a cloud with every traversal variant; all must equal brute force.
template <class T, int K> void nearest_variants_match(BuildMethod m) {
  const auto pts = cloud<T>(2000, 3);
  std::vector<Aabb<T>> boxes;
  for (const auto& p : pts) boxes.push_back(Aabb<T>::of(p));
  BuildOptions o;
  o.method = m;
  const auto w = flatten<K>(build(Span<const Aabb<T>>(boxes), Span<const Vec3<T>>(pts), o));
  for (const auto& q : test::random_points(Aabb<T>::of({-2, -2, -2}, {2, 2, 2}), 300, 9)) {
    const auto ref = brute_force_nearest(Span<const Vec3<T>>(pts), q);
    auto run = [&](auto&& search) {
      T best2 = std::numeric_limits<T>::infinity();
      std::uint32_t best = ~0u;
      search(w, q, best2, [&](std::uint32_t first, std::uint32_t count, T& b2) {
        for (std::uint32_t s = first; s < first + count; ++s) {
          const T d2 = norm2(pts[w.prim[s]] - q);
          if (d2 < b2) b2 = d2, best = w.prim[s];
        }
      });
      EXPECT_EQ(best2, ref.dist2);
      EXPECT_EQ(norm2(pts[best] - q), ref.dist2);
    };
    run([](auto&&... a) { nearest(a...); });
    run([](auto&&... a) { nearest<true>(a...); });
    run([](auto&&... a) { experimental::nearest_unordered(a...); });
    run([](auto&&... a) { experimental::nearest_recursive(a...); });
    // With a prefetch hook: the same result; the hook sees only real children, and every leaf the
    // search scans was announced to it before.
    {
      std::vector<std::uint32_t> announced;
      bool bad = false;
      T best2 = std::numeric_limits<T>::infinity();
      nearest(
          w, q, best2,
          [&](std::uint32_t first, std::uint32_t count, T& b2) {
            if (!w.root.is_leaf() &&
                std::find(announced.begin(), announced.end(), first) == announced.end())
              bad = true;
            for (std::uint32_t s = first; s < first + count; ++s)
              b2 = std::min(b2, norm2(pts[w.prim[s]] - q));
          },
          T(0),
          [&](ChildRef c) {
            if (c.is_empty() || (!c.is_leaf() && c.index >= w.nodes.size())) bad = true;
            if (c.is_leaf()) announced.push_back(c.index);
          });
      EXPECT_FALSE(bad);
      EXPECT_EQ(best2, ref.dist2);
    }
  }
}
} // namespace

TYPED_TEST(TraverseTest, NearestVariantsEqualBruteForce) {
  for (BuildMethod m : {BuildMethod::sah_binned, BuildMethod::median, BuildMethod::morton}) {
    nearest_variants_match<TypeParam, 2>(m);
    nearest_variants_match<TypeParam, 4>(m);
    nearest_variants_match<TypeParam, 8>(m);
  }
}

TYPED_TEST(TraverseTest, PointCloudNearestKNearestAndRadius) {
  using T = TypeParam;
  const auto pts = cloud<T>(3000, 5);
  const PointCloud<T, 4> pc(pts);
  const PointCloud<T, 8> pc8(pts, 1);
  for (const auto& q :
       test::random_points(Aabb<T>::of({-1.5, -1.5, -1.5}, {1.5, 1.5, 1.5}), 200, 11)) {
    const auto ref = brute_force_nearest(Span<const Vec3<T>>(pts), q);
    const auto got = pc.nearest(q);
    EXPECT_EQ(got.index, ref.index);
    EXPECT_EQ(got.dist2, ref.dist2);
    EXPECT_EQ(pc8.nearest(q).index, ref.index);
    for (std::size_t k : {1u, 2u, 7u, 40u}) {
      const auto rk = brute_force_k_nearest(Span<const Vec3<T>>(pts), q, k);
      const auto gk = pc.k_nearest(q, k);
      ASSERT_EQ(gk.size(), rk.size());
      for (std::size_t i = 0; i < k; ++i) {
        EXPECT_EQ(gk[i].index, rk[i].index) << "k=" << k << " i=" << i;
        EXPECT_EQ(gk[i].dist2, rk[i].dist2);
      }
    }
    const T r = T(0.2);
    std::vector<std::uint32_t> rr;
    for (std::size_t i = 0; i < pts.size(); ++i)
      if (norm2(pts[i] - q) <= r * r) rr.push_back(std::uint32_t(i));
    EXPECT_EQ(pc.within(q, r), rr);
  }
  // Bounded nearest: nothing within a tiny radius of a far point.
  EXPECT_EQ(pc.nearest({10, 10, 10}, T(1)).index, PointHit<T>::none);
  // More neighbours asked than points exist.
  EXPECT_EQ(pc.k_nearest({0, 0, 0}, 5000).size(), pts.size());
}

TYPED_TEST(TraverseTest, PointCloudIgnoresNonFinitePoints) {
  using T = TypeParam;
  std::vector<Vec3<T>> pts = {{0, 0, 0}, {std::numeric_limits<T>::quiet_NaN(), 0, 0}, {1, 0, 0}};
  pts.push_back({std::numeric_limits<T>::infinity(), 0, 0});
  const PointCloud<T> pc(pts);
  EXPECT_EQ(pc.nearest({T(0.9), 0, 0}).index, 2u);
  const auto k = pc.k_nearest({5, 0, 0}, 4);
  ASSERT_EQ(k.size(), 2u);
  EXPECT_EQ(k[0].index, 2u);
  EXPECT_EQ(k[1].index, 0u);
}

TYPED_TEST(TraverseTest, OverlapAndRadiusVisitorsFindEveryCandidate) {
  using T = TypeParam;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1, 1), s(0, 0.1);
  std::vector<Aabb<T>> boxes;
  for (int i = 0; i < 2000; ++i) {
    const Vec3<T> c{T(u(rng)), T(u(rng)), T(u(rng))};
    const Vec3<T> h{T(s(rng)), T(s(rng)), T(s(rng))};
    boxes.push_back({c - h, c + h});
  }
  std::vector<Vec3<T>> cent;
  for (const auto& b : boxes) cent.push_back(b.center());
  const auto w =
      flatten<4>(build(Span<const Aabb<T>>(boxes), Span<const Vec3<T>>(cent), BuildOptions{}));
  for (int q = 0; q < 50; ++q) {
    const Vec3<T> c{T(u(rng)), T(u(rng)), T(u(rng))};
    const Aabb<T> region{c - Vec3<T>::constant(T(0.2)), c + Vec3<T>::constant(T(0.3))};
    std::vector<std::uint32_t> got, ref;
    for_each_overlapping(w, region, [&](std::uint32_t slot) {
      if (boxes[w.prim[slot]].overlaps(region)) got.push_back(w.prim[slot]);
    });
    for (std::uint32_t i = 0; i < boxes.size(); ++i)
      if (boxes[i].overlaps(region)) ref.push_back(i);
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, ref);
    got.clear(), ref.clear();
    for_each_within(w, c, T(0.25), [&](std::uint32_t slot) {
      if (boxes[w.prim[slot]].distance2(c) <= T(0.25) * T(0.25)) got.push_back(w.prim[slot]);
    });
    for (std::uint32_t i = 0; i < boxes.size(); ++i)
      if (boxes[i].distance2(c) <= T(0.25) * T(0.25)) ref.push_back(i);
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, ref);
  }
  // Early stop: the visitor returns false at the first leaf.
  int leaves = 0;
  for_each_leaf_if(
      w, [](const Aabb<T>&) { return true; },
      [&](std::uint32_t, std::uint32_t) { return ++leaves < 1; });
  EXPECT_EQ(leaves, 1);
}

TYPED_TEST(TraverseTest, SphereBoundingVolumesGiveTheSameNearestAndVisits) {
  using T = TypeParam;
  const auto pts = cloud<T>(1500, 21);
  std::vector<Aabb<T>> boxes;
  for (const auto& p : pts) boxes.push_back(Aabb<T>::of(p).grown(T(0.01)));
  std::vector<Vec3<T>> cent;
  for (const auto& b : boxes) cent.push_back(b.center());
  const auto tree = build(Span<const Aabb<T>>(boxes), Span<const Vec3<T>>(cent));
  const auto w = flatten<4, BoundingSphere<T>>(tree, [&](std::uint32_t first, std::uint32_t n) {
    std::vector<Aabb<T>> mine;
    for (std::uint32_t s = first; s < first + n; ++s) mine.push_back(boxes[tree.prim[s]]);
    return BoundingSphere<T>::of_boxes(Span<const Aabb<T>>(mine));
  });
  for (const auto& q : test::random_points(Aabb<T>::of({-2, -2, -2}, {2, 2, 2}), 300, 4)) {
    const auto ref = brute_force_nearest(Span<const Vec3<T>>(pts), q);
    T best2 = std::numeric_limits<T>::infinity();
    nearest<true>(w, q, best2, [&](std::uint32_t first, std::uint32_t count, T& b2) {
      for (std::uint32_t s = first; s < first + count; ++s)
        b2 = std::min(b2, norm2(pts[w.prim[s]] - q));
    });
    EXPECT_EQ(best2, ref.dist2);
    // Within a radius: every point within 0.3 is reported (sphere pruning is conservative).
    std::size_t n = 0, m = 0;
    for_each_within(w, q, T(0.3),
                    [&](std::uint32_t s) { n += norm2(pts[w.prim[s]] - q) <= T(0.09); });
    for (const auto& p : pts) m += norm2(p - q) <= T(0.09);
    EXPECT_EQ(n, m);
  }
  // Refit with spheres: after moving every point, the tree still finds the nearest.
  auto moved = pts;
  for (auto& p : moved) p = p * T(2) + Vec3<T>{1, 0, 0};
  auto w2 = w;
  refit(w2, [&](std::uint32_t first, std::uint32_t n) {
    std::vector<Vec3<T>> mine;
    for (std::uint32_t s = first; s < first + n; ++s) mine.push_back(moved[w2.prim[s]]);
    return BoundingSphere<T>::of_points(Span<const Vec3<T>>(mine));
  });
  const Vec3<T> q{T(0.3), T(0.2), T(-0.1)};
  T best2 = std::numeric_limits<T>::infinity();
  nearest(w2, q, best2, [&](std::uint32_t first, std::uint32_t count, T& b2) {
    for (std::uint32_t s = first; s < first + count; ++s)
      b2 = std::min(b2, norm2(moved[w2.prim[s]] - q));
  });
  EXPECT_EQ(best2, brute_force_nearest(Span<const Vec3<T>>(moved), q).dist2);
}

namespace {
/// `order_children` against a plain sort of the surviving children.
template <class T, int K, Isa I = native_isa>
void order_children_matches_a_sort(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> pick(0, 6);
  const T pool[7] = {T(0),
                     T(-0.0),
                     T(0.25),
                     T(1),
                     T(1),
                     T(3),
                     std::numeric_limits<T>::infinity()}; // -0 ties with +0
  for (int round = 0; round < 500; ++round) {
    T d2[K];
    for (int k = 0; k < K; ++k) d2[k] = pool[pick(rng)]; // ties, zeros and empty slots
    const T lim = round % 3 == 0 ? std::numeric_limits<T>::infinity() : T(1.5);
    std::uint32_t key[K];
    const int m = bvh::detail::order_children<T, K, I>(d2, lim, key);
    std::vector<std::pair<T, int>> want;
    for (int k = 0; k < K; ++k)
      if (d2[k] < lim) want.push_back({d2[k], k});
    std::sort(want.begin(), want.end());
    ASSERT_EQ(m, int(want.size()));
    for (int j = 0; j < m; ++j) {
      const int k = int(key[j] & bvh::detail::child_mask<K>);
      ASSERT_EQ(d2[k], want[std::size_t(j)].first)
          << "K " << K << " isa " << int(I) << " position " << j;
      ASSERT_EQ(k, want[std::size_t(j)].second) << "ties keep the child order";
    }
  }
}
} // namespace

TYPED_TEST(TraverseTest, OrderChildrenSortsTheSurvivorsNearestFirst) {
  std::mt19937_64 rng(11);
  order_children_matches_a_sort<TypeParam, 2>(rng);
  order_children_matches_a_sort<TypeParam, 4>(rng);
  order_children_matches_a_sort<TypeParam, 8>(rng);
  order_children_matches_a_sort<TypeParam, 16>(rng);
  order_children_matches_a_sort<TypeParam, 4, Isa::baseline>(rng);
  order_children_matches_a_sort<TypeParam, 8, Isa::baseline>(rng);
#if EBGEOM_ISA_DISPATCH
  if (int(detected_isa()) >= int(Isa::avx2)) { // the vector networks (K = 4 and 8)
    order_children_matches_a_sort<TypeParam, 4, Isa::avx2>(rng);
    order_children_matches_a_sort<TypeParam, 8, Isa::avx2>(rng);
  }
  if (int(detected_isa()) >= int(Isa::avx512)) { // K = 16 floats
    order_children_matches_a_sort<TypeParam, 8, Isa::avx512>(rng);
    order_children_matches_a_sort<TypeParam, 16, Isa::avx512>(rng);
  }
#endif
}
