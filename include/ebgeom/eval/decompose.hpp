// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Brick decomposition of a `GridSpec` into P parts, for distributed sampling (MPI ranks, or any
/// code that hands sub-boxes to `sample_grid_box`). Pure C++, no MPI: every process computes the
/// same decomposition from the same inputs.
///
/// - `BrickLayout`: the grid's samples cut into bricks of `brick` samples per axis (a multiple of
///   the 8^3 sampling tile, so no tile is evaluated by two parts); the last brick of an axis may
///   be smaller.
/// - `estimate_brick_work`: a coarse work estimate per brick. Dense grids cost the same per
///   sample; narrow bands cost little away from the surface, so one SDF value at each brick's
///   centre decides whether the brick may meet the band (1-Lipschitz test, as the samplers' own
///   octree uses).
/// - `decompose`: recursive coordinate bisection (RCB) of the brick grid by weight into P boxes,
///   one `GridRange` per part, so each part is one box (one VTK piece, one MPI-IO subarray).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <tuple>
#include <vector>

#include "ebgeom/core/parallel.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/eval/evaluate.hpp"
#include "ebgeom/eval/grid_spec.hpp"
#include "ebgeom/sdf/concepts.hpp"

namespace ebgeom {

/// The samples of a grid cut into bricks. Brick `(bi, bj, bk)` holds samples
/// `[b * brick, min((b + 1) * brick, dims))` on each axis; its linear index is
/// `bi + counts[0] * (bj + counts[1] * bk)`. Plain data.
struct BrickLayout {
  std::array<std::size_t, 3> dims{{1, 1, 1}};   ///< samples of the grid per axis
  std::array<std::size_t, 3> brick{{8, 8, 8}};  ///< samples of a brick per axis
  std::array<std::size_t, 3> counts{{1, 1, 1}}; ///< bricks per axis

  /// Bricks of `brick` samples per axis over `dims` (every entry >= 1).
  static BrickLayout of(const std::array<std::size_t, 3>& dims,
                        const std::array<std::size_t, 3>& brick) noexcept {
    BrickLayout l;
    l.dims = dims;
    l.brick = brick;
    for (int a = 0; a < 3; ++a) l.counts[a] = (dims[a] + brick[a] - 1) / brick[a];
    return l;
  }
  /// Number of bricks.
  std::size_t size() const noexcept { return counts[0] * counts[1] * counts[2]; }
  /// Samples of the box of bricks `[blo, bhi)` (brick indices), clipped to the grid.
  GridRange range(const std::array<std::size_t, 3>& blo,
                  const std::array<std::size_t, 3>& bhi) const noexcept {
    GridRange r;
    for (int a = 0; a < 3; ++a) {
      r.lo[a] = std::min(blo[a] * brick[a], dims[a]);
      r.hi[a] = std::min(bhi[a] * brick[a], dims[a]);
    }
    return r;
  }
  /// Samples of brick `b` (linear index).
  GridRange brick_range(std::size_t b) const noexcept {
    const std::array<std::size_t, 3> c{
        {b % counts[0], (b / counts[0]) % counts[1], b / (counts[0] * counts[1])}};
    return range(c, {{c[0] + 1, c[1] + 1, c[2] + 1}});
  }
};

/// Options of `make_brick_layout`.
struct BrickOptions {
  /// At most this many bricks: the brick side grows (in steps of `grid_tile`) until it fits.
  std::size_t max_bricks = std::size_t(1) << 18;
  /// Smallest brick side in samples; rounded up to a multiple of `grid_tile`.
  std::size_t min_side = grid_tile;
};

/// Cubic bricks whose side is the smallest multiple of `grid_tile` (and at least `opt.min_side`)
/// giving at most `opt.max_bricks` bricks. O(log) in the grid size.
template <class T>
BrickLayout make_brick_layout(const GridSpec<T>& spec, const BrickOptions& opt = {}) noexcept {
  std::size_t side = std::max<std::size_t>(grid_tile, opt.min_side);
  side = (side + grid_tile - 1) / grid_tile * grid_tile;
  const std::size_t cap = std::max<std::size_t>(1, opt.max_bricks);
  for (;;) {
    const BrickLayout l = BrickLayout::of(spec.dims, {{side, side, side}});
    if (l.size() <= cap) return l;
    side += grid_tile;
  }
}

/// Options of `estimate_brick_work`.
struct BrickWorkOptions {
  /// Narrow band half-width (length units) as in `GridOptions::band`; 0 = dense (every sample
  /// costs 1, no SDF evaluation).
  double band = 0;
  /// Relative cost of a sample in a brick proven farther than the band (filled, not searched).
  double far_cost = 0.02;
  ExecOptions exec{};
};

/// Writes the estimated work of bricks `[first, first + out.size())` of `layout` to `out`: the
/// brick's sample count, times `opt.far_cost` when the band is positive and
/// |S(c)| > band + r (c the centre of the brick's samples, r its half-diagonal, inflated by
/// 64 ulps): no sample of the brick can then be within the band, since S is 1-Lipschitz (true of
/// `exact` and `bound` SDFs; `implicit` SDFs get the dense estimate). One SDF evaluation per
/// brick when the band is positive, threaded over bricks; none otherwise. Deterministic.
template <class S>
void estimate_brick_work(const S& sdf, const GridSpec<sdf_scalar_t<S>>& spec,
                         const BrickLayout& layout, std::size_t first, Span<double> out,
                         const BrickWorkOptions& opt = {}) {
  using T = sdf_scalar_t<S>;
  const bool band = opt.band > 0 && kind_of(sdf) != SdfKind::implicit;
  const Vec3<T> o = spec.origin(), h = spec.spacing();
  ExecOptions ex = opt.exec;
  ex.serial_threshold = 64;
  parallel_for(
      0, out.size(), 16,
      [&](std::size_t b, std::size_t e) {
        for (std::size_t t = b; t < e; ++t) {
          const GridRange r = layout.brick_range(first + t);
          const double n = double(r.size());
          if (!band) {
            out[t] = n;
            continue;
          }
          Vec3<T> c;
          double r2 = 0;
          for (int a = 0; a < 3; ++a) {
            const double lo = double(o[a]) + double(r.lo[a]) * double(h[a]);
            const double hi = double(o[a]) + double(r.hi[a] - 1) * double(h[a]);
            c[a] = T(0.5 * (lo + hi));
            r2 += 0.25 * (hi - lo) * (hi - lo);
          }
          const double s = std::abs(double(sdf(c)));
          const double reach =
              (opt.band + std::sqrt(r2)) * (1 + 64 * double(std::numeric_limits<T>::epsilon())) +
              double(max_component(h));
          out[t] = s > reach ? n * opt.far_cost : n;
        }
      },
      ex);
}

/// One part of a decomposition: a box of bricks (`bricks_lo`/`bricks_hi`, brick indices), its
/// samples (`range`; empty when the part got no brick) and its estimated work.
struct DecompositionPart {
  std::array<std::size_t, 3> bricks_lo{{0, 0, 0}}, bricks_hi{{0, 0, 0}};
  GridRange range{};
  double work = 0;
  bool empty() const noexcept { return range.size() == 0; }
};

/// P parts of a brick layout. `imbalance()` is max(work) / mean(work) (1 = perfect).
struct Decomposition {
  BrickLayout layout;
  std::vector<DecompositionPart> parts;

  double imbalance() const noexcept {
    double mx = 0, sum = 0;
    for (const auto& p : parts) {
      mx = std::max(mx, p.work);
      sum += p.work;
    }
    return sum > 0 ? mx * double(parts.size()) / sum : 1.0;
  }
};

namespace detail {

struct RcbBox {
  std::array<std::size_t, 3> lo, hi;
  std::size_t volume() const noexcept {
    return (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
  }
};

inline void rcb(const BrickLayout& l, Span<const double> w, const RcbBox& box, std::size_t p0,
                std::size_t np, std::vector<DecompositionPart>& parts) {
  auto weight_of = [&](std::size_t b) { return w.empty() ? 1.0 : w[b]; };
  if (np == 1 || box.volume() <= 1) {
    // One part takes the box; any others (more parts than bricks) stay empty.
    DecompositionPart& p = parts[p0];
    p.bricks_lo = box.lo;
    p.bricks_hi = box.hi;
    p.range = l.range(box.lo, box.hi);
    p.work = 0;
    for (std::size_t k = box.lo[2]; k < box.hi[2]; ++k)
      for (std::size_t j = box.lo[1]; j < box.hi[1]; ++j)
        for (std::size_t i = box.lo[0]; i < box.hi[0]; ++i)
          p.work += weight_of(i + l.counts[0] * (j + l.counts[1] * k));
    return;
  }
  // Best cut over all axes and part counts n1 | np - n1 (n1 near np times the left side's share
  // of the work, or np / 2): minimise the larger per-part work of the two sides, preferring cuts
  // that leave each side at least as many bricks as parts, then balanced volume, then the axis
  // with the most samples (squarer boxes, smaller pieces' surfaces).
  struct Cut {
    int axis = -1;
    std::size_t at = 0, n1 = 0;
    bool feasible = false;
    double cost = 0, vcost = 0;
    std::size_t extent = 0;
  } best;
  auto key = [](const Cut& x) {
    return std::make_tuple(!x.feasible, x.cost, x.vcost, std::size_t(0) - x.extent, x.n1);
  };
  for (int a = 0; a < 3; ++a) {
    const std::size_t len = box.hi[a] - box.lo[a];
    if (len < 2) continue;
    std::vector<double> slab(len, 0.0);
    for (std::size_t k = box.lo[2]; k < box.hi[2]; ++k)
      for (std::size_t j = box.lo[1]; j < box.hi[1]; ++j)
        for (std::size_t i = box.lo[0]; i < box.hi[0]; ++i) {
          const std::array<std::size_t, 3> c{{i, j, k}};
          slab[c[a] - box.lo[a]] += weight_of(i + l.counts[0] * (j + l.counts[1] * k));
        }
    double total = 0;
    for (double s : slab) total += s;
    const std::size_t cross = box.volume() / len;
    const std::size_t extent = std::min(box.hi[a] * l.brick[a], l.dims[a]) - box.lo[a] * l.brick[a];
    double left = 0;
    for (std::size_t c = 1; c < len; ++c) {
      left += slab[c - 1];
      const double share = total > 0 ? left / total : double(c) / double(len);
      const double ideal = share * double(np);
      const std::size_t tries[3] = {np / 2, std::size_t(std::floor(ideal)),
                                    std::size_t(std::ceil(ideal))};
      for (std::size_t n1 : tries) {
        n1 = std::min(std::max<std::size_t>(n1, 1), np - 1);
        const std::size_t n2 = np - n1;
        Cut cut;
        cut.axis = a;
        cut.at = box.lo[a] + c;
        cut.n1 = n1;
        cut.feasible = c * cross >= n1 && (len - c) * cross >= n2;
        cut.cost = std::max(left / double(n1), (total - left) / double(n2));
        cut.vcost = std::max(double(c) / double(n1), double(len - c) / double(n2)) * double(cross);
        cut.extent = extent;
        if (best.axis < 0 || key(cut) < key(best)) best = cut;
      }
    }
  }
  RcbBox left = box, right = box;
  left.hi[best.axis] = best.at;
  right.lo[best.axis] = best.at;
  rcb(l, w, left, p0, best.n1, parts);
  rcb(l, w, right, p0 + best.n1, np - best.n1, parts);
}

} // namespace detail

/// Splits `layout` into `parts` boxes of bricks by recursive coordinate bisection: each step cuts
/// a box in two (at a brick boundary, on the axis and plane, and with the share of the parts,
/// that best balance the work per part, `weights` summed) and recurses, so every part is one box.
/// `weights` holds one non-negative value per brick (linear index), or is empty for equal weights.
/// Parts beyond the brick count are empty. Deterministic: the same inputs give the same parts on
/// every process. O(bricks * 3 * log2(parts)). Precondition: `parts >= 1`, `weights` empty or
/// `layout.size()` long.
inline Decomposition decompose(const BrickLayout& layout, std::size_t parts,
                               Span<const double> weights = {}) {
  Decomposition d;
  d.layout = layout;
  d.parts.resize(std::max<std::size_t>(parts, 1));
  detail::RcbBox all{{{0, 0, 0}}, layout.counts};
  detail::rcb(layout, weights, all, 0, d.parts.size(), d.parts);
  return d;
}

} // namespace ebgeom
