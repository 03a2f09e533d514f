// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// The engine behind `sample_grid`, `sample_grid_box` and `sample_grid_sparse` (no stability
/// promise: users call those). Two parts:
///
/// - `detail::plan_grid`: which 8^3 tiles to evaluate. Dense: every tile of the range. Narrow band
///   (exact or bound SDFs): an `Octree` over tile indices, built breadth-first with the levels
///   decided in parallel. A node evaluates S at the centre c of its samples' box (radius r) and is
///   dropped when |S(c)| > (r + band) (1 + 64 eps): S is 1-Lipschitz with |S| <= distance, so every
///   sample is farther than the band, on the side of sign S(c). Surviving nodes split down to
///   single tiles. Nodes are aligned to the whole grid's tiles, so a sub-range makes the same
///   decisions as the full grid. Leaves come out in Morton order (octant order, depth first).
/// - `detail::eval_tile`: the values of one tile. Dense, with `GridSearch::tile` (the default),
///   SDFs with a tile evaluation (`has_lattice_eval_v`) get one `eval_lattice` call. With a
///   bounded query (`has_bounded_query_v`), each sample's search in a band is bounded by the band;
///   samples the band search proves far get their sign from a neighbour inside the tile (a far
///   sample's ball of radius > band >= spacing holds no surface, so its axis neighbours share its
///   sign) or, failing that, from one full query.
/// - SDFs with a split sign (`has_split_sign_v`, e.g. `SignedMeshSdf` with a winding sign) whose
///   kind is `implicit` (signs must not be propagated: a winding sign also changes across the
///   surfaces that fill holes, far from the mesh) are planned with the unsigned distance and
///   signed by proof: a node proven far (as above, with |S| = d) whose samples' box gets a sign
///   from `sign_over` is skipped with it. A far single tile with no such sign is split into
///   octants (4^3, 2^3) whose boxes are tried in turn, and the samples left get `sign_at`: a tile
///   of one sign is skipped, one holding both (where w = 1/2 crosses far from the mesh) is kept,
///   with signs only. Kept tiles search distances within the band (`unsigned_within`) and sign
///   their samples the same way. Every sample's sign is the one `sign_at` gives it, so a banded
///   grid is the dense grid clamped, sign included.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/eval/evaluate.hpp"
#include "ebgeom/eval/grid_spec.hpp"
#include "ebgeom/octree/octree.hpp"
#include "ebgeom/sdf/concepts.hpp"
#include "ebgeom/sdf/split_sign.hpp"

EBGEOM_BEGIN_EXACT_FP

namespace ebgeom::detail {

/// Sample positions exactly as `GridSpec::point` computes them, plus tile counts.
template <class T> struct GridFrame {
  Vec3<T> o, h;
  std::array<std::size_t, 3> n, tiles;

  explicit GridFrame(const GridSpec<T>& s) noexcept : o(s.origin()), h(s.spacing()), n(s.dims) {
    for (int a = 0; a < 3; ++a) tiles[a] = (n[a] + grid_tile - 1) / grid_tile;
  }
  Vec3<T> point(std::size_t i, std::size_t j, std::size_t k) const noexcept {
    return grid_point(o, h, i, j, k);
  }
  /// Samples [lo, hi) of tiles [a, b) (clipped to the grid).
  void sample_range(const std::array<std::size_t, 3>& a, const std::array<std::size_t, 3>& b,
                    std::array<std::size_t, 3>& lo, std::array<std::size_t, 3>& hi) const noexcept {
    for (int d = 0; d < 3; ++d) {
      lo[d] = a[d] * grid_tile;
      hi[d] = std::min(n[d], b[d] * grid_tile);
    }
  }
};

/// Relative slack applied to Lipschitz bounds so rounding never turns a valid bound invalid.
template <class T> constexpr T lipschitz_slack() noexcept {
  return T(64) * std::numeric_limits<T>::epsilon();
}

/// One tile to evaluate (`fill == false`) or to fill from a skipped node's centre value.
template <class T> struct TileJob {
  std::array<std::uint32_t, 3> tile{};
  bool fill = false;
  bool has_centre = false; ///< `value`, `centre` hold S at the centre of an enclosing node
  bool sign_only = false;  ///< every sample is farther than the band: only signs are needed
  T value = 0;
  Vec3<T> centre{};
};

/// The tiles of a grid range: jobs in Morton order, plus skipped octree nodes (boxes of tiles).
template <class T> struct GridPlan {
  struct Skipped {
    std::array<std::size_t, 3> a, b; ///< tiles [a, b), clipped to the range's tiles
    T value;                         ///< S at `centre`; |value| > r + band
    Vec3<T> centre;
  };
  std::vector<TileJob<T>> eval;
  std::vector<Skipped> skipped;
};

/// Per-sample parameters of `eval_tile`.
template <class T> struct TileParams {
  T band = 0; ///< 0 = dense
  BandFill outside = BandFill::clamp;
  bool tile = false;          ///< dense values through `eval_lattice` (see `GridSearch::tile`)
  bool can_propagate = false; ///< band >= the largest spacing: far samples share neighbours' signs
  bool split = false; ///< split-sign SDF of kind `implicit`: signs by proof (see the file comment)
};

/// Value written at a sample proven (from a node's centre) farther than the band.
template <class T>
inline T far_value(const TileParams<T>& prm, T centre_value, T centre_dist) noexcept {
  if (prm.outside == BandFill::clamp) return std::copysign(prm.band, centre_value);
  const T eps = lipschitz_slack<T>();
  const T lb = (std::abs(centre_value) - centre_dist * (T(1) + eps)) * (T(1) - eps);
  return std::copysign(std::max(prm.band, lb), centre_value);
}

/// Value written at an evaluated sample in banded mode.
template <class T> inline T band_value(const TileParams<T>& prm, T v) noexcept {
  if (prm.outside == BandFill::clamp && std::abs(v) > prm.band) return std::copysign(prm.band, v);
  return v;
}

/// Gathers the `s[0]·s[1]·s[2]` lattice points of the tile at `o` (x fastest), evaluates them all
/// with one `eval(points, values)` call and scatters the values into `vals` (stride 8 per axis).
template <class T, class Eval>
void eval_packed(const GridFrame<T>& f, const std::array<std::size_t, 3>& o,
                 const std::array<std::size_t, 3>& s, T* vals, Eval&& eval) {
  constexpr std::size_t W = grid_tile;
  Vec3<T> pts[W * W * W];
  T tmp[W * W * W];
  std::size_t n = 0;
  for (std::size_t z = 0; z < s[2]; ++z)
    for (std::size_t y = 0; y < s[1]; ++y)
      for (std::size_t x = 0; x < s[0]; ++x) pts[n++] = f.point(o[0] + x, o[1] + y, o[2] + z);
  eval(Span<const Vec3<T>>(pts, n), Span<T>(tmp, n));
  n = 0;
  for (std::size_t z = 0; z < s[2]; ++z)
    for (std::size_t y = 0; y < s[1]; ++y)
      for (std::size_t x = 0; x < s[0]; ++x) vals[x + W * (y + W * z)] = tmp[n++];
}

/// Signs of the samples [lo, hi) (local indices in the tile whose first sample is `base`, stride
/// 8 per axis) that `sign_over` proves over boxes: the box of samples [lo, hi) first, then its
/// octants, down to boxes of 2 samples per side. Samples left `unknown` need `sign_at`. A box is
/// tried only when `dist(lo, hi)` (a lower bound on its samples' distances to the surface)
/// exceeds its diagonal: closer boxes rarely get a proof (the bounds grow like (radius /
/// distance)²) and their octants are tried anyway (on the bunny at 256³, fewer failed proofs and
/// less time than trying from half the diagonal on).
/// Boxes of fewer than `min_samples` samples are not tried; `gate` scales the diagonal (boxes
/// are tried when `dist(lo, hi)` > gate × diagonal); `try_box` false starts at the octants.
/// `sign_box(box)` proves a box's sign (`sign_over`, or a `SignScope`'s).
template <class T, class SignBox, class Dist>
void prove_signs(SignBox&& sign_box, const GridFrame<T>& f, const std::array<std::size_t, 3>& base,
                 const std::array<std::size_t, 3>& lo, const std::array<std::size_t, 3>& hi,
                 Sign* sg, Dist&& dist, std::size_t min_samples = 2, double gate = 1,
                 bool try_box = true) {
  constexpr std::size_t W = grid_tile;
  if ((hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]) < min_samples) return;
  const Vec3<T> p0 = f.point(base[0] + lo[0], base[1] + lo[1], base[2] + lo[2]);
  const Vec3<T> p1 = f.point(base[0] + hi[0] - 1, base[1] + hi[1] - 1, base[2] + hi[2] - 1);
  if (try_box && dist(lo, hi) > norm(p1 - p0) * T(gate)) {
    const Sign s = sign_box(Aabb<T>{p0, p1});
    if (s != Sign::unknown) {
      for (std::size_t z = lo[2]; z < hi[2]; ++z)
        for (std::size_t y = lo[1]; y < hi[1]; ++y)
          for (std::size_t x = lo[0]; x < hi[0]; ++x) sg[x + W * (y + W * z)] = s;
      return;
    }
  }
  std::array<std::size_t, 3> mid;
  for (int a = 0; a < 3; ++a) mid[a] = lo[a] + (hi[a] - lo[a] + 1) / 2;
  for (int o = 0; o < 8; ++o) {
    std::array<std::size_t, 3> a, b;
    bool empty = false;
    for (int ax = 0; ax < 3; ++ax) {
      const bool upper = (o >> ax) & 1;
      a[ax] = upper ? mid[ax] : lo[ax];
      b[ax] = upper ? hi[ax] : mid[ax];
      empty = empty || a[ax] >= b[ax];
    }
    if (!empty) prove_signs(sign_box, f, base, a, b, sg, dist, min_samples, gate);
  }
}

/// Calls `fn(sign_box)` with `sign_box(box)` = the sign `sdf` proves over a box inside the tile
/// at `base` (`size` samples per axis): a `SignScope` of the tile's box where the SDF has one
/// (made at the first box tried, shared by the others), else `sign_over`.
template <class S, class Fn>
void with_tile_signer(const S& sdf, const GridFrame<sdf_scalar_t<S>>& f,
                      const std::array<std::size_t, 3>& base,
                      const std::array<std::size_t, 3>& size, Fn&& fn) {
  using T = sdf_scalar_t<S>;
  if constexpr (has_sign_scope_v<S>) {
    const Vec3<T> p0 = f.point(base[0], base[1], base[2]);
    const Vec3<T> p1 = f.point(base[0] + size[0] - 1, base[1] + size[1] - 1, base[2] + size[2] - 1);
    typename S::SignScope scope;
    bool made = false;
    fn([&](const Aabb<T>& box) {
      if (!made) sdf.sign_scope(Aabb<T>{p0, p1}, scope), made = true;
      return scope.sign_over(box);
    });
  } else {
    fn([&](const Aabb<T>& box) { return sdf.sign_over(box); });
  }
}

/// With a batch sign (`has_batch_sign_v`): `sg[l] = sign_at(sample l)` for the samples of the tile
/// at `base` (local indices, stride 8; `size` samples per axis) whose sign is `unknown` and that
/// `want(l)` selects, in one `signs_at` call over groups of 4x4x2 neighbours (packets of nearby
/// samples). Without one, nothing.
template <class S, class Want>
void batch_signs(const S& sdf, const GridFrame<sdf_scalar_t<S>>& f,
                 const std::array<std::size_t, 3>& base, const std::array<std::size_t, 3>& size,
                 Sign* sg, Want&& want) {
  if constexpr (has_batch_sign_v<S>) {
    using T = sdf_scalar_t<S>;
    constexpr std::size_t W = grid_tile;
    Vec3<T> pts[W * W * W];
    Sign got[W * W * W];
    std::uint16_t idx[W * W * W];
    std::size_t m = 0;
    for_each_in_sign_groups(size, [&](std::size_t x, std::size_t y, std::size_t z) {
      const std::size_t l = x + W * (y + W * z);
      if (sg[l] != Sign::unknown || !want(l)) return;
      idx[m] = static_cast<std::uint16_t>(l);
      pts[m++] = f.point(base[0] + x, base[1] + y, base[2] + z);
    });
    sdf.signs_at(Span<const Vec3<T>>(pts, m), Span<Sign>(got, m));
    for (std::size_t i = 0; i < m; ++i) sg[idx[i]] = got[i];
  }
}

/// The sign every sample of the tile `tile` gets from `sign_at` when it is one sign, else
/// `unknown`; `far` is a lower bound on the samples' distances. Proofs first (`prove_signs`),
/// then `sign_at` per remaining sample, stopping at the first disagreement. With a batch sign,
/// proofs only over boxes of at least 9 samples and the samples left in one batch (as
/// `eval_split_tile`: the packets cost less than the proofs over boxes of 2x2x2 samples).
template <class S>
Sign tile_sign(const S& sdf, const GridFrame<sdf_scalar_t<S>>& f,
               const std::array<std::size_t, 3>& tile, sdf_scalar_t<S> far) {
  using T = sdf_scalar_t<S>;
  constexpr std::size_t W = grid_tile;
  const std::array<std::size_t, 3> base{{tile[0] * W, tile[1] * W, tile[2] * W}};
  std::array<std::size_t, 3> size;
  for (int a = 0; a < 3; ++a) size[a] = std::min(f.n[a], base[a] + W) - base[a];
  Sign sg[W * W * W];
  std::fill(sg, sg + W * W * W, Sign::unknown);
  // The tile's whole box first, whatever its distance; then, with a scope (the boxes share the
  // walk above the tile), its octants from 0.7 of their diagonal on, not 1: more proofs, fewer
  // packets (bunny, band of 3 cells at 512³: 0.96 million of the far single tiles' 6.8 million
  // samples left to the packets instead of 2.09 million; those tiles about a quarter faster).
  const Sign whole = sdf.sign_over(
      Aabb<T>{f.point(base[0], base[1], base[2]),
              f.point(base[0] + size[0] - 1, base[1] + size[1] - 1, base[2] + size[2] - 1)});
  if (whole != Sign::unknown) return whole;
  with_tile_signer(sdf, f, base, size, [&](auto&& sign_box) {
    prove_signs(
        sign_box, f, base, {{0, 0, 0}}, size, sg,
        [&](const std::array<std::size_t, 3>&, const std::array<std::size_t, 3>&) { return far; },
        has_batch_sign_v<S> ? 9 : 2, has_sign_scope_v<S> ? 0.7 : 1.0, false);
  });
  batch_signs(sdf, f, base, size, sg, [](std::size_t) { return true; });
  Sign first = Sign::unknown;
  for (std::size_t z = 0; z < size[2]; ++z)
    for (std::size_t y = 0; y < size[1]; ++y)
      for (std::size_t x = 0; x < size[0]; ++x) {
        Sign s = sg[x + W * (y + W * z)];
        if (s == Sign::unknown) s = sdf.sign_at(f.point(base[0] + x, base[1] + y, base[2] + z));
        if (first == Sign::unknown) first = s;
        if (s != first) return Sign::unknown;
      }
  return first;
}

/// `eval_tile` for split-sign SDFs of kind `implicit` in a band (see the file comment).
template <class S>
void eval_split_tile(const S& sdf, const GridFrame<sdf_scalar_t<S>>& f,
                     const TileJob<sdf_scalar_t<S>>& job, const TileParams<sdf_scalar_t<S>>& prm,
                     sdf_scalar_t<S>* vals) {
  using T = sdf_scalar_t<S>;
  constexpr std::size_t W = grid_tile;
  const std::array<std::size_t, 3> base{{job.tile[0] * W, job.tile[1] * W, job.tile[2] * W}};
  std::array<std::size_t, 3> size;
  for (int a = 0; a < 3; ++a) size[a] = std::min(f.n[a], base[a] + W) - base[a];
  const T eps = lipschitz_slack<T>();
  // Distances: in the band, vals = d (near[l]); farther, vals = a lower bound >= band.
  bool near[W * W * W];
  for (std::size_t z = 0; z < size[2]; ++z)
    for (std::size_t y = 0; y < size[1]; ++y)
      for (std::size_t x = 0; x < size[0]; ++x) {
        const std::size_t l = x + W * (y + W * z);
        const Vec3<T> p = f.point(base[0] + x, base[1] + y, base[2] + z);
        near[l] = false;
        if (job.has_centre) {
          // |S(p)| >= |S(c)| - |p - c| (1-Lipschitz): proven far without a search.
          const T lb = (std::abs(job.value) - norm(p - job.centre) * (T(1) + eps)) * (T(1) - eps);
          if (job.sign_only || lb > prm.band) {
            vals[l] = prm.outside == BandFill::clamp ? prm.band : std::max(prm.band, lb);
            continue;
          }
        }
        const T d = sdf.unsigned_within(p, prm.band);
        near[l] = d <= prm.band;
        vals[l] = near[l] ? d : prm.band;
      }
  // Signs: proofs over boxes whose samples are all farther than the box's diagonal; with a batch
  // sign, not over boxes of 2x2x2 samples, whose packets cost less than their proofs (bunny,
  // 256³: 10% less time in all).
  Sign sg[W * W * W];
  std::fill(sg, sg + W * W * W, Sign::unknown);
  prove_signs([&](const Aabb<T>& box) { return sdf.sign_over(box); }, f, base, {{0, 0, 0}}, size,
              sg,
              [&](const std::array<std::size_t, 3>& lo, const std::array<std::size_t, 3>& hi) {
                T m = std::numeric_limits<T>::infinity();
                for (std::size_t z = lo[2]; z < hi[2]; ++z)
                  for (std::size_t y = lo[1]; y < hi[1]; ++y)
                    for (std::size_t x = lo[0]; x < hi[0]; ++x)
                      m = std::min(m, vals[x + W * (y + W * z)]);
                return m;
              },
              has_batch_sign_v<S> ? std::size_t(9) : std::size_t(2));
  // The samples left (off the surface): one batch, where the SDF has one.
  batch_signs(sdf, f, base, size, sg, [&](std::size_t l) { return vals[l] > T(0); });
  for (std::size_t z = 0; z < size[2]; ++z)
    for (std::size_t y = 0; y < size[1]; ++y)
      for (std::size_t x = 0; x < size[0]; ++x) {
        const std::size_t l = x + W * (y + W * z);
        if (!(vals[l] > T(0))) continue; // on the surface (or NaN): no sign
        Sign s = sg[l];
        if (s == Sign::unknown) s = sdf.sign_at(f.point(base[0] + x, base[1] + y, base[2] + z));
        vals[l] = near[l] ? band_value(prm, apply_sign(vals[l], s))
                          : (s == Sign::negative ? -vals[l] : vals[l]);
      }
}

/// Fills `vals[x + 8 (y + 8 z)]` (local indices, stride 8 even for partial tiles) with the values
/// of tile `job.tile`: S (dense) or the banded values of `TileParams`. Bit for bit what per-point
/// evaluation gives (then clamped) at every sample inside the band.
template <class S>
void eval_tile(const S& sdf, const GridFrame<sdf_scalar_t<S>>& f,
               const TileJob<sdf_scalar_t<S>>& job, const TileParams<sdf_scalar_t<S>>& prm,
               sdf_scalar_t<S>* vals) {
  using T = sdf_scalar_t<S>;
  constexpr std::size_t W = grid_tile;
  const std::size_t i0 = job.tile[0] * W, j0 = job.tile[1] * W, k0 = job.tile[2] * W;
  const std::size_t sx = std::min(f.n[0], i0 + W) - i0, sy = std::min(f.n[1], j0 + W) - j0,
                    sz = std::min(f.n[2], k0 + W) - k0;
  const T eps = lipschitz_slack<T>();

  if constexpr (has_split_sign_v<S>) {
    if (prm.band > 0 && prm.split) {
      eval_split_tile(sdf, f, job, prm, vals);
      return;
    }
  }
  if constexpr (has_lattice_eval_v<S>) {
    if (prm.band == 0 && prm.tile) {
      eval_packed(f, {{i0, j0, k0}}, {{sx, sy, sz}}, vals, [&](Span<const Vec3<T>> p, Span<T> v) {
        sdf.eval_lattice(p, {{sx, sy, sz}}, v);
      });
      return;
    }
  }

  if constexpr (has_bounded_query_v<S>) {
    if (prm.band > 0) {
      // 0: exact value in vals; 1: sign known (vals holds the final value); 2: sign unknown.
      std::uint8_t state[W * W * W];
      for (std::size_t z = 0; z < sz; ++z)
        for (std::size_t y = 0; y < sy; ++y)
          for (std::size_t x = 0; x < sx; ++x) {
            const std::size_t l = x + W * (y + W * z);
            const Vec3<T> p = f.point(i0 + x, j0 + y, k0 + z);
            if (job.has_centre) {
              // |S(p)| >= |S(c)| - |p - c| (1-Lipschitz): proven far without a search.
              const T d = norm(p - job.centre);
              const T lb = (std::abs(job.value) - d * (T(1) + eps)) * (T(1) - eps);
              if (lb > prm.band) {
                vals[l] = far_value(prm, job.value, d);
                state[l] = 1;
                continue;
              }
            }
            const T v = sdf.bounded(p, prm.band);
            if (std::abs(v) <= prm.band) {
              vals[l] = v;
              state[l] = 0;
            } else {
              state[l] = 2;
            }
          }
      // Signs of far samples: flood from known neighbours (see the file comment), else one full
      // query per remaining connected component.
      std::uint16_t stack[W * W * W];
      int top = 0;
      bool any_unknown = false;
      for (std::size_t z = 0; z < sz; ++z)
        for (std::size_t y = 0; y < sy; ++y)
          for (std::size_t x = 0; x < sx; ++x) {
            const std::size_t l = x + W * (y + W * z);
            any_unknown = any_unknown || state[l] == 2;
          }
      if (any_unknown) {
        auto flood = [&] {
          while (top > 0) {
            const std::size_t l = stack[--top];
            const std::size_t x = l % W, y = l / W % W, z = l / (W * W);
            const T sign = vals[l];
            auto visit = [&](std::size_t m) {
              if (state[m] != 2) return;
              state[m] = 1;
              vals[m] = std::copysign(prm.band, sign);
              stack[top++] = static_cast<std::uint16_t>(m);
            };
            if (x > 0) visit(l - 1);
            if (x + 1 < sx) visit(l + 1);
            if (y > 0) visit(l - W);
            if (y + 1 < sy) visit(l + W);
            if (z > 0) visit(l - W * W);
            if (z + 1 < sz) visit(l + W * W);
          }
        };
        if (prm.can_propagate) {
          for (std::size_t z = 0; z < sz; ++z)
            for (std::size_t y = 0; y < sy; ++y)
              for (std::size_t x = 0; x < sx; ++x) {
                const std::size_t l = x + W * (y + W * z);
                if (state[l] != 2) stack[top++] = static_cast<std::uint16_t>(l);
              }
          flood();
        }
        for (std::size_t z = 0; z < sz; ++z)
          for (std::size_t y = 0; y < sy; ++y)
            for (std::size_t x = 0; x < sx; ++x) {
              const std::size_t l = x + W * (y + W * z);
              if (state[l] != 2) continue;
              vals[l] = band_value(prm, sdf(f.point(i0 + x, j0 + y, k0 + z)));
              state[l] = 1;
              if (prm.can_propagate) {
                stack[top++] = static_cast<std::uint16_t>(l);
                flood();
              }
            }
      }
      for (std::size_t z = 0; z < sz; ++z)
        for (std::size_t y = 0; y < sy; ++y)
          for (std::size_t x = 0; x < sx; ++x) {
            const std::size_t l = x + W * (y + W * z);
            if (state[l] == 0) vals[l] = band_value(prm, vals[l]);
          }
      return;
    }
  }

  if constexpr (has_batch_eval_v<S>) {
    eval_packed(f, {{i0, j0, k0}}, {{sx, sy, sz}}, vals,
                [&](Span<const Vec3<T>> p, Span<T> v) { sdf.eval(p, v); });
  } else {
    for (std::size_t z = 0; z < sz; ++z)
      for (std::size_t y = 0; y < sy; ++y)
        for (std::size_t x = 0; x < sx; ++x)
          vals[x + W * (y + W * z)] = sdf(f.point(i0 + x, j0 + y, k0 + z));
  }
  if (prm.band > 0)
    for (std::size_t z = 0; z < sz; ++z)
      for (std::size_t y = 0; y < sy; ++y)
        for (std::size_t x = 0; x < sx; ++x) {
          T& v = vals[x + W * (y + W * z)];
          v = band_value(prm, v);
        }
}

/// Payload of a node (a box of tiles) of the tile octree.
template <class T> struct TileNodeInfo {
  T value = 0;
  Vec3<T> centre{};
  std::uint8_t state = 0; ///< 0: outside the range, 1: skipped (far), 2: kept, 3: far, signs only
};

/// Tiles `[ta, tb)` of the range `region` (sample indices).
inline void range_tiles(const GridRange& region, std::array<std::size_t, 3>& ta,
                        std::array<std::size_t, 3>& tb) noexcept {
  for (int a = 0; a < 3; ++a) {
    ta[a] = region.lo[a] / grid_tile;
    tb[a] = (region.hi[a] + grid_tile - 1) / grid_tile;
  }
}

/// Plans the tiles of `region` (see the file comment). `skip` enables the octree; `prm.split`
/// plans with the unsigned distance and signs by proof.
template <class S>
GridPlan<sdf_scalar_t<S>> plan_grid(const S& sdf, const GridFrame<sdf_scalar_t<S>>& f,
                                    const GridRange& region, const TileParams<sdf_scalar_t<S>>& prm,
                                    bool skip, const ExecOptions& exec) {
  using T = sdf_scalar_t<S>;
  GridPlan<T> plan;
  std::array<std::size_t, 3> ta, tb;
  range_tiles(region, ta, tb);
  if (!skip) {
    plan.eval.reserve((tb[0] - ta[0]) * (tb[1] - ta[1]) * (tb[2] - ta[2]));
    for (std::size_t k = ta[2]; k < tb[2]; ++k)
      for (std::size_t j = ta[1]; j < tb[1]; ++j)
        for (std::size_t i = ta[0]; i < tb[0]; ++i) {
          TileJob<T> job;
          job.tile = {{std::uint32_t(i), std::uint32_t(j), std::uint32_t(k)}};
          plan.eval.push_back(job);
        }
    std::sort(plan.eval.begin(), plan.eval.end(), [](const TileJob<T>& a, const TileJob<T>& b) {
      return morton3(a.tile[0], a.tile[1], a.tile[2]) < morton3(b.tile[0], b.tile[1], b.tile[2]);
    });
    return plan;
  }
  // Octree over tile indices [0, 2^D)^3 of the whole grid; nodes at depth D are single tiles.
  int depth = 0;
  while ((std::size_t(1) << depth) < std::max({f.tiles[0], f.tiles[1], f.tiles[2]})) ++depth;
  const T band = prm.band;
  const T eps = lipschitz_slack<T>();
  auto refine = [&](const Aabb<T>& box, int d, TileNodeInfo<T>& info) {
    std::array<std::size_t, 3> a, b, lo, hi;
    for (int ax = 0; ax < 3; ++ax) {
      a[ax] = std::size_t(box.lo[ax]);
      b[ax] = std::min(std::size_t(box.hi[ax]), f.tiles[ax]);
      if (a[ax] >= b[ax] || a[ax] >= tb[ax] || b[ax] <= ta[ax]) {
        info.state = 0;
        return false;
      }
    }
    f.sample_range(a, b, lo, hi);
    const Vec3<T> p0 = f.point(lo[0], lo[1], lo[2]);
    const Vec3<T> p1 = f.point(hi[0] - 1, hi[1] - 1, hi[2] - 1);
    const Vec3<T> mid = (p0 + p1) * T(0.5);
    const T r = norm(p1 - p0) * T(0.5);
    info.centre = mid;
    if constexpr (has_split_sign_v<S>) {
      if (prm.split) {
        const T ud = sdf.unsigned_distance(mid);
        info.value = ud;
        if (!(ud > (r + band) * (T(1) + eps))) {
          info.state = 2;
          return d < depth;
        }
        // Far: a sign for the whole node, else split; a single tile's samples decide.
        // A single tile: its box, then its octants (`tile_sign`).
        const Sign sign =
            d == depth ? tile_sign(sdf, f, a, ud - r) : sdf.sign_over(Aabb<T>{p0, p1});
        if (sign != Sign::unknown) {
          info.value = sign == Sign::negative ? -ud : ud;
          info.state = 1;
          return false;
        }
        info.state = 3;
        return d < depth;
      }
    }
    info.value = sdf(mid);
    if (std::abs(info.value) > (r + band) * (T(1) + eps)) {
      info.state = 1;
      return false;
    }
    info.state = 2;
    return d < depth;
  };
  OctreeOptions oopt;
  oopt.max_depth = depth + 1; // refine runs at depth D too, and declines to split there
  oopt.order = OctreeOrder::breadth_first;
  oopt.threads = exec.threads;
  const T side = T(std::size_t(1) << depth);
  const auto tree = Octree<T, TileNodeInfo<T>>::build(
                        Aabb<T>({T(0), T(0), T(0)}, {side, side, side}), refine, oopt)
                        .value(); // the root box is valid by construction
  tree.traverse([&](std::uint32_t, const auto& node) {
    if (!node.is_leaf()) return true;
    const TileNodeInfo<T>& info = node.payload;
    std::array<std::size_t, 3> a, b;
    for (int ax = 0; ax < 3; ++ax) {
      a[ax] = std::max(std::size_t(node.box.lo[ax]), ta[ax]);
      b[ax] = std::min(std::size_t(node.box.hi[ax]), tb[ax]);
    }
    if (info.state == 1) {
      plan.skipped.push_back({a, b, info.value, info.centre});
    } else if (info.state >= 2) {
      TileJob<T> job;
      job.sign_only = info.state == 3;
      job.tile = {{std::uint32_t(a[0]), std::uint32_t(a[1]), std::uint32_t(a[2])}};
      job.has_centre = true;
      job.value = info.value;
      job.centre = info.centre;
      plan.eval.push_back(job);
    }
    return true;
  });
  return plan;
}

/// `TileParams` for `opt` on grid `spec` with `sdf`.
template <class S>
TileParams<sdf_scalar_t<S>> tile_params(const S& sdf, const GridSpec<sdf_scalar_t<S>>& spec,
                                        const GridOptions& opt) noexcept {
  using T = sdf_scalar_t<S>;
  TileParams<T> prm;
  prm.band = T(opt.band);
  prm.outside = opt.outside;
  prm.tile = opt.search == GridSearch::tile;
  const Vec3<T> h = spec.spacing();
  T hmax = 0;
  for (int a = 0; a < 3; ++a)
    if (spec.dims[a] > 1) hmax = std::max(hmax, h[a]);
  const bool implicit = kind_of(sdf) == SdfKind::implicit;
  prm.can_propagate = !implicit && prm.band >= hmax * (T(1) + lipschitz_slack<T>());
  prm.split = has_split_sign_v<S> && implicit;
  return prm;
}

/// True when a band may skip tiles far from the surface: the SDF is `exact` or `bound`, or its
/// sign is proven over boxes (`TileParams::split`).
template <class S> bool skips_far_tiles(const S& sdf, const TileParams<sdf_scalar_t<S>>& prm) {
  return prm.band > 0 && (kind_of(sdf) != SdfKind::implicit || prm.split);
}

/// Common argument checks of the samplers.
template <class T>
Result<Ok> check_grid_args(const GridSpec<T>& spec, const GridRange& region, const GridOptions& opt,
                           const char* who) {
  if (auto ok = spec.validate(); !ok) return ok;
  if (auto ok = region.validate(spec); !ok) return ok;
  if (!(opt.band >= 0) || !std::isfinite(opt.band))
    return make_error(ErrorCode::invalid_argument, who, ": band must be finite and >= 0");
  return Ok{};
}

} // namespace ebgeom::detail

EBGEOM_END_EXACT_FP
