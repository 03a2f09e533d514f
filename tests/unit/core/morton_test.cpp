// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/core/morton.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

using namespace ebgeom;

namespace {
// Reference: interleave bit by bit (bit i of x goes to bit 3i, of y to 3i + 1, of z to 3i + 2).
std::uint64_t interleave_reference(std::uint64_t x, std::uint64_t y, std::uint64_t z) {
  std::uint64_t code = 0;
  for (int i = 0; i < 21; ++i) {
    code |= ((x >> i) & 1u) << (3 * i);
    code |= ((y >> i) & 1u) << (3 * i + 1);
    code |= ((z >> i) & 1u) << (3 * i + 2);
  }
  return code;
}
} // namespace

TEST(Morton, UnitAxesAndTheLargestCode) {
  EXPECT_EQ(morton_encode(0, 0, 0), 0u);
  EXPECT_EQ(morton_encode(1, 0, 0), 1u);
  EXPECT_EQ(morton_encode(0, 1, 0), 2u);
  EXPECT_EQ(morton_encode(0, 0, 1), 4u);
  EXPECT_EQ(morton_encode(0x1fffff, 0x1fffff, 0x1fffff), (std::uint64_t(1) << 63) - 1);
  EXPECT_EQ(morton_spread_21(0x1fffff), 0x1249249249249249ULL);
}

TEST(Morton, EqualsBitByBitInterleavingAndIgnoresHighBits) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 10000; ++i) {
    const std::uint64_t x = rng() & 0x1fffff, y = rng() & 0x1fffff, z = rng() & 0x1fffff;
    ASSERT_EQ(morton_encode(x, y, z), interleave_reference(x, y, z)) << x << " " << y << " " << z;
    ASSERT_EQ(morton_encode(x | (rng() << 21), y, z), morton_encode(x, y, z));
  }
}

namespace {
// Reference Morton order: each finite point's cell (1024 per axis over the finite points' box, in
// double) interleaved bit by bit, a stable sort by that key; non-finite points last, in input
// order.
template <class T>
std::vector<std::uint32_t> morton_order_reference(const std::vector<Vec3<T>>& p) {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (const auto& q : p)
    if (all_finite(q))
      for (int k = 0; k < 3; ++k)
        lo[k] = std::min(lo[k], double(q[k])), hi[k] = std::max(hi[k], double(q[k]));
  std::vector<std::uint64_t> key(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!all_finite(p[i])) {
      key[i] = ~std::uint64_t(0);
      continue;
    }
    std::uint64_t c[3];
    for (int k = 0; k < 3; ++k) {
      const double e = hi[k] - lo[k];
      const double f = e > 0 ? (double(p[i][k]) - lo[k]) * (1024.0 / e) : 0.0;
      c[k] = std::uint64_t(std::min(std::max(f, 0.0), 1023.0));
    }
    key[i] = interleave_reference(c[0], c[1], c[2]);
  }
  std::vector<std::uint32_t> order(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) order[i] = std::uint32_t(i);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });
  return order;
}

template <class T> void expect_reference_order(const std::vector<Vec3<T>>& p) {
  std::vector<std::uint32_t> order;
  std::vector<std::uint64_t> scratch;
  morton_order(Span<const Vec3<T>>(p), order, scratch);
  EXPECT_EQ(order, morton_order_reference(p));
}
} // namespace

TEST(Morton, OrderOfPointsIsAStableSortByCellCode) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-3, 7);
  std::vector<Vec3<double>> pd;
  std::vector<Vec3<float>> pf;
  for (int i = 0; i < 5000; ++i) {
    pd.push_back({u(rng), u(rng), u(rng)});
    pf.push_back({float(u(rng)), float(u(rng)), float(u(rng))});
  }
  expect_reference_order(pd);
  expect_reference_order(pf);
  // Repeated points (one cell: input order), a flat axis, clusters, empty, one point.
  std::vector<Vec3<double>> same(300, Vec3<double>{1, 2, 3});
  expect_reference_order(same);
  std::vector<Vec3<double>> flat;
  for (int i = 0; i < 2000; ++i) flat.push_back({u(rng), 4.0, u(rng) * 1e-6});
  expect_reference_order(flat);
  std::vector<Vec3<float>> clusters;
  for (int i = 0; i < 2000; ++i)
    clusters.push_back({float(i % 3) * 100.f + float(u(rng)) * 1e-3f, float(u(rng)) * 1e-3f, 0.f});
  expect_reference_order(clusters);
  expect_reference_order(std::vector<Vec3<double>>{});
  expect_reference_order(std::vector<Vec3<double>>{{1, 2, 3}});
}

TEST(Morton, OrderPutsNonFinitePointsLastInInputOrder) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Vec3<double>> p = {{nan, 0, 0}, {1, 1, 1}, {0, inf, 0}, {0, 0, 0}, {-inf, 0, nan}};
  std::vector<std::uint32_t> order;
  std::vector<std::uint64_t> scratch;
  morton_order(Span<const Vec3<double>>(p), order, scratch);
  EXPECT_EQ(order, (std::vector<std::uint32_t>{3, 1, 0, 2, 4}));
  expect_reference_order(p);
  std::vector<Vec3<double>> only_nan(3, Vec3<double>{nan, nan, nan});
  morton_order(Span<const Vec3<double>>(only_nan), order, scratch);
  EXPECT_EQ(order, (std::vector<std::uint32_t>{0, 1, 2}));
}
