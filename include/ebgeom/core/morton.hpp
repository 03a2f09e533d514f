// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Morton (Z-order) codes: the one place that interleaves bits. Used by the LBVH builder
/// (`bvh::morton_code`, centroids quantised in a box) and by the grid samplers (8^3 tiles in
/// Morton order).

#include <cstdint>

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

} // namespace ebgeom
