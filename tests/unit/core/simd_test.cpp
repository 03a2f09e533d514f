// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// The lane masks, lane minimum and lane square roots of core/simd.hpp against scalar comparisons,
// scans and std::sqrt.
#include "ebgeom/core/simd.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "test_support.hpp"

using namespace ebgeom;

template <class T> class SimdTest : public ::testing::Test {};
TYPED_TEST_SUITE(SimdTest, test::FloatTypes);

namespace {
/// `lane_min` against a scalar scan: the minimum and every lane equal to it.
template <class T, int W> void lane_min_matches_a_scan(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> pick(0, 7);
  const T nan = std::numeric_limits<T>::quiet_NaN();
  const T inf = std::numeric_limits<T>::infinity();
  for (int round = 0; round < 300; ++round) {
    T v[W];
    for (int l = 0; l < W; ++l) v[l] = T(pick(rng)); // few values: many ties
    if (round % 7 == 0) v[round % W] = inf;
    if (round % 11 == 0 && W > 1) v[(round / 11) % W] = nan; // a NaN lane never wins
    T want = std::numeric_limits<T>::infinity();
    for (int l = 0; l < W; ++l)
      if (v[l] < want) want = v[l];
    const LaneMin<T, W> got = lane_min<T, W>(v);
    ASSERT_EQ(got.min, want) << "W " << W;
    for (int l = 0; l < W; ++l) // a NaN lane counts as +inf
      ASSERT_EQ(((got.mask >> l) & 1) != 0, (std::isnan(v[l]) ? inf : v[l]) == want)
          << "W " << W << " lane " << l;
  }
}

/// `detail::lane_mask` (vector compares where the target has them) against the C++ comparisons.
template <class T, int W> void lane_mask_matches_the_comparisons(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> pick(0, 5);
  const T special[4] = {std::numeric_limits<T>::quiet_NaN(), std::numeric_limits<T>::infinity(),
                        T(-0.0), T(0)};
  for (int round = 0; round < 300; ++round) {
    T v[W];
    for (int l = 0; l < W; ++l) v[l] = T(pick(rng));
    v[round % W] = special[round % 4];
    const T b = round % 9 == 0 ? T(0) : T(pick(rng)) + (round % 2 ? T(0) : T(0.5));
    const LaneMask<W> le = detail::lane_mask<detail::LaneCmp::le>(v, b);
    const LaneMask<W> eq = detail::lane_mask<detail::LaneCmp::eq>(v, b);
    for (int l = 0; l < W; ++l) {
      ASSERT_EQ(((le >> l) & 1) != 0, v[l] <= b) << "W " << W << " lane " << l;
      ASSERT_EQ(((eq >> l) & 1) != 0, v[l] == b) << "W " << W << " lane " << l;
    }
  }
}
} // namespace

namespace {
/// `lane_sqrt` on instruction set I (vector square roots where it has them) against `std::sqrt`,
/// bit for bit: zeros of both signs, infinity, NaN, subnormals and random magnitudes.
template <class T, int W, Isa I> void lane_sqrt_matches_std_sqrt(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> mant(1, 2);
  std::uniform_int_distribution<int> expo(-60, 60);
  const T special[6] = {T(0),
                        T(-0.0),
                        std::numeric_limits<T>::infinity(),
                        std::numeric_limits<T>::quiet_NaN(),
                        std::numeric_limits<T>::denorm_min(),
                        std::numeric_limits<T>::min()};
  for (int round = 0; round < 200; ++round) {
    T v[W], got[W];
    for (int l = 0; l < W; ++l) v[l] = T(std::ldexp(mant(rng), expo(rng)));
    v[round % W] = special[round % 6];
    detail::lane_sqrt<I>(v, got);
    for (int l = 0; l < W; ++l) {
      const T want = std::sqrt(v[l]);
      ASSERT_TRUE(std::isnan(want) ? std::isnan(got[l])
                                   : std::memcmp(&got[l], &want, sizeof(T)) == 0)
          << "W " << W << " isa " << int(I) << " v " << v[l];
    }
  }
}

template <class T, Isa I> void lane_sqrt_matches_on(std::mt19937_64& rng) {
  lane_sqrt_matches_std_sqrt<T, 1, I>(rng);
  lane_sqrt_matches_std_sqrt<T, 4, I>(rng);
  lane_sqrt_matches_std_sqrt<T, 8, I>(rng);
  lane_sqrt_matches_std_sqrt<T, 16, I>(rng);
  lane_sqrt_matches_std_sqrt<T, 24, I>(rng); // several registers, not a power of two
  lane_sqrt_matches_std_sqrt<T, 5, I>(rng);  // no whole register: the plain loop
}
} // namespace

TYPED_TEST(SimdTest, LaneSqrtEqualsStdSqrtOnEveryInstructionSet) {
  std::mt19937_64 rng(12);
  lane_sqrt_matches_on<TypeParam, Isa::baseline>(rng);
  lane_sqrt_matches_on<TypeParam, native_isa>(rng);
  if (int(detected_isa()) >= int(Isa::avx2)) lane_sqrt_matches_on<TypeParam, Isa::avx2>(rng);
  if (int(detected_isa()) >= int(Isa::avx512)) lane_sqrt_matches_on<TypeParam, Isa::avx512>(rng);
}

TYPED_TEST(SimdTest, LaneMaskEqualsTheScalarComparisons) {
  std::mt19937_64 rng(10);
  lane_mask_matches_the_comparisons<TypeParam, 1>(rng);
  lane_mask_matches_the_comparisons<TypeParam, 4>(rng);
  lane_mask_matches_the_comparisons<TypeParam, 8>(rng);
  lane_mask_matches_the_comparisons<TypeParam, 16>(rng);
  lane_mask_matches_the_comparisons<TypeParam, 24>(rng); // several registers, not a power of two
  lane_mask_matches_the_comparisons<TypeParam, 33>(rng);
  lane_mask_matches_the_comparisons<TypeParam, 64>(rng); // 64-bit mask
}

TYPED_TEST(SimdTest, LaneMinIsTheMinimumAndTheLanesAtIt) {
  std::mt19937_64 rng(9);
  lane_min_matches_a_scan<TypeParam, 1>(rng);
  lane_min_matches_a_scan<TypeParam, 4>(rng);
  lane_min_matches_a_scan<TypeParam, 5>(rng); // not a power of two
  lane_min_matches_a_scan<TypeParam, 8>(rng);
  lane_min_matches_a_scan<TypeParam, 16>(rng);
  lane_min_matches_a_scan<TypeParam, 33>(rng); // 64-bit mask
  lane_min_matches_a_scan<TypeParam, 64>(rng);
}
