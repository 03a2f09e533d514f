// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Morton (Z-order) codes: the one place that interleaves bits. Used by the LBVH builder
/// (`bvh::morton_code`, centroids quantised in a box), by the grid samplers (8^3 tiles in
/// Morton order) and by batch queries that visit their points in space order (`morton_order`).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"

namespace ebgeom {

/// Spreads the low 21 bits of `v` to every third bit (bit i goes to bit 3i). O(1).
inline std::uint64_t morton_spread_21(std::uint64_t v) noexcept {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

/// 63-bit Morton code of three 21-bit coordinates, x in the lowest bit (bits above 21 are
/// ignored). O(1).
inline std::uint64_t morton_encode(std::uint64_t x, std::uint64_t y, std::uint64_t z) noexcept {
  return morton_spread_21(x) | morton_spread_21(y) << 1 | morton_spread_21(z) << 2;
}

/// The permutation that sorts `pts` in Morton order: `order[k]` is the index of the k-th point
/// along a Z-order curve through the points' bounding box, quantised to 1024 cells per axis
/// (points of the same cell keep their input order; points with a NaN or infinite coordinate come
/// last, in input order). Precondition: `pts.size() < 2^32`. O(N): an LSD radix sort (three
/// passes of 10 bits) of (key, index) pairs; `order` is resized to N and `scratch` receives
/// 2 N 64-bit words of working memory (both reused across calls: no allocation when their
/// capacities suffice). Deterministic.
template <class T>
void morton_order(Span<const Vec3<T>> pts, std::vector<std::uint32_t>& order,
                  std::vector<std::uint64_t>& scratch) {
  const std::size_t n = pts.size();
  order.resize(n);
  if (n == 0) return;
  T lo[3], hi[3];
  for (int k = 0; k < 3; ++k) lo[k] = std::numeric_limits<T>::infinity(), hi[k] = -lo[k];
  for (std::size_t i = 0; i < n; ++i)
    if (all_finite(pts[i]))
      for (int k = 0; k < 3; ++k) {
        lo[k] = pts[i][k] < lo[k] ? pts[i][k] : lo[k];
        hi[k] = pts[i][k] > hi[k] ? pts[i][k] : hi[k];
      }
  // Cells per unit length, in double (a float box's extent may overflow in float); 0 on a flat or
  // empty axis.
  constexpr int bits = 10;
  constexpr std::uint64_t cells = std::uint64_t(1) << bits;
  double scale[3];
  for (int k = 0; k < 3; ++k) {
    const double e = double(hi[k]) - double(lo[k]);
    scale[k] = e > 0 && std::isfinite(e) ? double(cells) / e : 0.0;
  }
  scratch.resize(2 * n);
  std::uint64_t* a = scratch.data();
  std::uint64_t* b = a + n;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t key = std::uint64_t(1) << (3 * bits); // after every finite point's key
    if (all_finite(pts[i])) {
      std::uint64_t c[3];
      for (int k = 0; k < 3; ++k) {
        const double f = (double(pts[i][k]) - double(lo[k])) * scale[k];
        c[k] = f >= double(cells - 1) ? cells - 1 : std::uint64_t(f > 0 ? f : 0.0);
      }
      key = morton_encode(c[0], c[1], c[2]);
    }
    a[i] = key << 32 | std::uint64_t(i);
  }
  // Keys have 3 * bits + 1 bits, above the index: passes over bits [32, 42), [42, 52), [52, 63).
  for (int pass = 0; pass < 3; ++pass) {
    const int shift = 32 + pass * bits;
    const int width = pass == 2 ? bits + 1 : bits;
    const std::uint64_t mask = (std::uint64_t(1) << width) - 1;
    std::uint32_t count[(std::size_t(1) << (bits + 1)) + 1] = {}; // n < 2^32
    for (std::size_t i = 0; i < n; ++i) ++count[((a[i] >> shift) & mask) + 1];
    for (std::size_t d = 1; d <= mask + 1; ++d) count[d] += count[d - 1];
    for (std::size_t i = 0; i < n; ++i) b[count[(a[i] >> shift) & mask]++] = a[i];
    std::swap(a, b);
  }
  for (std::size_t i = 0; i < n; ++i) order[i] = std::uint32_t(a[i] & 0xffffffffu);
}

} // namespace ebgeom
