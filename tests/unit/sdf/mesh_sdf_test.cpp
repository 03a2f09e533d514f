// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/sdf/mesh_sdf.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "ebgeom/eval/evaluate.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"
#include "test_support.hpp"

using namespace ebgeom;

template <class T> class MeshSdfTest : public ::testing::Test {};
TYPED_TEST_SUITE(MeshSdfTest, test::FloatTypes);

namespace {
template <class T> bool same_bits(T a, T b) { return std::memcmp(&a, &b, sizeof(T)) == 0; }

/// A closed, non-convex test mesh: a torus (polygons of 4 corners triangulated) of a few thousand
/// triangles.
template <class T> PolygonSoup<T> torus() { return make_torus<T>(T(1), T(0.35), 40, 20).value(); }

/// Every query point kind: uniform in the box, near the surface, on vertices and edges.
template <class T> std::vector<Vec3<T>> probes(const TriangleMesh<T>& m, std::size_t n) {
  const Aabb<T> box = m.bounds().grown(T(0.3));
  auto pts = test::random_points(box, n, 17);
  std::mt19937_64 rng(3);
  for (std::size_t t = 0; t < m.triangle_count(); t += 37) {
    const Vec3<T> a = m.corner(t, 0), b = m.corner(t, 1), c = m.corner(t, 2);
    pts.push_back(a);                                                // on a vertex
    pts.push_back((a + b) * T(0.5));                                 // on an edge
    pts.push_back((a + b + c) / T(3) + m.face_normals[t] * T(1e-3)); // just outside a face
    pts.push_back((a + b + c) / T(3) - m.face_normals[t] * T(1e-3)); // just inside
  }
  return pts;
}

template <class T, int K, int W>
void matches_brute_force(const PolygonSoup<T>& soup, bvh::BuildMethod method, std::size_t n) {
  const auto ref = BruteForceMeshSdf<T>::build(soup).value();
  bvh::BuildOptions o = MeshSdf<T, K, W>::default_build_options();
  o.method = method;
  const auto sdf = MeshSdf<T, K, W>::build(soup, o).value();
  for (const auto& p : probes(ref.mesh(), n)) {
    const auto a = sdf.closest(p), b = ref.closest(p);
    ASSERT_TRUE(same_bits(a.distance, b.distance))
        << "K=" << K << " W=" << W << " p=" << p << " bvh=" << a.distance << " ref=" << b.distance;
    // Exact ties go to the lowest triangle index in both: the same triangle, feature and point.
    EXPECT_EQ(a.triangle, b.triangle) << p;
    EXPECT_EQ(a.feature, b.feature) << p;
    EXPECT_EQ(a.point, b.point) << p;
    ASSERT_TRUE(same_bits(sdf(p), b.distance));
  }
}
} // namespace

TYPED_TEST(MeshSdfTest, SatisfiesTheSdfContract) {
  using S = MeshSdf<TypeParam>;
  static_assert(is_sdf_v<S>);
  static_assert(S::kind == SdfKind::exact);
  const auto s = S::build(make_cube<TypeParam>(1).value()).value();
  EXPECT_EQ(s.bounds(), Aabb<TypeParam>::of({-1, -1, -1}, {1, 1, 1}));
  EXPECT_GT(s.memory_bytes(), 0u);
}

TYPED_TEST(MeshSdfTest, EqualsBruteForceForEveryArityBuilderAndBlockWidth) {
  using T = TypeParam;
  const auto soup = torus<T>();
  for (auto m :
       {bvh::BuildMethod::sah_binned, bvh::BuildMethod::median, bvh::BuildMethod::morton}) {
    matches_brute_force<T, 2, 4>(soup, m, 1500);
    matches_brute_force<T, 4, 8>(soup, m, 1500);
    matches_brute_force<T, 8, 8>(soup, m, 1500);
    matches_brute_force<T, 4, 1>(soup, m, 500);
  }
  matches_brute_force<T, 4, 8>(make_icosphere<T>(3, T(0.7)).value(), bvh::BuildMethod::sah_binned,
                               2000);
  matches_brute_force<T, 4, 8>(make_cube<T>(T(1)).value(), bvh::BuildMethod::sah_binned, 2000);
}

TYPED_TEST(MeshSdfTest, ClosestWithinIsANarrowBand) {
  using T = TypeParam;
  const auto sdf = MeshSdf<T>::build(torus<T>()).value();
  const auto ref = BruteForceMeshSdf<T>::build(torus<T>()).value();
  for (const auto& p : test::random_points(sdf.bounds().grown(T(0.5)), 2000, 23)) {
    const T d = ref(p);
    const auto c = sdf.closest_within(p, T(0.1));
    if (std::abs(d) <= T(0.099)) {
      EXPECT_TRUE(same_bits(c.distance, d)) << p;
    } else if (std::abs(d) > T(0.101)) {
      EXPECT_EQ(c.triangle, MeshClosestPoint<T>::invalid_triangle) << p;
      EXPECT_EQ(c.distance, std::numeric_limits<T>::infinity());
    }
    EXPECT_EQ(sdf.unsigned_distance(p), std::abs(d));
  }
  EXPECT_EQ(sdf.closest_within({0, 0, 0}, T(-1)).triangle, MeshClosestPoint<T>::invalid_triangle);
}

// The unsigned bounded search (what winding-signed bands search) is |bounded| bit for bit within
// the bound, +inf beyond it, on probes of every kind and at several bounds, the brute force
// deciding which side of the bound each probe is.
TYPED_TEST(MeshSdfTest, UnsignedBoundedIsTheMagnitudeOfBounded) {
  using T = TypeParam;
  const auto sdf = MeshSdf<T>::build(torus<T>()).value();
  const auto ref = BruteForceMeshSdf<T>::build(torus<T>()).value();
  std::size_t inside = 0, beyond = 0;
  for (const T max : {T(0), T(0.01), T(0.1), T(0.4), std::numeric_limits<T>::infinity()}) {
    for (const auto& p : probes(ref.mesh(), 600)) {
      const T u = sdf.unsigned_bounded(p, max), b = sdf.bounded(p, max), d = std::abs(ref(p));
      if (std::abs(b) <= max) {
        ASSERT_TRUE(same_bits(u, std::abs(b))) << p << " max " << max << ": " << u << " " << b;
        ASSERT_TRUE(same_bits(u, d)) << p;
        ++inside;
      } else {
        ASSERT_GT(u, max) << p;
        EXPECT_GT(d, max * T(0.999)) << p; // beyond the bound by the brute force too
        ++beyond;
      }
    }
  }
  EXPECT_GT(inside, 1000u);
  EXPECT_GT(beyond, 1000u);
  const T nan = std::numeric_limits<T>::quiet_NaN();
  EXPECT_TRUE(std::isnan(sdf.unsigned_bounded({nan, 0, 0}, T(1))));
  EXPECT_EQ(sdf.unsigned_bounded({0, 0, 0}, T(-1)), std::numeric_limits<T>::infinity());
  EXPECT_EQ(sdf.unsigned_bounded({0, 0, 0}, nan), std::numeric_limits<T>::infinity());
}

// Queries start from the bound of a seed triangle (the one nearest to the centre of the query's
// cell in an 8^3 grid over the box): equal to the brute force where that seed is itself the
// nearest triangle or ties with others (cell centres, a cube's symmetric points), far outside the
// grid (nearest cell), and on a mesh far from the origin (float rounding of large coordinates).
TYPED_TEST(MeshSdfTest, SeededSearchEqualsBruteForceAtCellCentresFarAwayAndOffset) {
  using T = TypeParam;
  PolygonSoup<T> offset = torus<T>();
  for (auto& v : offset.vertices) v = v + Vec3<T>{T(3e3), T(-1e3), T(500)};
  for (const PolygonSoup<T>& soup : {torus<T>(), offset, make_cube<T>(T(1)).value()}) {
    const auto sdf = MeshSdf<T>::build(soup).value();
    const auto ref = BruteForceMeshSdf<T>::build(soup).value();
    const Aabb<T> box = sdf.bounds();
    const Vec3<T> e = box.extent();
    std::vector<Vec3<T>> pts;
    for (int z = 0; z <= 8; ++z)
      for (int y = 0; y <= 8; ++y)
        for (int x = 0; x <= 8; ++x) {
          const int i[3] = {x, y, z};
          Vec3<T> centre, corner;
          for (int k = 0; k < 3; ++k) {
            centre[k] = box.lo[k] + e[k] * ((T(i[k]) + T(0.5)) / T(8)); // as the grid's seeds
            corner[k] = box.lo[k] + e[k] * (T(i[k]) / T(8));            // cell boundaries
          }
          pts.push_back(centre);
          pts.push_back(corner);
          pts.push_back(box.center() + (centre - box.center()) * T(1e3)); // far away
        }
    pts.push_back(box.center());
    for (const auto& p : pts) {
      const auto a = sdf.closest(p), b = ref.closest(p);
      ASSERT_TRUE(same_bits(a.distance, b.distance)) << p << " " << a.distance << " " << b.distance;
      EXPECT_EQ(a.triangle, b.triangle) << p;
      EXPECT_TRUE(same_bits(sdf.unsigned_distance(p), std::abs(b.distance))) << p;
      EXPECT_TRUE(
          same_bits(sdf.closest_within(p, T(2) * std::abs(b.distance) + T(1)).distance, b.distance))
          << p;
    }
  }
}

namespace {
/// `sdf.eval` on `pts` against one `sdf(p)` per point, bit for bit (NaN where the query is NaN).
template <class S, class T>
void expect_batch_equals_single(const S& sdf, const std::vector<Vec3<T>>& pts, const char* what) {
  std::vector<T> out(pts.size(), T(-7));
  sdf.eval(Span<const Vec3<T>>(pts), Span<T>(out));
  for (std::size_t i = 0; i < pts.size(); ++i)
    ASSERT_TRUE(same_bits(out[i], sdf(pts[i])))
        << what << ": point " << i << " of " << pts.size() << " " << pts[i] << " batch " << out[i]
        << " single " << sdf(pts[i]);
}
} // namespace

// The batch query visits the points in Morton order, each search seeded by the previous point's
// nearest triangle: every value equals the single query's, on scattered, clustered and repeated
// points (where the seed is the winner itself, at distance 0 on vertices and edges), with NaN and
// infinite coordinates mixed in, below and above the size where it starts sorting, in any input
// order; and the single queries equal the brute force.
TYPED_TEST(MeshSdfTest, BatchEvalEqualsSingleQueriesBitForBit) {
  using T = TypeParam;
  using S = MeshSdf<T>;
  static_assert(has_batch_eval_v<S> && has_ordered_batch_v<S>);
  for (const PolygonSoup<T>& soup : {torus<T>(), make_cube<T>(T(1)).value()}) {
    const auto sdf = S::build(soup).value();
    const auto ref = BruteForceMeshSdf<T>::build(soup).value();
    const std::vector<Vec3<T>> scattered = probes(ref.mesh(), 3000);
    for (std::size_t i = 0; i < scattered.size(); i += 7)
      ASSERT_TRUE(same_bits(sdf(scattered[i]), ref(scattered[i]))) << scattered[i];
    expect_batch_equals_single(sdf, scattered, "scattered");

    std::vector<Vec3<T>> clustered;
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    const Aabb<T> box = sdf.bounds();
    for (int c = 0; c < 6; ++c) {
      const Vec3<T> centre = box.lo + box.extent() * T(0.2 * c);
      for (int i = 0; i < 400; ++i)
        clustered.push_back(centre + Vec3<T>{T(u(rng)), T(u(rng)), T(u(rng))} * T(1e-3));
    }
    expect_batch_equals_single(sdf, clustered, "clustered");

    std::vector<Vec3<T>> repeated;
    const TriangleMesh<T>& m = ref.mesh();
    for (std::size_t t = 0; t < m.triangle_count(); t += 5) // vertices, edges: exact ties
      for (int k = 0; k < 40; ++k)
        repeated.push_back(k % 2 ? m.corner(t, 0) : (m.corner(t, 0) + m.corner(t, 1)) * T(0.5));
    for (int k = 0; k < 500; ++k) repeated.push_back(box.center());
    expect_batch_equals_single(sdf, repeated, "repeated");

    std::vector<Vec3<T>> odd = scattered;
    const T inf = std::numeric_limits<T>::infinity(), nan = std::numeric_limits<T>::quiet_NaN();
    for (std::size_t i = 0; i < odd.size(); i += 13) odd[i].y = i % 2 ? nan : -inf;
    odd.push_back({inf, inf, inf});
    expect_batch_equals_single(sdf, odd, "NaN and inf");

    std::vector<Vec3<T>> reversed(scattered.rbegin(), scattered.rend());
    expect_batch_equals_single(sdf, reversed, "reversed");
    for (std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(2), S::batch_order_min - 1,
                          S::batch_order_min, S::batch_order_min + 1})
      expect_batch_equals_single(
          sdf, std::vector<Vec3<T>>(scattered.begin(), scattered.begin() + std::ptrdiff_t(n)),
          "short");
    // Only the first min(points, values) are written.
    std::vector<T> out(10, T(-7));
    sdf.eval(Span<const Vec3<T>>(scattered), Span<T>(out).first(5));
    for (std::size_t i = 0; i < 10; ++i)
      EXPECT_TRUE(same_bits(out[i], i < 5 ? sdf(scattered[i]) : T(-7))) << i;
  }
}

// The tile query takes its bounds from a lattice's corner samples: on points that are no lattice
// (a tile's samples shuffled) it still returns the single queries' values.
TYPED_TEST(MeshSdfTest, LatticeEvalOfPointsThatAreNoLatticeEqualsSingleQueries) {
  using T = TypeParam;
  const auto sdf = MeshSdf<T>::build(torus<T>()).value();
  const std::vector<Vec3<T>> pts = test::random_points(sdf.bounds().grown(T(0.3)), 51200, 31);
  std::vector<T> out(512);
  for (const std::array<std::size_t, 3> dims :
       {std::array<std::size_t, 3>{{8, 8, 8}}, std::array<std::size_t, 3>{{512, 1, 1}}})
    for (std::size_t s = 0; s < pts.size(); s += 512) {
      sdf.eval_lattice(Span<const Vec3<T>>(pts).subspan(s, 512), dims, Span<T>(out));
      for (std::size_t i = 0; i < 512; ++i)
        ASSERT_TRUE(same_bits(out[i], sdf(pts[s + i]))) << dims[0] << " point " << s + i;
      sdf.unsigned_lattice(Span<const Vec3<T>>(pts).subspan(s, 512), dims, Span<T>(out));
      for (std::size_t i = 0; i < 512; ++i)
        ASSERT_TRUE(same_bits(out[i], std::abs(sdf(pts[s + i])))) << dims[0] << " point " << s + i;
    }
}

// The unsigned tile query (what grids with a winding sign evaluate) is |S| bit for bit on real
// lattices: tiles across the surface, inside, outside, and of odd sizes, against the brute force.
TYPED_TEST(MeshSdfTest, UnsignedLatticeIsTheMagnitudeOnLattices) {
  using T = TypeParam;
  const auto sdf = MeshSdf<T>::build(torus<T>()).value();
  const auto ref = BruteForceMeshSdf<T>::build(torus<T>()).value();
  const Aabb<T> box = sdf.bounds().grown(T(0.2));
  std::size_t near = 0;
  for (const std::array<std::size_t, 3> dims :
       {std::array<std::size_t, 3>{{8, 8, 8}}, std::array<std::size_t, 3>{{5, 3, 7}},
        std::array<std::size_t, 3>{{1, 1, 1}}, std::array<std::size_t, 3>{{16, 2, 1}}})
    for (const auto& o : test::random_points(box, 40, 5)) {
      const T h = T(0.043);
      std::vector<Vec3<T>> tile;
      for (std::size_t z = 0; z < dims[2]; ++z)
        for (std::size_t y = 0; y < dims[1]; ++y)
          for (std::size_t x = 0; x < dims[0]; ++x)
            tile.push_back(o + Vec3<T>{T(x), T(y), T(z)} * h);
      std::vector<T> out(tile.size());
      sdf.unsigned_lattice(tile, dims, out);
      for (std::size_t l = 0; l < tile.size(); ++l) {
        const T d = std::abs(ref(tile[l]));
        ASSERT_TRUE(same_bits(out[l], d)) << tile[l] << ": " << out[l] << " vs " << d;
        near += d < T(0.05);
      }
    }
  EXPECT_GT(near, 500u);
}

// `evaluate` hands MeshSdf's batch query large spans: the same bits whatever the thread count.
TYPED_TEST(MeshSdfTest, EvaluateDoesNotDependOnTheThreadCount) {
  using T = TypeParam;
  const auto sdf = MeshSdf<T>::build(torus<T>()).value();
  const std::vector<Vec3<T>> pts = test::random_points(sdf.bounds().grown(T(0.5)), 20000, 29);
  std::vector<T> single(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) single[i] = sdf(pts[i]);
  for (int threads : {1, 2, 3, 7}) {
    ExecOptions ex;
    ex.threads = threads;
    ex.serial_threshold = 0;
    std::vector<T> out(pts.size(), T(-7));
    ASSERT_TRUE(evaluate(sdf, Span<const Vec3<T>>(pts), Span<T>(out), ex));
    for (std::size_t i = 0; i < pts.size(); ++i)
      ASSERT_TRUE(same_bits(out[i], single[i])) << threads << " threads, point " << i;
  }
}

TYPED_TEST(MeshSdfTest, DegenerateMeshes) {
  using T = TypeParam;
  auto tri_soup = [](std::vector<Vec3<T>> v, std::vector<Index> idx) {
    PolygonSoup<T> s;
    s.vertices = std::move(v);
    s.offsets.clear();
    s.offsets.push_back(0);
    for (std::size_t i = 0; i < idx.size(); i += 3) s.offsets.push_back(Index(i + 3));
    s.indices = std::move(idx);
    return s;
  };
  // One triangle; duplicate triangles; zero-area triangles.
  const std::vector<Vec3<T>> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 2, 2}, {3, 3, 3}};
  for (const auto& idx : std::vector<std::vector<Index>>{
           {0, 1, 2}, {0, 1, 2, 0, 1, 2, 0, 1, 2}, {0, 1, 2, 3, 4, 3}, {3, 4, 3, 3, 3, 3}}) {
    const auto soup = tri_soup(v, idx);
    const auto ref = BruteForceMeshSdf<T>::build(soup).value();
    const auto sdf = MeshSdf<T>::build(soup).value();
    for (const auto& p : test::random_points(Aabb<T>::of({-1, -1, -1}, {4, 4, 4}), 300, 2))
      EXPECT_TRUE(same_bits(sdf(p), ref(p))) << p;
    for (const auto& q : v) EXPECT_TRUE(same_bits(sdf(q), ref(q))) << q;
  }
  // 10^6 copies of one triangle (10^5 in the sanitizer builds): no stack overflow, logarithmic
  // depth, exact answers.
  std::vector<Index> many;
  const int copies = test::full_or_sanitized(1000000, 100000);
  for (int i = 0; i < copies; ++i) many.insert(many.end(), {0, 1, 2});
  const auto big = MeshSdf<T>::build(tri_soup(v, many)).value();
  EXPECT_LE(big.tree().depth, 30);
  const auto one = BruteForceMeshSdf<T>::build(tri_soup(v, {0, 1, 2})).value();
  for (const auto& p : test::random_points(Aabb<T>::of({-1, -1, -1}, {2, 2, 2}), 50, 4))
    EXPECT_TRUE(same_bits(big(p), one(p))) << p;
}

TYPED_TEST(MeshSdfTest, RejectsBadMeshesBeforeTheBuild) {
  using T = TypeParam;
  auto m = make_triangle_mesh(make_cube<T>(1).value()).value();
  auto nan = m;
  nan.vertices[3].y = std::numeric_limits<T>::quiet_NaN();
  auto r = MeshSdf<T>::make(nan);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::non_finite);
  EXPECT_NE(r.error().what().find("vertex 3"), std::string::npos) << r.error().what();
  auto bad = m;
  bad.triangles[2][1] = 99;
  EXPECT_EQ(MeshSdf<T>::make(bad).error().code, ErrorCode::bad_index);
  EXPECT_EQ(MeshSdf<T>::make(TriangleMesh<T>{}).error().code, ErrorCode::empty);
  PolygonSoup<T> nan_soup = make_cube<T>(1).value();
  nan_soup.vertices[0].x = std::numeric_limits<T>::infinity();
  EXPECT_EQ(MeshSdf<T>::build(nan_soup).error().code, ErrorCode::non_finite);
}

TYPED_TEST(MeshSdfTest, RefitAfterVerticesMoveEqualsARebuild) {
  using T = TypeParam;
  auto soup = torus<T>();
  auto sdf = MeshSdf<T>::build(soup).value();
  // Twist and stretch the torus.
  for (auto& v : soup.vertices) {
    const T a = T(0.4) * v.z;
    v = {v.x * std::cos(a) - v.y * std::sin(a), (v.x * std::sin(a) + v.y * std::cos(a)) * T(1.5),
         v.z + T(0.2) * v.x};
  }
  ASSERT_EQ(sdf.refit(soup).code, ErrorCode::ok);
  const auto ref = BruteForceMeshSdf<T>::build(soup).value();
  EXPECT_EQ(sdf.bounds(), ref.bounds());
  for (const auto& p : probes(ref.mesh(), 1000)) ASSERT_TRUE(same_bits(sdf(p), ref(p))) << p;
  // Different faces are refused.
  EXPECT_EQ(sdf.refit(make_cube<T>(1).value()).code, ErrorCode::invalid_argument);
}
