// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/sdf/bvh_union.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <memory>
#include <random>
#include <vector>

#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/sdf/any_sdf.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"
#include "ebgeom/sdf/csg.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"
#include "ebgeom/sdf/shapes.hpp"
#include "ebgeom/sdf/signed_mesh_sdf.hpp"
#include "ebgeom/sdf/transforms.hpp"
#include "test_support.hpp"
#include "union_scenes.hpp"

using namespace ebgeom;
using test::lattice;
using test::same_bits;
using test::SoftBall;

namespace {
template <class T> using Ball = Sphere<T>;
template <class T> struct Slab { // unbounded: z < h
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  T h;
  T operator()(const Vec3<T>& p) const noexcept { return p.z - h; }
  Aabb<T> bounds() const noexcept { return Aabb<T>::infinite(); }
};
/// An exact ball that counts its evaluations (to see that a union prunes).
template <class T> struct CountingBall {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  Sphere<T> ball;
  std::shared_ptr<std::atomic<long>> calls;
  T operator()(const Vec3<T>& p) const noexcept {
    calls->fetch_add(1, std::memory_order_relaxed);
    return ball(p);
  }
  Aabb<T> bounds() const noexcept { return ball.bounds(); }
};
} // namespace

template <class T> class BvhUnionTest : public ::testing::Test {};
TYPED_TEST_SUITE(BvhUnionTest, test::FloatTypes);

TYPED_TEST(BvhUnionTest, EqualsTheLinearUnionOnTheSeedsLattice) {
  using T = TypeParam;
  const auto balls = lattice<T>(12, T(0.02));
  const BvhUnion<Ball<T>> u(balls);
  static_assert(BvhUnion<Ball<T>>::kind == SdfKind::bound);
  static_assert(BvhUnion<Ball<T>>::prunes);
  static_assert(is_sdf_v<BvhUnion<Ball<T>>>);
  EXPECT_EQ(u.size(), balls.size());
  for (const auto& p :
       test::random_points(Aabb<T>::of({-1.2, -1.2, -1.2}, {1.2, 1.2, 1.2}), 3000)) {
    T ref = std::numeric_limits<T>::infinity();
    for (const auto& b : balls) ref = std::min(ref, b(p));
    ASSERT_TRUE(same_bits(u(p), ref)) << p << ": " << u(p) << " vs " << ref;
    ASSERT_TRUE(same_bits(u.linear(p), ref));
  }
  // Centres are inside (negative), order() maps leaf order back to the input.
  for (std::size_t i = 0; i < u.objects().size(); ++i)
    EXPECT_EQ(u.objects()[i].center, balls[u.order()[i]].center);
  EXPECT_EQ(u(balls[5].center), -T(0.02));
}

TYPED_TEST(BvhUnionTest, OverlappingObjectsAndUnboundedOnes) {
  using T = TypeParam;
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u01(-1, 1), rad(0.05, 0.6);
  std::vector<Ball<T>> balls;
  for (int i = 0; i < 300; ++i)
    balls.push_back({{T(u01(rng)), T(u01(rng)), T(u01(rng))}, T(rad(rng))});
  const BvhUnion<Ball<T>, 8> u(balls);
  std::vector<SoftBall<T>> soft;
  for (const auto& b : balls) soft.push_back(SoftBall<T>{b});
  const BvhUnion<SoftBall<T>, 2> us(soft);
  static_assert(!BvhUnion<SoftBall<T>, 2>::prunes);
  for (const auto& p : test::random_points(Aabb<T>::of({-2, -2, -2}, {2, 2, 2}), 3000, 3)) {
    T ref = std::numeric_limits<T>::infinity();
    for (const auto& b : balls) ref = std::min(ref, b(p));
    ASSERT_TRUE(same_bits(u(p), ref)) << p; // deep inside several overlapping balls too
    ASSERT_TRUE(same_bits(us(p), ref)) << p;
  }
  const BvhUnion<Slab<T>> slabs(std::vector<Slab<T>>{{T(0.5)}, {T(-0.25)}});
  EXPECT_EQ(slabs({0, 0, 1}), T(0.5));
  EXPECT_EQ(slabs.bounds(), Aabb<T>::infinite());
  const BvhUnion<Ball<T>> empty(std::vector<Ball<T>>{});
  EXPECT_EQ(empty({0, 0, 0}), std::numeric_limits<T>::infinity());
  // NaN bounds are refused by the checked constructor.
  std::vector<Ball<T>> bad = {{{0, 0, 0}, T(1)}, {{std::numeric_limits<T>::quiet_NaN(), 0, 0}, 1}};
  const auto r = BvhUnion<Ball<T>>::make(bad);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::non_finite);
}

TYPED_TEST(BvhUnionTest, ABvhOfMeshBvhsEqualsTheUnionOfBruteForceMeshes) {
  using T = TypeParam;
  std::vector<MeshSdf<T>> meshes;
  std::vector<BruteForceMeshSdf<T>> refs;
  for (int i = 0; i < 6; ++i) {
    auto soup = make_icosphere<T>(2, T(0.3)).value();
    for (auto& v : soup.vertices) v += Vec3<T>{T(0.45) * T(i), T(0.1) * T(i % 2), 0};
    meshes.push_back(MeshSdf<T>::build(soup).value());
    refs.push_back(BruteForceMeshSdf<T>::build(soup).value());
  }
  const BvhUnion<MeshSdf<T>> scene(meshes);
  for (const auto& p : test::random_points(scene.bounds().grown(T(0.5)), 1500, 12)) {
    T ref = std::numeric_limits<T>::infinity();
    for (const auto& m : refs) ref = std::min(ref, m(p));
    ASSERT_TRUE(same_bits(scene(p), ref)) << p;
  }
}

// A union of type-erased objects of mixed kinds: spheres, boxes, rotated boxes, BVH meshes, a
// signed mesh (kind known only at run time), a smooth union (bound: not prunable) and a half-space
// (unbounded). The prunable ones go in the tree; the value equals the linear union bit for bit.
TYPED_TEST(BvhUnionTest, MixedTypeErasedUnionPrunesAndEqualsTheLinearUnion) {
  using T = TypeParam;
  static_assert(BvhUnion<AnySdf<T>>::prunes);
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> c(-3, 3), r(0.05, 0.3);
  std::vector<AnySdf<T>> objects;
  std::size_t not_prunable = 0;
  for (int i = 0; i < 400; ++i) {
    const Vec3<T> at{T(c(rng)), T(c(rng)), T(c(rng))};
    switch (i % 8) {
    case 0:
    case 1:
    case 2:
      objects.emplace_back(Sphere<T>{at, T(r(rng))});
      break;
    case 3:
    case 4:
      objects.emplace_back(translate(Box<T>{Vec3<T>{T(r(rng)), T(r(rng)), T(r(rng))}}, at));
      break;
    case 5:
      objects.emplace_back(
          translate(rotate(Box<T>{Vec3<T>{T(0.3), T(0.1), T(0.05)}}, Axis::z, T(30)), at));
      break;
    case 6: {
      auto soup = make_icosphere<T>(1, T(r(rng))).value();
      for (auto& v : soup.vertices) v += at;
      if (i % 16 == 6)
        objects.emplace_back(MeshSdf<T>::build(soup).value());
      else
        objects.emplace_back(SignedMeshSdf<T>::build(soup).value()); // automatic: exact here
      break;
    }
    default:
      objects.emplace_back(smooth_unite(Sphere<T>{at, T(0.1)},
                                        Sphere<T>{at + Vec3<T>{T(0.1), 0, 0}, T(0.1)}, T(0.05)));
      ++not_prunable;
    }
  }
  objects.emplace_back(Plane<T>{Vec3<T>{0, 0, 1}, T(-5)}); // z < -5
  ++not_prunable;
  const BvhUnion<AnySdf<T>> u(objects);
  EXPECT_EQ(u.size(), objects.size());
  // only the bound (smooth) objects and the half-space are evaluated by every query
  EXPECT_EQ(u.unbounded().size(), not_prunable);
  EXPECT_EQ(u.objects().size(), objects.size() - not_prunable);
  for (const auto& p : test::random_points(Aabb<T>::of({-4, -4, -6}, {4, 4, 4}), 3000, 5)) {
    T ref = std::numeric_limits<T>::infinity();
    for (const auto& o : objects) ref = std::min(ref, o(p));
    ASSERT_TRUE(same_bits(u(p), ref)) << p << ": " << u(p) << " vs " << ref;
    ASSERT_TRUE(same_bits(u.linear(p), ref));
  }
}

// The type-erased union really prunes: one query on EBGeometry's lattice of 20^3 balls evaluates a
// few dozen of them, not all 8,000 (as it did when AnySdf reported only its static kind).
TYPED_TEST(BvhUnionTest, TypeErasedUnionEvaluatesFewObjectsPerQuery) {
  using T = TypeParam;
  const auto balls = lattice<T>(20, T(0.02));
  auto calls = std::make_shared<std::atomic<long>>(0);
  std::vector<AnySdf<T>> any;
  std::vector<CountingBall<T>> direct;
  for (const auto& b : balls) {
    any.emplace_back(CountingBall<T>{b, calls});
    direct.push_back(CountingBall<T>{b, calls});
  }
  const BvhUnion<AnySdf<T>> u(any);
  const BvhUnion<CountingBall<T>> ud(direct);
  ASSERT_TRUE(u.unbounded().empty());
  const auto pts = test::random_points(Aabb<T>::of({-1, -1, -1}, {1, 1, 1}), 200, 9);
  calls->store(0);
  for (const auto& p : pts) (void)u(p);
  const long erased = calls->load();
  calls->store(0);
  for (const auto& p : pts) (void)ud(p);
  const long typed = calls->load();
  EXPECT_EQ(erased, typed); // the same search as the statically typed union
  EXPECT_LT(double(erased) / double(pts.size()), 100.0) << erased;
}
