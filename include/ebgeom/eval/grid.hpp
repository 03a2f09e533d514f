// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Dense SDF grids: `sample_grid(sdf, spec, out, GridOptions)` fills a dense array with S at every
/// sample of a `GridSpec`, and `sample_grid_box` fills any sub-box (`GridRange`) of it with the
/// same values (for MPI ranks and AMReX/Chombo boxes). Work goes by 8^3 tiles in Morton order,
/// threads over tiles. SDFs with a bounded query search a narrow band only within the band; a
/// narrow band skips, through an octree over the tiles, every box of tiles proven farther than the
/// band from the surface (see `grid_tiles.hpp`).
///
/// Memory layout of every grid array in ebgeom: **x fastest**, then y, then z:
/// `out[i + nx * (j + ny * k)]` is the sample `(i, j, k)`. Seen as a C-order array its shape is
/// `(nz, ny, nx)` (what NumPy reads from the .npy writer).

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
#include "ebgeom/core/vec.hpp"
#include "ebgeom/eval/evaluate.hpp"
#include "ebgeom/eval/grid_spec.hpp"
#include "ebgeom/eval/grid_tiles.hpp"
#include "ebgeom/sdf/concepts.hpp"

namespace ebgeom {

/// Fills `out` (x fastest within `range`: `out[range.index(i, j, k)]`) with the values of the
/// samples of `range`, a sub-box of `spec`: exactly the values `sample_grid` gives those samples
/// on the whole grid, for any thread count.
///
/// - Dense (`opt.band == 0`): `out[...] = sdf(spec.point(i, j, k))`, bit for bit.
/// - Narrow band (`opt.band > 0`): samples with |S| <= band get S bit for bit; the others get
///   `opt.outside` (±band by default) with the sign of S. For `exact` and `bound` SDFs, tiles
///   proven farther than the band are not evaluated, so the work follows the surface area; so
///   are they for `implicit` SDFs with a split sign (`has_split_sign_v`: `SignedMeshSdf` with a
///   winding sign), whose far tiles are signed by proof, each sample as the dense grid signs it.
///   Far samples' signs are decided from their neighbours when the band is at least the sample
///   spacing (exact for closed surfaces; a sign is the same as per-point evaluation's wherever
///   S's sign is well defined, i.e. not for open meshes).
///
/// Work: tiles intersecting `range` are evaluated whole (a sub-box costs up to one tile more per
/// face). SDFs with a batch `eval` get one call per tile where no bounded query applies.
/// Thread-safe for a const `sdf`; `opt.progress` runs once per tile.
/// Errors: `invalid_argument` for an invalid `spec` or `range`, a negative or non-finite band, or
/// `out.size() != range.size()`.
template <class S>
Result<Ok> sample_grid_box(const S& sdf, const GridSpec<sdf_scalar_t<S>>& spec,
                           const GridRange& range, Span<sdf_scalar_t<S>> out,
                           const GridOptions& opt = {}) {
  EBGEOM_REQUIRE_SDF(S);
  using T = sdf_scalar_t<S>;
  constexpr std::size_t W = grid_tile;
  if (auto ok = detail::check_grid_args(spec, range, opt, "sample_grid"); !ok) return ok;
  if (out.size() != range.size())
    return make_error(ErrorCode::invalid_argument, "sample_grid: the range has ", range.size(),
                      " samples but the output holds ", out.size());

  const detail::GridFrame<T> f(spec);
  const detail::TileParams<T> prm = detail::tile_params(sdf, spec, opt);
  const bool skip = detail::skips_far_tiles(sdf, prm);
  detail::GridPlan<T> plan = detail::plan_grid(sdf, f, range, prm, skip, opt.exec);
  // Skipped boxes of tiles become fill jobs, one per tile, so threads share them evenly.
  for (const auto& s : plan.skipped)
    for (std::size_t k = s.a[2]; k < s.b[2]; ++k)
      for (std::size_t j = s.a[1]; j < s.b[1]; ++j)
        for (std::size_t i = s.a[0]; i < s.b[0]; ++i) {
          detail::TileJob<T> job;
          job.tile = {{std::uint32_t(i), std::uint32_t(j), std::uint32_t(k)}};
          job.fill = true;
          job.has_centre = true;
          job.value = s.value;
          job.centre = s.centre;
          plan.eval.push_back(job);
        }
  std::vector<typename detail::GridPlan<T>::Skipped>().swap(plan.skipped);

  std::atomic<std::size_t> done{0};
  const std::size_t total = plan.eval.size();
  ExecOptions ex = opt.exec;
  ex.serial_threshold = 2; // a tile is already a lot of work
  parallel_for(
      0, total, 1,
      [&](std::size_t b, std::size_t e) {
        T vals[W * W * W];
        for (std::size_t t = b; t < e; ++t) {
          const detail::TileJob<T>& job = plan.eval[t];
          std::array<std::size_t, 3> lo, hi;
          for (int a = 0; a < 3; ++a) {
            lo[a] = std::max<std::size_t>(job.tile[a] * W, range.lo[a]);
            hi[a] = std::min<std::size_t>(job.tile[a] * W + W, range.hi[a]);
          }
          if (job.fill) {
            for (std::size_t k = lo[2]; k < hi[2]; ++k)
              for (std::size_t j = lo[1]; j < hi[1]; ++j)
                for (std::size_t i = lo[0]; i < hi[0]; ++i)
                  out[range.index(i, j, k)] =
                      detail::far_value(prm, job.value, norm(f.point(i, j, k) - job.centre));
          } else {
            detail::eval_tile(sdf, f, job, prm, vals);
            const std::size_t i0 = job.tile[0] * W, j0 = job.tile[1] * W, k0 = job.tile[2] * W;
            for (std::size_t k = lo[2]; k < hi[2]; ++k)
              for (std::size_t j = lo[1]; j < hi[1]; ++j)
                for (std::size_t i = lo[0]; i < hi[0]; ++i)
                  out[range.index(i, j, k)] = vals[(i - i0) + W * ((j - j0) + W * (k - k0))];
          }
          const std::size_t d = done.fetch_add(1, std::memory_order_relaxed) + 1;
          if (opt.progress) opt.progress(d, total);
        }
      },
      ex);
  return Ok{};
}

/// Fills `out` (x fastest, see the file comment) with S at every sample of `spec`:
/// `sample_grid_box` over the whole grid. Dense: `out[spec.index(i, j, k)] =
/// sdf(spec.point(i, j, k))` bit for bit, for any thread count; with `opt.band > 0`, see
/// `GridOptions::band`. Errors: `invalid_argument` for an invalid `spec`, a negative or
/// non-finite band, or `out.size() != spec.size()`.
template <class S>
Result<Ok> sample_grid(const S& sdf, const GridSpec<sdf_scalar_t<S>>& spec,
                       Span<sdf_scalar_t<S>> out, const GridOptions& opt = {}) {
  EBGEOM_REQUIRE_SDF(S);
  if (auto ok = spec.validate(); !ok) return ok;
  if (out.size() != spec.size())
    return make_error(ErrorCode::invalid_argument, "sample_grid: the grid has ", spec.size(),
                      " samples but the output holds ", out.size());
  return sample_grid_box(sdf, spec, GridRange::all(spec), out, opt);
}

} // namespace ebgeom
