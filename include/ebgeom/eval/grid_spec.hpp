// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Grid descriptions: `GridSpec<T>` (box, samples per axis, cell- or node-centred), `GridRange`
/// (a sub-box of sample indices) and `GridOptions` (threads, narrow band, search strategy), shared
/// by the dense (`grid.hpp`) and sparse (`sparse_grid.hpp`) samplers.
///
/// Memory layout of every grid array in ebgeom: **x fastest**, then y, then z:
/// `out[i + nx * (j + ny * k)]` is the sample `(i, j, k)`. Seen as a C-order array its shape is
/// `(nz, ny, nx)` (what NumPy reads from the .npy writer).

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/error.hpp"
#include "ebgeom/core/morton.hpp"
#include "ebgeom/core/parallel.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/core/vec.hpp"

EBGEOM_BEGIN_EXACT_FP

namespace ebgeom {

/// Where the samples of a grid lie in its box.
enum class Centering : std::uint8_t {
  cell, ///< n cells per axis; samples at the cell centres lo + (i + 1/2) h, h = extent / n
  node  ///< n samples per axis including both faces: lo + i h, h = extent / (n - 1)
};

inline const char* to_string(Centering c) noexcept {
  return c == Centering::cell ? "cell" : "node";
}

/// Sample `(i, j, k)` of a grid with origin `o` and spacing `h`: `o + (i, j, k)·h`, never
/// contracted into fused multiply-adds (`EBGEOM_EXACT_KERNEL`), so every path that places samples
/// (`GridSpec::point`, the tile samplers) agrees bit for bit in `-mfma` / `-march=native` builds
/// too, where the compiler would otherwise fuse some inlined call sites and not others. One
/// out-of-line call per sample.
template <class T>
EBGEOM_EXACT_KERNEL inline Vec3<T> grid_point(const Vec3<T>& o, const Vec3<T>& h, std::size_t i,
                                              std::size_t j, std::size_t k) noexcept {
  return {o.x + T(i) * h.x, o.y + T(j) * h.y, o.z + T(k) * h.z};
}

/// A regular grid of samples over `box`. `dims` are the number of samples per axis (x, y, z).
/// Plain data; `validate()` checks it. Sample `(i, j, k)` lives at `point(i, j, k)` and at index
/// `i + nx * (j + ny * k)` of every grid array (x fastest).
template <class T> struct GridSpec {
  using scalar_type = T;
  Aabb<T> box{Vec3<T>::zero(), Vec3<T>::one()};
  std::array<std::size_t, 3> dims{{1, 1, 1}};
  Centering centering = Centering::cell;

  /// `n` cell-centred samples on every axis of `box`.
  static GridSpec cells(const Aabb<T>& box, std::size_t n) noexcept {
    return {box, {{n, n, n}}, Centering::cell};
  }

  std::size_t nx() const noexcept { return dims[0]; }
  std::size_t ny() const noexcept { return dims[1]; }
  std::size_t nz() const noexcept { return dims[2]; }
  /// Number of samples (nx * ny * nz).
  std::size_t size() const noexcept { return dims[0] * dims[1] * dims[2]; }
  /// Distance between neighbouring samples on each axis. For node centring with one sample on an
  /// axis, the box extent on that axis.
  Vec3<T> spacing() const noexcept {
    const Vec3<T> e = box.extent();
    Vec3<T> h;
    for (int a = 0; a < 3; ++a) {
      const std::size_t n = dims[a];
      const std::size_t cells = centering == Centering::cell ? n : (n > 1 ? n - 1 : 1);
      h[a] = e[a] / T(cells);
    }
    return h;
  }
  /// Position of sample (0, 0, 0).
  Vec3<T> origin() const noexcept {
    // h · 0.5 is exact, so the origin is the same whether or not the add is fused.
    return centering == Centering::cell ? box.lo + spacing() * T(0.5) : box.lo;
  }
  /// Position of sample `(i, j, k)`: `origin() + (i, j, k) * spacing()`, computed in `T`.
  Vec3<T> point(std::size_t i, std::size_t j, std::size_t k) const noexcept {
    const Vec3<T> o = origin(), h = spacing();
    return grid_point(o, h, i, j, k);
  }
  /// Array index of sample `(i, j, k)` (x fastest).
  std::size_t index(std::size_t i, std::size_t j, std::size_t k) const noexcept {
    return i + dims[0] * (j + dims[1] * k);
  }
  /// Checks: finite box (and extent) with lo < hi on every axis, 1 <= dims[a] <= 2^21, and a total
  /// size that fits in memory addressing. Errors: `invalid_argument` naming the field.
  Result<Ok> validate() const {
    for (int a = 0; a < 3; ++a) {
      if (!std::isfinite(box.lo[a]) || !std::isfinite(box.hi[a]) ||
          !std::isfinite(box.hi[a] - box.lo[a]))
        return make_error(ErrorCode::invalid_argument, "grid box is not finite (axis ", "xyz"[a],
                          ")");
      if (!(box.lo[a] < box.hi[a]))
        return make_error(ErrorCode::invalid_argument, "grid box has lo >= hi on axis ", "xyz"[a],
                          " (", box.lo[a], " >= ", box.hi[a], ")");
      if (dims[a] < 1 || dims[a] > (std::size_t(1) << 21))
        return make_error(ErrorCode::invalid_argument, "grid resolution on axis ", "xyz"[a], " is ",
                          dims[a], "; expected 1 to 2097152");
    }
    return Ok{};
  }
};

/// A box of sample indices: `lo[a] <= index < hi[a]` on each axis. Plain data. A sub-box of a
/// `GridSpec` is what a distributed code (MPI ranks, AMReX/Chombo boxes) asks one process for.
struct GridRange {
  std::array<std::size_t, 3> lo{{0, 0, 0}};
  std::array<std::size_t, 3> hi{{0, 0, 0}};

  /// Every sample of `spec`.
  template <class T> static GridRange all(const GridSpec<T>& spec) noexcept {
    return {{{0, 0, 0}}, spec.dims};
  }
  /// Samples per axis.
  std::array<std::size_t, 3> dims() const noexcept {
    return {{hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}};
  }
  std::size_t size() const noexcept {
    const auto d = dims();
    return d[0] * d[1] * d[2];
  }
  /// Index of sample `(i, j, k)` (global indices) in an array holding this range, x fastest.
  std::size_t index(std::size_t i, std::size_t j, std::size_t k) const noexcept {
    return (i - lo[0]) + (hi[0] - lo[0]) * ((j - lo[1]) + (hi[1] - lo[1]) * (k - lo[2]));
  }
  /// Checks `lo < hi <= spec.dims` on every axis. Errors: `invalid_argument`.
  template <class T> Result<Ok> validate(const GridSpec<T>& spec) const {
    for (int a = 0; a < 3; ++a)
      if (!(lo[a] < hi[a]) || hi[a] > spec.dims[a])
        return make_error(ErrorCode::invalid_argument, "grid range on axis ", "xyz"[a], " is [",
                          lo[a], ", ", hi[a], "); expected lo < hi <= ", spec.dims[a]);
    return Ok{};
  }
};

/// What a narrow-band grid stores at samples farther than the band from the surface.
enum class BandFill : std::uint8_t {
  clamp,      ///< ±band with the sign of S (as OpenVDB level sets); the default
  lower_bound ///< a value v with the sign of S and band <= |v| <= |S| (up to rounding): where S
              ///< was evaluated, S itself; in skipped boxes of tiles |S(c)| - |p - c| from the
              ///< box's centre c
};

/// How the exact values of a grid are searched for (never changes them).
enum class GridSearch : std::uint8_t {
  /// The default. SDFs with a tile evaluation (`has_lattice_eval_v`: `MeshSdf`, `SignedMeshSdf`)
  /// get one call per 8^3 tile, which shares one candidate list of BVH leaves between the tile's
  /// samples (`MeshSdf::eval_lattice`); others are evaluated per sample, as `independent`.
  tile,
  /// Every sample is searched for on its own; in a narrow band, SDFs with a bounded query
  /// (`has_bounded_query_v`) search only within the band.
  independent,
  /// Formerly seeded each sample's bounded search with its neighbour's value; it gave no gain
  /// (0.97x on the ogre mesh at 256^3) and is removed: now the same as `independent`.
  coherent [[deprecated("GridSearch::coherent is removed; it now searches as independent")]] =
      independent
};

/// Options of `sample_grid`, `sample_grid_box` and `sample_grid_sparse`.
struct GridOptions {
  /// Threads (0 = all cores). Results never depend on it.
  ExecOptions exec{};
  /// Narrow band half-width in length units; 0 (default) = dense exact everywhere. When > 0:
  /// samples with |S| <= band get the value S; the others get what `outside` says. For `exact`
  /// and `bound` SDFs an octree over the grid's tiles skips tiles proven to lie farther than
  /// `band` from the surface, so the work follows the surface area; `implicit` SDFs are evaluated
  /// everywhere.
  double band = 0;
  /// Values outside the band (ignored when `band == 0`).
  BandFill outside = BandFill::clamp;
  /// Search strategy for exact values (never changes them).
  GridSearch search = GridSearch::tile;
  /// Called after each tile with (tiles done, tile count), possibly from several threads at once:
  /// it must be thread-safe and cheap. Empty = no reporting.
  std::function<void(std::size_t, std::size_t)> progress;
};

namespace detail {
/// 63-bit Morton code of three 21-bit coordinates (x in the lowest bit); `morton_encode`.
inline std::uint64_t morton3(std::uint32_t x, std::uint32_t y, std::uint32_t z) noexcept {
  return morton_encode(x, y, z);
}
} // namespace detail

/// Side of the tiles grid samplers process and sparse grids store (samples per axis).
inline constexpr std::size_t grid_tile = 8;

} // namespace ebgeom

EBGEOM_END_EXACT_FP
