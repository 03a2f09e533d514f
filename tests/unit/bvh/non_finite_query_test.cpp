// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Query points with a NaN or infinite coordinate: every BVH-backed SDF returns NaN (no distance
// or sign is defined there) and never crashes. MeshSdf<float> used to pick an empty child of a
// wide node (its box distance came out as 0 from inf - inf) and read far outside the node array.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/sdf/bvh_union.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"
#include "ebgeom/sdf/shapes.hpp"
#include "ebgeom/sdf/signed_mesh_sdf.hpp"
#include "test_support.hpp"

using namespace ebgeom;

template <class T> class NonFiniteQueryTest : public ::testing::Test {};
TYPED_TEST_SUITE(NonFiniteQueryTest, test::FloatTypes);

namespace {
template <class T> bool same_bits(T a, T b) { return std::memcmp(&a, &b, sizeof(T)) == 0; }

template <class T> std::vector<Vec3<T>> non_finite_points() {
  const T inf = std::numeric_limits<T>::infinity(), nan = std::numeric_limits<T>::quiet_NaN();
  return {{-inf, inf, -inf}, {inf, 0, 0},        {0, -inf, 0},     {0, 0, inf},
          {inf, inf, inf},   {-inf, -inf, -inf}, {nan, 0, 0},      {0, nan, 0},
          {0, 0, nan},       {nan, nan, nan},    {nan, inf, T(1)}, {T(1e30), nan, -inf}};
}
} // namespace

TYPED_TEST(NonFiniteQueryTest, MeshSdfGivesNaNAndFiniteNeighboursAreUnchanged) {
  using T = TypeParam;
  const auto sdf = MeshSdf<T>::build(make_torus<T>(T(1), T(0.35), 40, 20).value()).value();
  for (const Vec3<T>& p : non_finite_points<T>()) {
    SCOPED_TRACE(testing::Message() << p.x << " " << p.y << " " << p.z);
    EXPECT_TRUE(std::isnan(sdf(p)));
    EXPECT_TRUE(std::isnan(sdf.closest(p).distance));
    EXPECT_EQ(sdf.closest(p).triangle, MeshClosestPoint<T>::invalid_triangle);
    EXPECT_TRUE(std::isnan(sdf.closest_within(p, T(0.5)).distance));
    EXPECT_TRUE(std::isnan(sdf.bounded(p, T(0.5))));
    EXPECT_TRUE(std::isnan(sdf.unsigned_distance(p)));
  }
  // A lattice block with one non-finite sample: NaN there, the per-point value elsewhere.
  const std::array<std::size_t, 3> dims{{4, 4, 4}};
  std::vector<Vec3<T>> pts;
  for (std::size_t z = 0; z < 4; ++z)
    for (std::size_t y = 0; y < 4; ++y)
      for (std::size_t x = 0; x < 4; ++x)
        pts.push_back({T(-1.5) + T(x), T(-1.5) + T(y), T(-0.3) + T(0.2) * T(z)});
  pts[21] = {-std::numeric_limits<T>::infinity(), std::numeric_limits<T>::infinity(), T(0)};
  std::vector<T> out(pts.size());
  sdf.eval_lattice(Span<const Vec3<T>>(pts), dims, Span<T>(out));
  for (std::size_t l = 0; l < pts.size(); ++l) {
    if (l == 21)
      EXPECT_TRUE(std::isnan(out[l]));
    else
      EXPECT_TRUE(same_bits(out[l], sdf(pts[l]))) << l;
  }
}

TYPED_TEST(NonFiniteQueryTest, SignedMeshSdfGivesNaNInEveryMode) {
  using T = TypeParam;
  const PolygonSoup<T> soup = make_icosphere<T>(2, T(1)).value();
  for (SignMode m : {SignMode::pseudonormal, SignMode::winding, SignMode::fast_winding,
                     SignMode::unsigned_distance, SignMode::automatic}) {
    SignOptions opt;
    opt.mode = m;
    const auto sdf = SignedMeshSdf<T>::build(soup, opt).value();
    for (const Vec3<T>& p : non_finite_points<T>()) {
      EXPECT_TRUE(std::isnan(sdf(p))) << to_string(m);
      EXPECT_TRUE(std::isnan(sdf.closest(p).distance)) << to_string(m);
    }
  }
}

TYPED_TEST(NonFiniteQueryTest, BvhUnionGivesNaN) {
  using T = TypeParam;
  std::vector<Sphere<T>> balls;
  for (int i = 0; i < 50; ++i) balls.push_back({{T(i), T(0), T(0)}, T(0.4)});
  const BvhUnion<Sphere<T>> u(balls);
  for (const Vec3<T>& p : non_finite_points<T>()) EXPECT_TRUE(std::isnan(u(p)));
  EXPECT_NEAR(u({T(3), T(1), T(0)}), T(0.6), T(1e-6)); // finite points unchanged
}
