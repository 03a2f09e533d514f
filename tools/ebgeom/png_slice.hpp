// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// PNG slice of a grid (dense, or any with a value per sample): a diverging colour map (blue inside,
// red outside, white at zero), faint distance bands, the zero level set in black, a scale bar and
// a colour bar. No text is drawn: the legend (colour scale, slice position, scale bar length) is
// in the PNG's tEXt chunks and in `PngInfo` (for --json). Written with libpng.

#include <cmath>
#include <string>
#include <vector>

#include "ebgeom/core/span.hpp"
#include "ebgeom/eval/grid.hpp"

namespace ebgeom::cli {

/// Which plane to draw: the axis normal to it (0 = x, 1 = y, 2 = z) and where along it, as a
/// fraction of the box (0 = lo face, 1 = hi face).
struct SliceSpec {
  int axis = 2;
  double fraction = 0.5;
};

/// Parses `x`, `y`, `z`, optionally followed by `=FRACTION` (0..1). Throws CliError (usage).
SliceSpec parse_slice(const std::string& text);

/// A 2D slice of sample values, `u` fastest; rows go along `v`.
struct SliceData {
  std::size_t width = 0, height = 0; // samples along u and v
  double du = 1, dv = 1;             // sample spacings
  std::vector<double> values;
  char axis_name = 'z';
  double plane = 0; // coordinate of the plane
  std::size_t plane_index = 0, plane_count = 1;
};

/// The written image: its size and its legend.
struct PngInfo {
  int width = 0, height = 0;
  double inside_scale = 0;  ///< |S| at the left end of the colour bar (full blue)
  double outside_scale = 0; ///< S at the right end (full red)
  double scale_bar = 0;     ///< length of the scale bar, in the input's units
  int scale_bar_pixels = 0;
  char axis = 'z'; ///< the slice: axis, coordinate, 0-based plane index of plane_count
  double plane = 0;
  std::size_t plane_index = 0, plane_count = 1;
};

/// Renders and writes `slice` to `path` (atomically). Throws CliError (output) on failure.
PngInfo write_png_slice(const std::string& path, const SliceData& slice);

/// Extracts the plane chosen by `where` from a grid whose sample (i, j, k) is `at(i, j, k)`.
template <class T, class At>
SliceData extract_slice_of(const GridSpec<T>& spec, const At& at, const SliceSpec& where) {
  SliceData s;
  const int a = where.axis;
  const int ua = a == 0 ? 1 : 0, va = a == 2 ? 1 : 2;
  const Vec3<T> o = spec.origin(), h = spec.spacing();
  const double pos = double(spec.box.lo[a]) + where.fraction * double(spec.box.extent()[a]);
  long idx = std::lround((pos - double(o[a])) / double(h[a]));
  idx = std::max(0L, std::min(long(spec.dims[a]) - 1, idx));
  s.width = spec.dims[ua];
  s.height = spec.dims[va];
  s.du = double(h[ua]);
  s.dv = double(h[va]);
  s.axis_name = "xyz"[a];
  s.plane_index = std::size_t(idx);
  s.plane_count = spec.dims[a];
  s.plane = double(o[a]) + double(idx) * double(h[a]);
  s.values.resize(s.width * s.height);
  for (std::size_t v = 0; v < s.height; ++v)
    for (std::size_t u = 0; u < s.width; ++u) {
      std::size_t ijk[3];
      ijk[a] = std::size_t(idx);
      ijk[ua] = u;
      ijk[va] = v;
      s.values[v * s.width + u] = double(at(ijk[0], ijk[1], ijk[2]));
    }
  return s;
}

/// Extracts the plane chosen by `where` from a dense grid (layout: x fastest).
template <class T>
SliceData extract_slice(const GridSpec<T>& spec, Span<const T> values, const SliceSpec& where) {
  return extract_slice_of(
      spec,
      [&](std::size_t i, std::size_t j, std::size_t k) { return values[spec.index(i, j, k)]; },
      where);
}

} // namespace ebgeom::cli
