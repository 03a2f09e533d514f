// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Sparse narrow-band grids: `sample_grid_sparse(sdf, spec, opt)` returns a `SparseGrid<T>`, the
/// 8^3 tiles the narrow band keeps (tile coordinates and 512 values each) plus one signed code per
/// tile for the rest, for resolutions where a dense array does not fit (1024^3 and beyond).

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "ebgeom/core/error.hpp"
#include "ebgeom/core/parallel.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/eval/evaluate.hpp"
#include "ebgeom/eval/grid_spec.hpp"
#include "ebgeom/eval/grid_tiles.hpp"
#include "ebgeom/sdf/concepts.hpp"

namespace ebgeom {

/// A narrow-band grid stored by 8^3 tiles (`grid_tile`). Plain data.
///
/// - `kept_tiles[b]`: tile coordinates of kept tile `b` (samples `kept_tiles[b][a] * 8 + 0..7` on
///   axis a), in Morton order; its values are `values[b * 512 + x + 8 * (y + 8 * z)]` for local
///   sample (x, y, z), each exactly what the dense `sample_grid` gives there. Local samples beyond
///   the grid's last sample (partial tiles) hold +band.
/// - `tiles`: the number of tiles on each axis, TX = ceil(NX / 8), TY, TZ;
/// - `tile_code[tx + tiles[0] * (ty + tiles[1] * tz)]`: the index b (>= 0) of a kept tile,
///   `inside` or `outside` for a tile proven farther than the band from the surface.
/// - `value(i, j, k)`: any sample; ±band in skipped tiles (`BandFill::clamp`).
///
/// Memory: 4 B per tile plus 512 values and 12 B per kept tile (`memory_bytes()`).
///
/// In 0.1, `kept_tiles` was named `blocks` and `kept_tile_count()` `block_count()`.
template <class T> struct SparseGrid {
  using scalar_type = T;
  static constexpr std::int32_t inside = -1;  ///< skipped tile, S < 0 everywhere in it
  static constexpr std::int32_t outside = -2; ///< skipped tile, S > 0 everywhere in it

  GridSpec<T> spec;
  T band = 0;
  std::array<std::size_t, 3> tiles{{0, 0, 0}}; ///< tiles per axis
  std::vector<std::array<std::uint32_t, 3>> kept_tiles;
  std::vector<T> values;
  std::vector<std::int32_t> tile_code;

  /// Number of kept tiles, M.
  std::size_t kept_tile_count() const noexcept { return kept_tiles.size(); }
  [[deprecated("SparseGrid::block_count is now kept_tile_count")]] std::size_t
  block_count() const noexcept {
    return kept_tiles.size();
  }
  /// Code of the tile holding sample (i, j, k).
  std::int32_t code(std::size_t i, std::size_t j, std::size_t k) const noexcept {
    const std::size_t W = grid_tile;
    return tile_code[i / W + tiles[0] * (j / W + tiles[1] * (k / W))];
  }
  /// Value at sample (i, j, k) (precondition: inside `spec.dims`).
  T value(std::size_t i, std::size_t j, std::size_t k) const noexcept {
    const std::size_t W = grid_tile;
    const std::int32_t c = code(i, j, k);
    if (c >= 0) return values[std::size_t(c) * W * W * W + i % W + W * (j % W + W * (k % W))];
    return c == inside ? -band : band;
  }
  /// Heap bytes held (capacity of the three arrays).
  std::size_t memory_bytes() const noexcept {
    return kept_tiles.capacity() * sizeof(kept_tiles[0]) + values.capacity() * sizeof(T) +
           tile_code.capacity() * sizeof(std::int32_t);
  }
};

/// Samples `sdf` on `spec` in a narrow band of half-width `opt.band` (> 0) and keeps only the
/// tiles the band needs (see `SparseGrid`). Kept values are bit for bit those of `sample_grid`
/// with the same options (`opt.outside` applies inside kept tiles; skipped tiles read ±band).
/// For `implicit` SDFs every tile is kept, unless they follow the split-sign protocol
/// (`has_split_sign_v`, e.g. `SignedMeshSdf` with a winding sign): then far tiles are signed by
/// proof and only tiles near the surface, or crossed far from it by a change of sign, are kept.
/// Results never depend on the thread count. Errors: `invalid_argument` for an invalid spec or a
/// band that is not finite and > 0; Allocation failure throws `std::bad_alloc` (size the grid with
/// `memory_bytes` in mind).
template <class S>
Result<SparseGrid<sdf_scalar_t<S>>>
sample_grid_sparse(const S& sdf, const GridSpec<sdf_scalar_t<S>>& spec, const GridOptions& opt) {
  EBGEOM_REQUIRE_SDF(S);
  using T = sdf_scalar_t<S>;
  constexpr std::size_t W = grid_tile;
  const GridRange all = GridRange::all(spec);
  if (auto ok = detail::check_grid_args(spec, all, opt, "sample_grid_sparse"); !ok)
    return ok.error();
  if (!(opt.band > 0))
    return make_error(ErrorCode::invalid_argument, "sample_grid_sparse: band must be > 0");

  const detail::GridFrame<T> f(spec);
  const detail::TileParams<T> prm = detail::tile_params(sdf, spec, opt);
  const bool skip = detail::skips_far_tiles(sdf, prm);
  detail::GridPlan<T> plan = detail::plan_grid(sdf, f, all, prm, skip, opt.exec);

  SparseGrid<T> g;
  g.spec = spec;
  g.band = prm.band;
  g.tiles = f.tiles;
  g.tile_code.assign(f.tiles[0] * f.tiles[1] * f.tiles[2], SparseGrid<T>::outside);
  for (const auto& s : plan.skipped) {
    const std::int32_t c = std::signbit(s.value) ? SparseGrid<T>::inside : SparseGrid<T>::outside;
    for (std::size_t k = s.a[2]; k < s.b[2]; ++k)
      for (std::size_t j = s.a[1]; j < s.b[1]; ++j)
        for (std::size_t i = s.a[0]; i < s.b[0]; ++i)
          g.tile_code[i + f.tiles[0] * (j + f.tiles[1] * k)] = c;
  }
  const std::size_t n = plan.eval.size();
  g.kept_tiles.resize(n);
  g.values.assign(n * W * W * W, prm.band);
  for (std::size_t b = 0; b < n; ++b) {
    const auto& t = plan.eval[b].tile;
    g.kept_tiles[b] = t;
    g.tile_code[t[0] + f.tiles[0] * (t[1] + f.tiles[1] * std::size_t(t[2]))] = std::int32_t(b);
  }
  std::atomic<std::size_t> done{0};
  ExecOptions ex = opt.exec;
  ex.serial_threshold = 2;
  parallel_for(
      0, n, 1,
      [&](std::size_t b, std::size_t e) {
        for (std::size_t t = b; t < e; ++t) {
          detail::eval_tile(sdf, f, plan.eval[t], prm, g.values.data() + t * W * W * W);
          const std::size_t d = done.fetch_add(1, std::memory_order_relaxed) + 1;
          if (opt.progress) opt.progress(d, n);
        }
      },
      ex);
  return g;
}

} // namespace ebgeom
