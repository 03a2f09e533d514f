// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Internal: triangle strips to triangles (PLY `tristrips`, VTK `TRIANGLE_STRIPS`).

#include <cstdint>
#include <utility>
#include <vector>

#include "ebgeom/mesh/polygon_soup.hpp"

namespace ebgeom::io::detail {

/// Appends the triangles of strip `s`: (s0 s1 s2), (s2 s1 s3), (s2 s3 s4), ... (every second
/// triangle flipped so all share the first one's orientation). Triangles with a repeated vertex
/// (used to stitch strips together) are dropped. Returns the number of triangles appended.
template <class T> std::uint64_t append_strip(PolygonSoup<T>& soup, const std::vector<Index>& s) {
  std::uint64_t n = 0;
  for (std::size_t i = 2; i < s.size(); ++i) {
    Index a = s[i - 2], b = s[i - 1];
    const Index c = s[i];
    if (i % 2 == 1) std::swap(a, b);
    if (a == b || b == c || a == c) continue;
    soup.add_triangle(a, b, c);
    ++n;
  }
  return n;
}

} // namespace ebgeom::io::detail
