// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/sdf/dcel_sdf.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "ebgeom/bvh/traverse.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/sdf/brute_force_dcel_sdf.hpp"
#include "ebgeom/sdf/bvh_union.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"
#include "ebgeom/sdf/shapes.hpp"
#include "test_support.hpp"

using namespace ebgeom;

template <class T> class DcelSdfTest : public ::testing::Test {};
TYPED_TEST_SUITE(DcelSdfTest, test::FloatTypes);

namespace {
template <class T> bool same_bits(T a, T b) { return std::memcmp(&a, &b, sizeof(T)) == 0; }

template <class T, int K, class BV>
void dcel_matches_brute_force(const PolygonSoup<T>& soup, InsideTest test) {
  const auto ref = BruteForceDcelSdf<T>::build(soup, test).value();
  for (auto m : {bvh::BuildMethod::sah_binned, bvh::BuildMethod::morton}) {
    bvh::BuildOptions o;
    o.method = m;
    const auto sdf = DcelSdf<T, K, BV>::build(soup, test, o).value();
    static_assert(is_sdf_v<DcelSdf<T, K, BV>>);
    auto pts = test::random_points(ref.bounds().grown(T(0.4)), 1500, 31);
    for (std::size_t v = 0; v < ref.mesh().vertex_count(); v += 3)
      pts.push_back(ref.mesh().position(Index(v)));
    for (const auto& p : pts) {
      const auto a = sdf.closest(p), b = ref.closest(p);
      ASSERT_TRUE(same_bits(a.distance, b.distance))
          << "K=" << K << " p=" << p << ": " << a.distance << " vs " << b.distance;
      ASSERT_EQ(a.distance2, b.distance2);
    }
  }
}
} // namespace

TYPED_TEST(DcelSdfTest, BoxAndSphereBvhsEqualBruteForceOnPolygonMeshes) {
  using T = TypeParam;
  // Quads (torus), triangles (icosphere), quads with sharp edges (cube).
  const auto torus = make_torus<T>(T(1), T(0.4), 24, 12).value();
  const auto ico = make_icosphere<T>(2, T(0.8)).value();
  const auto cube = make_cube<T>(T(0.6)).value();
  for (const auto* soup : {&torus, &ico, &cube}) {
    dcel_matches_brute_force<T, 4, Aabb<T>>(*soup, InsideTest::crossing_number);
    dcel_matches_brute_force<T, 2, BoundingSphere<T>>(*soup, InsideTest::crossing_number);
    dcel_matches_brute_force<T, 8, BoundingSphere<T>>(*soup, InsideTest::winding_number);
  }
}

TYPED_TEST(DcelSdfTest, SphereNodesEncloseTheirFaces) {
  using T = TypeParam;
  const auto sdf =
      DcelSdf<T, 4, BoundingSphere<T>>::build(make_torus<T>(1, T(0.3)).value()).value();
  const auto& t = sdf.tree();
  std::size_t faces = 0;
  for (const auto& node : t.nodes)
    for (int k = 0; k < 4; ++k) {
      const auto r = node.child[k];
      if (!r.is_leaf()) continue;
      const BoundingSphere<T> s = node.child_bv(k);
      for (std::uint32_t i = r.index; i < r.index + r.count; ++i, ++faces)
        sdf.mesh().for_each_vertex(
            Index(t.prim[i]), [&](Index v) { EXPECT_TRUE(s.contains(sdf.mesh().position(v))); });
    }
  EXPECT_EQ(faces, sdf.mesh().face_count());
  // The generic visitors work on sphere trees too.
  std::size_t seen = 0;
  bvh::for_each_within(t, Vec3<T>{1, 0, 0}, T(0.5), [&](std::uint32_t) { ++seen; });
  EXPECT_GT(seen, 0u);
  EXPECT_LT(seen, sdf.mesh().face_count());
}

TYPED_TEST(DcelSdfTest, RejectsBadInput) {
  using T = TypeParam;
  auto soup = make_cube<T>(1).value();
  soup.vertices[2].z = std::numeric_limits<T>::quiet_NaN();
  const auto r = DcelSdf<T>::build(soup);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::non_finite);
}

// Enumeration values outside their lists are refused with an error, never replaced by a default
// method (the DCEL SDF, the triangle-mesh SDF and the BVH union share `bvh::check`).
TEST(DcelSdfOptions, OutOfRangeEnumValuesAreErrors) {
  const auto soup = make_cube<double>().value();
  EXPECT_TRUE(DcelSdf<double>::build(soup).has_value());
  const auto bad_test = DcelSdf<double>::build(soup, static_cast<InsideTest>(9));
  ASSERT_FALSE(bad_test.has_value());
  EXPECT_EQ(bad_test.error().code, ErrorCode::invalid_argument);
  EXPECT_NE(bad_test.error().message.find("InsideTest value 9"), std::string::npos);
  bvh::BuildOptions o;
  o.method = static_cast<bvh::BuildMethod>(5);
  const auto bad_method = DcelSdf<double>::build(soup, InsideTest::crossing_number, o);
  ASSERT_FALSE(bad_method.has_value());
  EXPECT_EQ(bad_method.error().code, ErrorCode::invalid_argument);
  o.max_leaf_size = MeshSdf<double>::default_build_options().max_leaf_size;
  const auto mesh_sdf = MeshSdf<double>::build(soup, o);
  ASSERT_FALSE(mesh_sdf.has_value());
  EXPECT_EQ(mesh_sdf.error().code, ErrorCode::invalid_argument);
  EXPECT_NE(mesh_sdf.error().message.find("BuildMethod value 5"), std::string::npos);
  EXPECT_EQ(BvhUnion<Sphere<double>>::make({Sphere<double>{}}, o).error().code,
            ErrorCode::invalid_argument);
}
