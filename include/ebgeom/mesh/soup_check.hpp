// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `check_soup`: the structural checks every mesh builder runs before it dereferences anything in a
/// `PolygonSoup` (well-formed offsets, faces of at least 3 corners, indices in range, finite
/// coordinates). For the full diagnostic report see mesh/validate.hpp.

#include <cstddef>

#include "ebgeom/core/error.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"

namespace ebgeom {

/// Returns an `Error` with `code == ErrorCode::ok` when `soup` is structurally usable, otherwise
/// the first problem found, checked in this order: `size_mismatch` (offsets not starting at 0,
/// not non-decreasing, or not ending at `indices.size()`), `empty` (no faces), `bad_index` (a
/// corner >= vertex count), `non_finite` (a NaN/Inf coordinate of a vertex), `degenerate` (a face
/// with fewer than 3 corners; reported last, so a caller may accept it knowing the rest passed).
/// Never reads out of range. O(V + corners).
template <class T> Error check_soup(const PolygonSoup<T>& soup) {
  if (soup.offsets.empty() || soup.offsets.front() != 0)
    return make_error(ErrorCode::size_mismatch, "polygon soup offsets must start with 0");
  if (soup.offsets.back() != soup.indices.size())
    return make_error(ErrorCode::size_mismatch, "polygon soup offsets end at ", soup.offsets.back(),
                      " but there are ", soup.indices.size(), " indices");
  if (soup.offsets.size() < 2) return make_error(ErrorCode::empty, "polygon soup has no faces");
  for (std::size_t f = 0; f + 1 < soup.offsets.size(); ++f)
    if (soup.offsets[f + 1] < soup.offsets[f])
      return make_error(ErrorCode::size_mismatch, "polygon soup offsets decrease at face ", f);
  // Offsets are now non-decreasing and end at indices.size(): every corner below is in range.
  const std::size_t nv = soup.vertices.size();
  for (std::size_t f = 0; f + 1 < soup.offsets.size(); ++f)
    for (std::size_t i = soup.offsets[f]; i < soup.offsets[f + 1]; ++i)
      if (soup.indices[i] >= nv)
        return make_error(ErrorCode::bad_index, "face ", f, ": vertex index ", soup.indices[i],
                          " >= vertex count ", nv);
  for (std::size_t v = 0; v < nv; ++v)
    if (!all_finite(soup.vertices[v]))
      return make_error(ErrorCode::non_finite, "vertex ", v, " has a NaN/Inf coordinate");
  // Last, so that a caller accepting short faces knows everything else was checked.
  for (std::size_t f = 0; f + 1 < soup.offsets.size(); ++f)
    if (soup.offsets[f + 1] - soup.offsets[f] < 3)
      return make_error(ErrorCode::degenerate, "face ", f, " has ",
                        soup.offsets[f + 1] - soup.offsets[f], " corners (at least 3 needed)");
  return Error{};
}

} // namespace ebgeom
