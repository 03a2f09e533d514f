// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// The shared grid job of `ebgeom sdf` and `ebgeom demo`: sample an SDF on a dense grid (or a
// sparse narrow band) with a progress bar, then write the grid and an optional PNG slice.

#include <cmath>
#include <cstdint>
#include <limits>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "common.hpp"
#include "ebgeom/eval/grid.hpp"
#include "ebgeom/eval/sparse_grid.hpp"
#include "ebgeom/eval/write_grid.hpp"
#include "png_slice.hpp"
#include "progress.hpp"

namespace ebgeom::cli {

/// Summary statistics of a grid.
struct GridStats {
  double min = 0, max = 0, inside_fraction = 0;
  std::uint64_t non_finite = 0; ///< NaN or infinite samples (left out of min and max)
};

template <class T> GridStats grid_stats(Span<const T> v) {
  GridStats s;
  s.min = std::numeric_limits<double>::infinity();
  s.max = -s.min;
  std::size_t inside = 0;
  for (T x : v) {
    if (!std::isfinite(x)) {
      ++s.non_finite;
      continue;
    }
    s.min = std::min(s.min, double(x));
    s.max = std::max(s.max, double(x));
    inside += x < 0;
  }
  s.inside_fraction = v.empty() ? 0 : double(inside) / double(v.size());
  return s;
}

/// The same statistics over every sample of a sparse grid: a skipped tile counts its samples
/// (those inside the grid) as -band (inside) or +band; the padding of partial tiles is left out.
/// Equal to `grid_stats` of the dense grid the band gives.
template <class T> GridStats grid_stats(const SparseGrid<T>& g) {
  constexpr std::size_t W = grid_tile;
  GridStats s;
  s.min = std::numeric_limits<double>::infinity();
  s.max = -s.min;
  std::uint64_t inside = 0;
  const auto& d = g.spec.dims;
  for (std::size_t tz = 0; tz < g.tiles[2]; ++tz)
    for (std::size_t ty = 0; ty < g.tiles[1]; ++ty)
      for (std::size_t tx = 0; tx < g.tiles[0]; ++tx) {
        const std::size_t sx = std::min(W, d[0] - tx * W), sy = std::min(W, d[1] - ty * W),
                          sz = std::min(W, d[2] - tz * W);
        const std::int32_t c = g.tile_code[tx + g.tiles[0] * (ty + g.tiles[1] * tz)];
        if (c < 0) {
          const double v = c == SparseGrid<T>::inside ? -double(g.band) : double(g.band);
          s.min = std::min(s.min, v);
          s.max = std::max(s.max, v);
          inside += c == SparseGrid<T>::inside ? std::uint64_t(sx * sy * sz) : 0;
          continue;
        }
        const T* t = g.values.data() + std::size_t(c) * W * W * W;
        for (std::size_t z = 0; z < sz; ++z)
          for (std::size_t y = 0; y < sy; ++y)
            for (std::size_t x = 0; x < sx; ++x) {
              const T val = t[x + W * (y + W * z)];
              if (!std::isfinite(val)) {
                ++s.non_finite;
                continue;
              }
              s.min = std::min(s.min, double(val));
              s.max = std::max(s.max, double(val));
              inside += val < 0;
            }
      }
  const std::size_t n = g.spec.size();
  s.inside_fraction = n == 0 ? 0 : double(inside) / double(n);
  return s;
}

/// Samples `sdf` on `spec` (throws CliError on failure), showing a progress bar if `progress`.
template <class S>
std::vector<sdf_scalar_t<S>> sample_with_progress(const S& sdf,
                                                  const GridSpec<sdf_scalar_t<S>>& spec,
                                                  GridOptions opt, bool progress) {
  using T = sdf_scalar_t<S>;
  std::vector<T> values(spec.size());
  Progress bar("sampling", progress);
  if (bar.enabled()) opt.progress = [&bar](std::size_t d, std::size_t t) { bar.update(d, t); };
  auto ok = sample_grid(sdf, spec, Span<T>(values), opt);
  bar.finish();
  if (!ok) fail(exit_failure, ok.error().what());
  return values;
}

/// Samples `sdf` on `spec` in the band `opt.band` (> 0) keeping only the tiles the band needs
/// (`sample_grid_sparse`), with a progress bar if `progress`. Throws CliError on failure
/// (`exit_resource` when the kept tiles do not fit in memory).
template <class S>
SparseGrid<sdf_scalar_t<S>> sample_sparse_with_progress(const S& sdf,
                                                        const GridSpec<sdf_scalar_t<S>>& spec,
                                                        GridOptions opt, bool progress) {
  Progress bar("sampling", progress);
  if (bar.enabled()) opt.progress = [&bar](std::size_t d, std::size_t t) { bar.update(d, t); };
  try {
    auto g = sample_grid_sparse(sdf, spec, opt);
    bar.finish();
    if (!g) fail(exit_failure, g.error().what());
    return std::move(*g);
  } catch (const std::bad_alloc&) {
    bar.finish();
    fail(exit_resource, "the tiles of the narrow band do not fit in memory (" +
                            human_bytes(available_memory_bytes()) +
                            " available); lower the resolution (--res/--dx), narrow --band or "
                            "shrink --box");
  }
}

/// Writes `values` to `path` by extension; throws CliError (output) on failure.
template <class T>
void write_grid_or_fail(const std::string& path, const GridSpec<T>& spec, Span<const T> values,
                        DType dtype) {
  WriteGridOptions w;
  w.dtype = dtype;
  auto ok = write_grid(path, spec, values, w);
  if (!ok)
    fail(ok.error().code == ErrorCode::unsupported ? exit_usage : exit_output, ok.error().what());
}

} // namespace ebgeom::cli
