// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/sdf/any_sdf.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "ebgeom/eval/evaluate.hpp"
#include "ebgeom/sdf/csg.hpp"
#include "ebgeom/sdf/shapes.hpp"
#include "ebgeom/sdf/transforms.hpp"
#include "test_support.hpp"

using namespace ebgeom;

template <class T> class AnySdfTest : public ::testing::Test {};
TYPED_TEST_SUITE(AnySdfTest, test::FloatTypes);

static_assert(is_sdf_v<AnySdf<float>> && is_sdf_v<AnySdf<double>>);
static_assert(AnySdf<double>::kind == SdfKind::implicit);
static_assert(has_batch_eval_v<AnySdf<double>>);
static_assert(std::is_copy_constructible_v<AnySdf<float>>);
static_assert(!std::is_constructible_v<AnySdf<double>, int>);

namespace {
template <class T> Vec3<T> v3(double x, double y, double z) { return {T(x), T(y), T(z)}; }
} // namespace

TYPED_TEST(AnySdfTest, EqualsTheWrappedShape) {
  using T = TypeParam;
  const auto shape =
      subtract(smooth_unite(Sphere<T>{Vec3<T>::zero(), T(1)},
                            Capsule<T>{Vec3<T>::zero(), v3<T>(2, 0, 0), T(0.3)}, T(0.1)),
               translate(Box<T>{v3<T>(0.5, 0.5, 0.5)}, v3<T>(0, 0, 1)));
  const AnySdf<T> any(shape);
  const AnySdf<T> copy = any; // shares the model
  const auto pts = test::random_points(Aabb<T>::of(v3<T>(-2, -2, -2), v3<T>(3, 2, 2)), 1000);
  std::vector<T> out(pts.size(), T(-99));
  any.eval(pts, out);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    EXPECT_EQ(out[i], shape(pts[i]));
    EXPECT_EQ(any(pts[i]), shape(pts[i]));
    EXPECT_EQ(copy(pts[i]), shape(pts[i]));
  }
  EXPECT_EQ(any.bounds(), shape.bounds());
  EXPECT_EQ(any.dynamic_kind(), SdfKind::bound);
  EXPECT_EQ(AnySdf<T>(Sphere<T>{Vec3<T>::zero(), T(1)}).dynamic_kind(), SdfKind::exact);
  EXPECT_EQ(kind_of(any), SdfKind::bound);

  // a short output span: only that many values are written, nothing past it
  std::vector<T> shorter(10, T(-99));
  any.eval(pts, Span<T>(shorter.data(), 5));
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(shorter[i], shape(pts[i]));
  for (std::size_t i = 5; i < 10; ++i) EXPECT_EQ(shorter[i], T(-99));

  // the batch evaluator takes the batch path and gives the same values
  std::vector<T> via(pts.size());
  ASSERT_TRUE(evaluate(any, Span<const Vec3<T>>(pts), Span<T>(via), ExecOptions{}).has_value());
  for (std::size_t i = 0; i < pts.size(); ++i) EXPECT_EQ(via[i], out[i]);

  // AnySdf composes like any SDF (and can wrap itself)
  const AnySdf<T> nested(unite(any, Sphere<T>{v3<T>(5, 0, 0), T(1)}));
  EXPECT_EQ(nested(v3<T>(5, 0, 0)), T(-1));
  EXPECT_EQ(nested(pts[3]), std::min(shape(pts[3]), norm(pts[3] - v3<T>(5, 0, 0)) - T(1)));
}
