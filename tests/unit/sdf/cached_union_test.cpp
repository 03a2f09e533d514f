// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/sdf/cached_union.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "ebgeom/eval/evaluate.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"
#include "ebgeom/sdf/shapes.hpp"
#include "test_support.hpp"
#include "union_scenes.hpp"

using namespace ebgeom;
using test::lattice;
using test::same_bits;
using test::SoftBall;

namespace {
template <class T> using Ball = Sphere<T>;
/// A ball, or (when `slab`) the half-space z < h with an unbounded box: one type for both.
template <class T> struct BallOrSlab {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  Ball<T> ball;
  bool slab = false;
  T operator()(const Vec3<T>& p) const noexcept { return slab ? p.z - ball.radius : ball(p); }
  Aabb<T> bounds() const noexcept { return slab ? Aabb<T>::infinite() : ball.bounds(); }
};

template <class T> std::vector<Ball<T>> random_balls(int n, double rmin, double rmax, int seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> c(-1, 1), rad(rmin, rmax);
  std::vector<Ball<T>> v;
  for (int i = 0; i < n; ++i) v.push_back({{T(c(rng)), T(c(rng)), T(c(rng))}, T(rad(rng))});
  return v;
}

/// Checks `u` against its linear union at `points`, one by one and as a batch (`eval` and
/// `evaluate`); returns how many points the cache answered.
template <class U>
std::size_t expect_linear(const U& u, const std::vector<Vec3<typename U::scalar_type>>& points) {
  using T = typename U::scalar_type;
  std::vector<T> batch(points.size()), threaded(points.size());
  u.eval(points, batch);
  EXPECT_TRUE(evaluate(u, Span<const Vec3<T>>(points), Span<T>(threaded)).has_value());
  std::size_t cached = 0, wrong = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const T ref = u.linear(points[i]);
    const T v = u(points[i]);
    if (!same_bits(v, ref) || !same_bits(batch[i], ref) || !same_bits(threaded[i], ref)) {
      if (++wrong <= 5)
        ADD_FAILURE() << points[i] << ": " << v << ", batch " << batch[i] << ", evaluate "
                      << threaded[i] << " vs linear " << ref;
    }
    cached += u.cell(points[i]).cached;
  }
  EXPECT_EQ(wrong, 0u);
  return cached;
}

/// Points on the top grid's cell faces, edges and corners, and their neighbours one ulp away,
/// down to `levels` octree levels.
template <class T>
std::vector<Vec3<T>> grid_points(const Aabb<T>& region, const UnionCacheStats& st, int levels,
                                 std::size_t n, int seed) {
  std::mt19937_64 rng(seed);
  std::vector<Vec3<T>> pts;
  for (std::size_t k = 0; k < n; ++k) {
    const int level = int(rng() % std::uint64_t(levels + 1));
    Vec3<T> p;
    for (int a = 0; a < 3; ++a) {
      const std::uint64_t cells = std::uint64_t(st.dims[a]) << level;
      const std::uint64_t i = rng() % (cells + 1);
      p[a] = region.lo[a] + (region.hi[a] - region.lo[a]) * T(i) / T(cells);
      const int nudge = int(rng() % 3);
      if (nudge == 1) p[a] = std::nextafter(p[a], -std::numeric_limits<T>::infinity());
      if (nudge == 2) p[a] = std::nextafter(p[a], std::numeric_limits<T>::infinity());
    }
    pts.push_back(p);
  }
  return pts;
}

template <int K, class T> void check_lattice() {
  const auto balls = lattice<T>(12, T(0.02));
  UnionCacheOptions<T> opt;
  opt.region = Aabb<T>::of({-1, -1, -1}, {1, 1, 1});
  const CachedUnion<Ball<T>, K> u(balls, opt);
  static_assert(CachedUnion<Ball<T>, K>::cacheable);
  static_assert(CachedUnion<Ball<T>, K>::kind == SdfKind::bound);
  static_assert(is_sdf_v<CachedUnion<Ball<T>, K>>);
  static_assert(has_batch_eval_v<CachedUnion<Ball<T>, K>>);
  const UnionCacheStats& st = u.stats();
  // The cache exists and is used: short lists, every point in the region answered by it.
  ASSERT_GT(st.top_cells, 0u);
  EXPECT_GT(st.leaf_cells, st.top_cells / 2);
  EXPECT_GT(st.split_cells, 0u);
  EXPECT_EQ(st.fallback_cells, 0u);
  EXPECT_FALSE(st.capped);
  EXPECT_LE(st.longest_list, 40u);
  EXPECT_LT(st.mean_candidates, 12.0);
  EXPECT_GT(st.mean_candidates, 1.0);
  EXPECT_GT(st.bytes, 4 * st.top_cells);
  EXPECT_EQ(u.region(), opt.region);
  EXPECT_EQ(u.size(), balls.size());

  const auto inside = test::random_points(opt.region, 4000, 3);
  EXPECT_EQ(expect_linear(u, inside), inside.size());
  std::size_t listed = 0, evaluated = 0;
  for (const auto& p : inside) {
    const UnionCacheCell c = u.cell(p);
    ASSERT_TRUE(c.cached);
    ASSERT_LT(c.slots.size(), balls.size() / 10);
    for (std::size_t i = 1; i < c.slots.size(); ++i) ASSERT_LT(c.slots[i - 1], c.slots[i]);
    ASSERT_GE(c.evaluated, 1u);
    ASSERT_LE(c.evaluated, c.slots.size());
    listed += c.slots.size();
    evaluated += c.evaluated;
  }
  // The gap test skips candidates that cannot win at the point itself.
  EXPECT_LT(double(evaluated), 0.8 * double(listed));
  // Points on the region's upper faces (and one ulp above) are outside it.
  EXPECT_GT(expect_linear(u, grid_points(opt.region, st, st.depth, 4000, 4)), 3000u);
  // Inside the balls (negative values) and at their centres.
  std::vector<Vec3<T>> centres;
  for (std::size_t i = 0; i < balls.size(); i += 7) {
    centres.push_back(balls[i].center);
    centres.push_back(balls[i].center + Vec3<T>{T(0.011), T(-0.007), T(0.003)});
  }
  EXPECT_EQ(expect_linear(u, centres), centres.size());
  EXPECT_EQ(u(balls[5].center), -T(0.02));
  // Outside the region: the BVH answers.
  std::vector<Vec3<T>> outside;
  for (const auto& p : test::random_points(Aabb<T>::of({-3, -3, -3}, {3, 3, 3}), 3000, 5))
    if (!opt.region.contains(p)) outside.push_back(p);
  EXPECT_EQ(expect_linear(u, outside), 0u);
}
} // namespace

template <class T> class CachedUnionTest : public ::testing::Test {};
TYPED_TEST_SUITE(CachedUnionTest, test::FloatTypes);

TYPED_TEST(CachedUnionTest, EqualsTheLinearUnionOnTheSeedsLatticeForEveryWidth) {
  check_lattice<2, TypeParam>();
  check_lattice<4, TypeParam>();
  check_lattice<8, TypeParam>();
}

TYPED_TEST(CachedUnionTest, OverlappingObjectsWithTheDefaultRegion) {
  using T = TypeParam;
  const auto balls = random_balls<T>(400, 0.05, 0.6, 8);
  const CachedUnion<Ball<T>> u(balls);
  const UnionCacheStats& st = u.stats();
  ASSERT_GT(st.leaf_cells, 0u);
  EXPECT_LT(st.mean_candidates, double(balls.size()) / 4);
  // The default region: the balls' box grown by 1/16 of its longest side.
  Aabb<T> box;
  for (const auto& b : balls) box.extend(b.bounds());
  const T margin = max_component(box.extent()) / 16;
  EXPECT_NEAR(u.region().lo.x, box.lo.x - margin, T(1e-5));
  EXPECT_NEAR(u.region().hi.z, box.hi.z + margin, T(1e-5));
  const auto pts = test::random_points(u.region(), 4000, 9);
  EXPECT_EQ(expect_linear(u, pts), pts.size());
  std::size_t negative = 0;
  for (const auto& p : pts) negative += u(p) < T(0);
  EXPECT_GT(negative, pts.size() / 4); // deep inside several overlapping balls
  expect_linear(u, grid_points(u.region(), st, st.depth, 3000, 10));
  expect_linear(u, test::random_points(u.region().grown(T(1)), 2000, 11));
}

TYPED_TEST(CachedUnionTest, UnboundedObjectsAreAlwaysEvaluated) {
  using T = TypeParam;
  std::vector<BallOrSlab<T>> objects;
  for (const auto& b : random_balls<T>(300, 0.02, 0.15, 12)) objects.push_back({b, false});
  objects.insert(objects.begin() + 100, BallOrSlab<T>{{{0, 0, 0}, T(-0.4)}, true}); // z < -0.4
  objects.push_back({{{0, 0, 0}, T(-0.9)}, true});
  UnionCacheOptions<T> opt;
  opt.region = Aabb<T>::of({-1.2, -1.2, -1.2}, {1.2, 1.2, 1.2});
  const CachedUnion<BallOrSlab<T>, 8> u(objects, opt);
  EXPECT_EQ(u.bvh_union().unbounded().size(), 2u);
  EXPECT_EQ(u.bvh_union().unbounded_order()[0], 100u);
  ASSERT_GT(u.stats().leaf_cells, 0u);
  const auto pts = test::random_points(opt.region, 4000, 13);
  EXPECT_EQ(expect_linear(u, pts), pts.size());
  // Deep below the slab's plane, no ball can win: cells there have empty lists.
  const UnionCacheCell c = u.cell({T(0.05), T(-0.3), T(-1.15)});
  EXPECT_TRUE(c.cached);
  EXPECT_EQ(c.slots.size(), 0u);
  EXPECT_EQ(u({T(0.05), T(-0.3), T(-1.15)}), T(-1.15) + T(0.4));
  expect_linear(u, grid_points(opt.region, u.stats(), u.stats().depth, 2000, 14));
}

TYPED_TEST(CachedUnionTest, OneObjectNoObjectAndObjectsWithoutACache) {
  using T = TypeParam;
  const CachedUnion<Ball<T>> one(std::vector<Ball<T>>{{{T(0.1), 0, 0}, T(0.5)}});
  ASSERT_EQ(one.stats().leaf_cells, one.stats().top_cells);
  EXPECT_EQ(one.stats().longest_list, 1u);
  EXPECT_EQ(expect_linear(one, test::random_points(one.region(), 500, 15)), 500u);
  EXPECT_EQ(one({T(0.1), 0, 0}), T(-0.5));

  const CachedUnion<Ball<T>> none(std::vector<Ball<T>>{});
  EXPECT_EQ(none.stats().top_cells, 0u);
  EXPECT_TRUE(none.region().is_empty());
  EXPECT_EQ(none({0, 0, 0}), std::numeric_limits<T>::infinity());
  EXPECT_FALSE(none.cell({0, 0, 0}).cached);

  // Only unbounded objects: no box to cache.
  const CachedUnion<BallOrSlab<T>> slabs(std::vector<BallOrSlab<T>>{{{{0, 0, 0}, T(0.5)}, true}});
  EXPECT_EQ(slabs.stats().top_cells, 0u);
  EXPECT_EQ(slabs({0, 0, 1}), T(0.5));

  // Not prunable: no cache, the BVH union's values.
  const auto balls = random_balls<T>(100, 0.05, 0.3, 16);
  std::vector<SoftBall<T>> soft;
  for (const auto& b : balls) soft.push_back(SoftBall<T>{b});
  const CachedUnion<SoftBall<T>> us(soft);
  static_assert(!CachedUnion<SoftBall<T>>::cacheable);
  EXPECT_EQ(us.stats().top_cells, 0u);
  EXPECT_EQ(expect_linear(us, test::random_points(us.bounds(), 500, 17)), 0u);

  // Checked construction refuses NaN bounds.
  std::vector<Ball<T>> bad = {{{0, 0, 0}, T(1)}, {{std::numeric_limits<T>::quiet_NaN(), 0, 0}, 1}};
  const auto r = CachedUnion<Ball<T>>::make(bad);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::non_finite);
  EXPECT_TRUE(CachedUnion<Ball<T>>::make(balls).has_value());
}

TYPED_TEST(CachedUnionTest, TheMemoryCapHoldsAndCellsFallBack) {
  using T = TypeParam;
  const auto balls = lattice<T>(8, T(0.05));
  UnionCacheOptions<T> opt;
  opt.region = Aabb<T>::of({-1, -1, -1}, {1, 1, 1});
  opt.max_bytes = 4096; // the top grid fits, not every list
  const CachedUnion<Ball<T>> u(balls, opt);
  const UnionCacheStats& st = u.stats();
  EXPECT_TRUE(st.capped);
  EXPECT_LE(st.bytes, opt.max_bytes);
  EXPECT_GT(st.top_cells, 0u);
  EXPECT_GT(st.fallback_cells, 0u);
  EXPECT_GT(st.leaf_cells, 0u);
  const auto pts = test::random_points(opt.region, 3000, 18);
  const std::size_t cached = expect_linear(u, pts);
  EXPECT_GT(cached, 0u);
  EXPECT_LT(cached, pts.size());

  // A cap that stops splits but not lists; and a cap below one top cell: no cache.
  UnionCacheOptions<T> mid = opt;
  mid.max_bytes = std::size_t(1) << 16;
  mid.top_cells_per_object = 1;
  mid.max_candidates = 1;
  mid.min_split_gain = 0;
  const CachedUnion<Ball<T>> m(balls, mid);
  EXPECT_TRUE(m.stats().capped);
  EXPECT_LE(m.stats().bytes, mid.max_bytes);
  EXPECT_GT(m.stats().split_cells, 0u);
  expect_linear(m, pts);
  UnionCacheOptions<T> tiny = opt;
  tiny.max_bytes = 4;
  EXPECT_EQ(CachedUnion<Ball<T>>(balls, tiny).stats().top_cells, 0u);
}

TYPED_TEST(CachedUnionTest, TheCacheDoesNotDependOnTheThreadCount) {
  using T = TypeParam;
  const auto balls = random_balls<T>(2000, 0.01, 0.05, 19);
  UnionCacheOptions<T> a, b;
  a.exec.threads = 1;
  b.exec.threads = 3;
  b.exec.serial_threshold = 1;
  const CachedUnion<Ball<T>> ua(balls, a), ub(balls, b);
  EXPECT_GT(ua.stats().split_cells, 0u); // the parallel split step ran
  EXPECT_EQ(ua.stats().bytes, ub.stats().bytes);
  EXPECT_EQ(ua.stats().split_cells, ub.stats().split_cells);
  EXPECT_EQ(ua.stats().candidates, ub.stats().candidates);
  for (const auto& p : test::random_points(ua.region(), 2000, 20)) {
    const UnionCacheCell ca = ua.cell(p), cb = ub.cell(p);
    ASSERT_EQ(ca.cached, cb.cached);
    ASSERT_EQ(ca.slots.size(), cb.slots.size());
    for (std::size_t i = 0; i < ca.slots.size(); ++i) ASSERT_EQ(ca.slots[i], cb.slots[i]);
  }
}

TYPED_TEST(CachedUnionTest, ACacheOfMeshSdfs) {
  using T = TypeParam;
  std::vector<MeshSdf<T>> meshes;
  for (int i = 0; i < 6; ++i) {
    auto soup = make_icosphere<T>(2, T(0.3)).value();
    for (auto& v : soup.vertices) v += Vec3<T>{T(0.45) * T(i), T(0.1) * T(i % 2), 0};
    meshes.push_back(MeshSdf<T>::build(soup).value());
  }
  const CachedUnion<MeshSdf<T>> scene(meshes);
  ASSERT_GT(scene.stats().leaf_cells, 0u);
  EXPECT_LT(scene.stats().mean_candidates, 5.0);
  const auto pts = test::random_points(scene.region(), 1500, 21);
  EXPECT_EQ(expect_linear(scene, pts), pts.size());
}
