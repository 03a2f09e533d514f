#pragma once
/// \file
/// Dense SDF grids: `GridSpec<T>` (box, samples per axis, cell- or node-centred) and
/// `sample_grid(sdf, spec, out, GridOptions)`, which fills a dense array with S at every sample,
/// threading over 8^3 tiles visited in Morton order. Optional narrow band: exact values where
/// |S| <= band, ±band (correct sign) elsewhere, skipping whole tiles that lie outside the band.
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
#include <functional>
#include <limits>
#include <vector>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/error.hpp"
#include "ebgeom/core/parallel.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/eval/evaluate.hpp"
#include "ebgeom/sdf/concepts.hpp"

namespace ebgeom {

/// Where the samples of a grid lie in its box.
enum class Centering : std::uint8_t {
  cell, ///< n cells per axis; samples at the cell centres lo + (i + 1/2) h, h = extent / n
  node  ///< n samples per axis including both faces: lo + i h, h = extent / (n - 1)
};

inline const char* to_string(Centering c) noexcept {
  return c == Centering::cell ? "cell" : "node";
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
    return centering == Centering::cell ? box.lo + spacing() * T(0.5) : box.lo;
  }
  /// Position of sample `(i, j, k)`: `origin() + (i, j, k) * spacing()`, computed in `T`.
  Vec3<T> point(std::size_t i, std::size_t j, std::size_t k) const noexcept {
    const Vec3<T> o = origin(), h = spacing();
    return {o.x + T(i) * h.x, o.y + T(j) * h.y, o.z + T(k) * h.z};
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

/// Options of `sample_grid`.
struct GridOptions {
  /// Threads (0 = all cores). Results never depend on it.
  ExecOptions exec{};
  /// Narrow band half-width in length units; 0 (default) = dense exact everywhere. When > 0:
  /// samples with |S| <= band get the value S; the others get ±band with the sign of S (clamped,
  /// as OpenVDB level sets). Tiles proven to lie farther than `band` from the surface are filled
  /// without evaluating each sample (legal for `exact` and `bound` SDFs; `implicit` ones are
  /// evaluated everywhere and clamped).
  double band = 0;
  /// Called after each tile with (tiles done, tile count), possibly from several threads at once:
  /// it must be thread-safe and cheap. Empty = no reporting.
  std::function<void(std::size_t, std::size_t)> progress;
};

namespace detail {
inline std::uint64_t spread_bits3(std::uint64_t v) noexcept {
  v &= 0x1fffff; // 21 bits
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}
/// 63-bit Morton code of three 21-bit coordinates (x in the lowest bit).
inline std::uint64_t morton3(std::uint32_t x, std::uint32_t y, std::uint32_t z) noexcept {
  return spread_bits3(x) | spread_bits3(y) << 1 | spread_bits3(z) << 2;
}
} // namespace detail

/// Side of the tiles `sample_grid` processes (samples per axis).
inline constexpr std::size_t grid_tile = 8;

/// Fills `out` (x fastest, see the file comment) with S at every sample of `spec`:
/// `out[spec.index(i, j, k)] = sdf(spec.point(i, j, k))`, bit for bit the same as evaluating each
/// point on its own, for any thread count. With `opt.band > 0`, see `GridOptions::band`.
/// Work: 8^3 tiles in Morton order (neighbouring tiles stay in cache), threads over tiles; SDFs
/// with a batch `eval` member get one call per tile row batch. Thread-safe for a const `sdf`.
/// Errors: `invalid_argument` for an invalid `spec`, a negative or non-finite band, or
/// `out.size() != spec.size()`.
template <class S>
Result<Ok> sample_grid(const S& sdf, const GridSpec<sdf_scalar_t<S>>& spec,
                       Span<sdf_scalar_t<S>> out, const GridOptions& opt = {}) {
  EBGEOM_REQUIRE_SDF(S);
  using T = sdf_scalar_t<S>;
  if (auto ok = spec.validate(); !ok) return ok;
  if (out.size() != spec.size())
    return make_error(ErrorCode::invalid_argument, "sample_grid: the grid has ", spec.size(),
                      " samples but the output holds ", out.size());
  if (!(opt.band >= 0) || !std::isfinite(opt.band))
    return make_error(ErrorCode::invalid_argument, "sample_grid: band must be finite and >= 0");

  constexpr std::size_t W = grid_tile;
  const std::size_t nx = spec.nx(), ny = spec.ny(), nz = spec.nz();
  const std::size_t tx = (nx + W - 1) / W, ty = (ny + W - 1) / W, tz = (nz + W - 1) / W;
  std::vector<std::array<std::uint32_t, 3>> coords;
  coords.reserve(tx * ty * tz);
  for (std::size_t k = 0; k < tz; ++k)
    for (std::size_t j = 0; j < ty; ++j)
      for (std::size_t i = 0; i < tx; ++i)
        coords.push_back({std::uint32_t(i), std::uint32_t(j), std::uint32_t(k)});
  std::sort(coords.begin(), coords.end(), [](const auto& a, const auto& b) {
    return detail::morton3(a[0], a[1], a[2]) < detail::morton3(b[0], b[1], b[2]);
  });

  const Vec3<T> o = spec.origin(), h = spec.spacing();
  const T band = T(opt.band);
  const bool use_band = opt.band > 0;
  const bool can_skip = use_band && kind_of(sdf) != SdfKind::implicit;
  std::atomic<std::size_t> done{0};
  const std::size_t total = coords.size();

  parallel_for(
      0, coords.size(), 1,
      [&](std::size_t b, std::size_t e) {
        Vec3<T> pts[W * W * W];
        T vals[W * W * W];
        for (std::size_t t = b; t < e; ++t) {
          const std::size_t i0 = coords[t][0] * W, j0 = coords[t][1] * W, k0 = coords[t][2] * W;
          const std::size_t i1 = std::min(nx, i0 + W), j1 = std::min(ny, j0 + W),
                            k1 = std::min(nz, k0 + W);
          bool filled = false;
          if (can_skip) {
            // The tile's samples lie in the box [p(i0,j0,k0), p(i1-1,j1-1,k1-1)]. S is
            // 1-Lipschitz with |S| <= distance, so |S(c)| > r + band proves every sample is
            // farther than band from the surface, on the side of sign(S(c)).
            const Vec3<T> a{o.x + T(i0) * h.x, o.y + T(j0) * h.y, o.z + T(k0) * h.z};
            const Vec3<T> c{o.x + T(i1 - 1) * h.x, o.y + T(j1 - 1) * h.y, o.z + T(k1 - 1) * h.z};
            const Vec3<T> mid = (a + c) * T(0.5);
            const T r = norm(c - a) * T(0.5);
            const T v = sdf(mid);
            const T margin = (r + band) * (T(1) + T(64) * std::numeric_limits<T>::epsilon());
            if (std::abs(v) > margin) {
              const T fill = std::copysign(band, v);
              for (std::size_t k = k0; k < k1; ++k)
                for (std::size_t j = j0; j < j1; ++j)
                  for (std::size_t i = i0; i < i1; ++i) out[spec.index(i, j, k)] = fill;
              filled = true;
            }
          }
          if (!filled) {
            if constexpr (has_batch_eval_v<S>) {
              std::size_t n = 0;
              for (std::size_t k = k0; k < k1; ++k)
                for (std::size_t j = j0; j < j1; ++j)
                  for (std::size_t i = i0; i < i1; ++i)
                    pts[n++] = {o.x + T(i) * h.x, o.y + T(j) * h.y, o.z + T(k) * h.z};
              sdf.eval(Span<const Vec3<T>>(pts, n), Span<T>(vals, n));
              n = 0;
              for (std::size_t k = k0; k < k1; ++k)
                for (std::size_t j = j0; j < j1; ++j)
                  for (std::size_t i = i0; i < i1; ++i) out[spec.index(i, j, k)] = vals[n++];
            } else {
              for (std::size_t k = k0; k < k1; ++k)
                for (std::size_t j = j0; j < j1; ++j)
                  for (std::size_t i = i0; i < i1; ++i)
                    out[spec.index(i, j, k)] =
                        sdf(Vec3<T>{o.x + T(i) * h.x, o.y + T(j) * h.y, o.z + T(k) * h.z});
            }
            if (use_band) {
              for (std::size_t k = k0; k < k1; ++k)
                for (std::size_t j = j0; j < j1; ++j)
                  for (std::size_t i = i0; i < i1; ++i) {
                    T& v = out[spec.index(i, j, k)];
                    if (std::abs(v) > band) v = std::copysign(band, v);
                  }
            }
          }
          const std::size_t d = done.fetch_add(1, std::memory_order_relaxed) + 1;
          if (opt.progress) opt.progress(d, total);
        }
      },
      [&] {
        ExecOptions e = opt.exec;
        e.serial_threshold = 2; // a tile is already a lot of work
        return e;
      }());
  return Ok{};
}

} // namespace ebgeom
