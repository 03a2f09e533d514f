// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Tile evaluation of `MeshSdf` (`MeshSdf::eval_lattice`): the nearest triangle slot of every
/// sample of a tile of lattice samples (an 8^3 tile of a grid), from one BVH search near the
/// tile's centre and a list of candidate leaves shared by the samples. The slots are exactly those
/// of the per-point search (`BlockSearch::nearest_slot`); see `MeshSdf::eval_lattice` for why.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "ebgeom/bvh/traverse.hpp"
#include "ebgeom/bvh/wide_bvh.hpp"
#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/isa.hpp"
#include "ebgeom/core/simd.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/geom/tri_block.hpp"
#include "ebgeom/sdf/mesh_block_search.hpp"

EBGEOM_BEGIN_EXACT_FP

namespace ebgeom {

namespace detail {
/// Squared distances from box `b` to `n` boxes stored as structure of arrays, each as
/// `MeshTileEval::box_box_distance2` computes it (same operations).
template <class T>
EBGEOM_VECTOR_KERNEL EBGEOM_FORCE_INLINE void
boxes_box_distance2_inline(std::size_t n, const T* EBGEOM_RESTRICT lx, const T* EBGEOM_RESTRICT ly,
                           const T* EBGEOM_RESTRICT lz, const T* EBGEOM_RESTRICT hx,
                           const T* EBGEOM_RESTRICT hy, const T* EBGEOM_RESTRICT hz,
                           const Aabb<T>& b, T* EBGEOM_RESTRICT out) noexcept {
  const T blx = b.lo.x, bly = b.lo.y, blz = b.lo.z, bhx = b.hi.x, bhy = b.hi.y, bhz = b.hi.z;
  // Ternaries, not std::max: the kernel's optimisation attribute keeps std::max from inlining.
  // Runs of 16 (a loop of constant length, which GCC vectorises at -O2 as well), then the rest.
  std::size_t i0 = 0;
  for (; i0 + 16 <= n; i0 += 16)
    for (std::size_t i = i0; i < i0 + 16; ++i) {
      T ax = lx[i] - bhx, bx = blx - hx[i], ay = ly[i] - bhy, by = bly - hy[i], az = lz[i] - bhz,
        bz = blz - hz[i];
      ax = ax < bx ? bx : ax, ay = ay < by ? by : ay, az = az < bz ? bz : az;
      ax = ax < T(0) ? T(0) : ax, ay = ay < T(0) ? T(0) : ay, az = az < T(0) ? T(0) : az;
      out[i] = ax * ax + ay * ay + az * az;
    }
  for (std::size_t i = i0; i < n; ++i) {
    T ax = lx[i] - bhx, bx = blx - hx[i], ay = ly[i] - bhy, by = bly - hy[i], az = lz[i] - bhz,
      bz = blz - hz[i];
    ax = ax < bx ? bx : ax, ay = ay < by ? by : ay, az = az < bz ? bz : az;
    ax = ax < T(0) ? T(0) : ax, ay = ay < T(0) ? T(0) : ay, az = az < T(0) ? T(0) : az;
    out[i] = ax * ax + ay * ay + az * az;
  }
}

/// Squared distances from `p` to `n` boxes stored as structure of arrays (`lo_x[i]`, ...): those
/// from the box [p, p] (`boxes_box_distance2_inline`), the same operations on the same values.
template <class T>
EBGEOM_VECTOR_KERNEL EBGEOM_FORCE_INLINE void
boxes_distance2_inline(std::size_t n, const T* EBGEOM_RESTRICT lx, const T* EBGEOM_RESTRICT ly,
                       const T* EBGEOM_RESTRICT lz, const T* EBGEOM_RESTRICT hx,
                       const T* EBGEOM_RESTRICT hy, const T* EBGEOM_RESTRICT hz, const Vec3<T>& p,
                       T* EBGEOM_RESTRICT out) noexcept {
  boxes_box_distance2_inline(n, lx, ly, lz, hx, hy, hz, Aabb<T>{p, p}, out);
}
} // namespace detail

template <class T>
EBGEOM_VECTOR_KERNEL inline void
boxes_distance2(std::size_t n, const T* EBGEOM_RESTRICT lx, const T* EBGEOM_RESTRICT ly,
                const T* EBGEOM_RESTRICT lz, const T* EBGEOM_RESTRICT hx,
                const T* EBGEOM_RESTRICT hy, const T* EBGEOM_RESTRICT hz, const Vec3<T>& p,
                T* EBGEOM_RESTRICT out) noexcept {
  detail::boxes_distance2_inline(n, lx, ly, lz, hx, hy, hz, p, out);
}

namespace detail {

/// `block_min` of a tile sample's search pruning with `lim` (>= `b2`), skipping the distance
/// kernel when no lane can be near enough: a lane is near enough when its triangle's box is within
/// `lim` (`block_box_mask_inline`, as `block_min_pruned`) and, given supporting planes
/// (`block_planes`, `nx != nullptr`), its plane's lower bound `n · p - off` is at most `r` (the
/// bound's distance with the planes' error margins). The planes bound each triangle's distance
/// from below (convexity), so a lane failing either test cannot reach `b2`; when some lane passes,
/// the result is `block_min_inline` over the whole block, as in `block_min_pruned`.

template <class T, int W, Isa I>
EBGEOM_VECTOR_KERNEL EBGEOM_FORCE_INLINE LaneMin<T, W>
block_min_planes_inline(const TriBlock<T, W>& t, const Vec3<T>& p, T b2, T lim, const T* nx,
                        const T* ny, const T* nz, const T* off, T r) noexcept {
  // Planes first: 4 W values against the block's 9 W, and they reject most blocks.
  LaneMask<W> m = ~LaneMask<W>(0);
  if (nx != nullptr) {
    T v[W];
    for (int l = 0; l < W; ++l) v[l] = nx[l] * p.x + ny[l] * p.y + nz[l] * p.z - off[l];
    m = lane_mask<LaneCmp::le, I>(v, r);
    if (m == 0) return {b2, 0};
  }
  m &= block_box_mask_inline<T, W, I>(t, p, lim);
  if (m == 0) return {b2, 0};
  return block_min_inline<T, W, I>(t, p, b2);
}

#if EBGEOM_ISA_DISPATCH || defined(__AVX512F__)
/// The indices i < n (n a multiple of 64 / sizeof(T): whole registers) with `d2[i] < lim`, in
/// increasing order, written from `idx[0]` on; returns their count. Compresses each register's
/// indices in registers and stores whole registers (compress stores to memory are slow on some
/// CPUs): `idx` needs room for 16 more entries than the count.
template <class T>
EBGEOM_TARGET_AVX512 EBGEOM_NOINLINE std::size_t
indices_below_avx512(const T* EBGEOM_RESTRICT d2, std::size_t n, T lim,
                     std::uint32_t* EBGEOM_RESTRICT idx) noexcept {
  std::size_t m = 0;
  const __m512i step = _mm512_set1_epi32(sizeof(T) == 4 ? 16 : 8);
  __m512i ids = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  constexpr std::size_t lanes = 64 / sizeof(T);
  for (std::size_t i = 0; i < n; i += lanes) {
    std::uint32_t k;
    if constexpr (sizeof(T) == 4)
      k = _mm512_cmp_ps_mask(_mm512_loadu_ps(d2 + i), _mm512_set1_ps(lim), _CMP_LT_OQ);
    else
      k = _mm512_cmp_pd_mask(_mm512_loadu_pd(d2 + i), _mm512_set1_pd(lim), _CMP_LT_OQ);
    _mm512_storeu_si512(idx + m, _mm512_maskz_compress_epi32(__mmask16(k), ids));
    m += std::size_t(_mm_popcnt_u32(k));
    ids = _mm512_add_epi32(ids, step);
  }
  return m;
}
#endif

template <Isa I> struct MeshTileKernels;

/// Nearest slots of the samples of a tile (see the file comment) over a `BlockSearch`, with the
/// absolute error bound of supporting planes `plane_margin` (`MeshSdf::plane_margin`), with the
/// kernels of instruction set I (`core/isa.hpp`).
template <class T, int K, int W, Isa I = native_isa> class MeshTileEval {
 public:
  MeshTileEval(const BlockSearch<T, K, W>& s, T plane_margin) noexcept
      : s_(s), plane_margin_(plane_margin) {}

  /// The nearest slot of each of the `dims[0] * dims[1] * dims[2]` finite samples `pts` (x
  /// fastest), equal to `BlockSearch::nearest_slot` from an infinite bound. Allocates
  /// O(candidate leaves) scratch; thread-safe.
  /// `best2`, when not null, receives each sample's squared distance to its slot as the block
  /// kernel computes it: the bits of `closest_point_triangle`'s (`geom/tri_block.hpp`).
  std::vector<std::uint32_t> nearest_slots(const Vec3<T>* pts,
                                           const std::array<std::size_t, 3>& dims,
                                           T* best2 = nullptr) const {
    const std::size_t n = dims[0] * dims[1] * dims[2];
    LatticeJob job{pts,
                   dims,
                   std::vector<std::uint32_t>(n, bvh::ChildRef::none),
                   best2,
                   {},
                   {},
                   bvh::ChildRef::none};
    job.d2.resize(64);
    MeshTileKernels<I>::solve_lattice(*this, job, {{0, 0, 0}}, dims, nullptr, 0);
    return std::move(job.slot);
  }

 private:
  template <Isa> friend struct MeshTileKernels;

  /// Candidate leaves of a tile (or part of one), structure of arrays (boxes padded with empty ones
  /// to a multiple of 16 so the box-distance loop has no remainder).
  struct LeafList {
    // Boxes, then per leaf the supporting planes of its first block's triangles (`block_planes`,
    // W lanes per leaf; `planes[i]` false: none yet).
    std::vector<T> lo_x, lo_y, lo_z, hi_x, hi_y, hi_z, pnx, pny, pnz, poff;
    std::vector<std::uint32_t> first, count, root;
    std::vector<std::uint8_t> planes;
    std::size_t size() const noexcept { return first.size(); }
    void clear() noexcept {
      for (auto* v : {&lo_x, &lo_y, &lo_z, &hi_x, &hi_y, &hi_z, &pnx, &pny, &pnz, &poff})
        v->clear();
      first.clear();
      count.clear();
      root.clear();
      planes.clear();
    }
    void add(const Aabb<T>& b, std::uint32_t f, std::uint32_t c) {
      lo_x.push_back(b.lo.x), lo_y.push_back(b.lo.y), lo_z.push_back(b.lo.z);
      hi_x.push_back(b.hi.x), hi_y.push_back(b.hi.y), hi_z.push_back(b.hi.z);
      root.push_back(std::uint32_t(first.size()));
      first.push_back(f), count.push_back(c);
      planes.push_back(0);
      for (auto* v : {&pnx, &pny, &pnz, &poff}) v->resize(v->size() + std::size_t(W)); // zeros
    }
    /// The leaves `i` of `o` with `d2[i] < lim2`, padded.
    void filter_from(const LeafList& o, const T* d2, T lim2) {
      const std::size_t n = o.size();
      std::size_t m = 0;
      for (std::size_t i = 0; i < n; ++i) m += d2[i] < lim2;
      const std::size_t mp = (m + 15) / 16 * 16;
      for (auto* v : {&lo_x, &lo_y, &lo_z, &hi_x, &hi_y, &hi_z}) v->resize(mp);
      first.resize(m), count.resize(m), root.resize(m);
      std::size_t k = 0;
      for (std::size_t i = 0; i < n; ++i) {
        if (!(d2[i] < lim2)) continue;
        lo_x[k] = o.lo_x[i], lo_y[k] = o.lo_y[i], lo_z[k] = o.lo_z[i];
        hi_x[k] = o.hi_x[i], hi_y[k] = o.hi_y[i], hi_z[k] = o.hi_z[i];
        first[k] = o.first[i], count[k] = o.count[i], root[k] = o.root[i];
        ++k;
      }
      const T inf = std::numeric_limits<T>::infinity();
      for (; k < mp; ++k) lo_x[k] = lo_y[k] = lo_z[k] = inf, hi_x[k] = hi_y[k] = hi_z[k] = -inf;
    }
    void pad() {
      const T inf = std::numeric_limits<T>::infinity();
      while (lo_x.size() % 16) {
        lo_x.push_back(inf), lo_y.push_back(inf), lo_z.push_back(inf);
        hi_x.push_back(-inf), hi_y.push_back(-inf), hi_z.push_back(-inf);
      }
    }
  };

  struct LatticeJob {
    const Vec3<T>* pts;
    std::array<std::size_t, 3> dims;
    std::vector<std::uint32_t> slot; ///< nearest slot per sample (none = not searched yet)
    T* best2;                        ///< per sample, the search's squared distance (or null)
    LeafList lists[8];               ///< one per recursion level
    std::vector<T> d2;               ///< box distances scratch
    std::uint32_t last;              ///< nearest slot of the last sample searched
  };

  /// Squared distance between two boxes (0 when they overlap). For p in `b`, never above
  /// `a.distance2(p)` in floating point (each step is monotone).
  static T box_box_distance2(const Aabb<T>& a, const Aabb<T>& b) noexcept {
    const T dx = std::max(std::max(a.lo.x - b.hi.x, b.lo.x - a.hi.x), T(0));
    const T dy = std::max(std::max(a.lo.y - b.hi.y, b.lo.y - a.hi.y), T(0));
    const T dz = std::max(std::max(a.lo.z - b.hi.z, b.lo.z - a.hi.z), T(0));
    return dx * dx + dy * dy + dz * dz;
  }

  /// Leaves whose box is within squared distance `lim2` of `box`, nearest to `c` first.
  EBGEOM_FORCE_INLINE void collect_leaves_inline(const Aabb<T>& box, T lim2, const Vec3<T>& c,
                                                 LeafList& out) const {
    struct Item {
      T key;
      Aabb<T> b;
      bvh::ChildRef r;
    };
    std::vector<Item> items;
    if (s_.bvh->root.is_leaf()) {
      items.push_back({T(0), s_.bvh->box, s_.bvh->root});
    } else if (!s_.bvh->root.is_empty()) {
      bvh::FixedStack<std::uint32_t, bvh::WideBvh<T, K>::stack_capacity> todo;
      todo.push(s_.bvh->root.index);
      while (!todo.empty()) {
        const auto& nd = s_.bvh->nodes[todo.pop()];
        for (int k = 0; k < K; ++k) {
          const bvh::ChildRef r = nd.child[k];
          if (r.is_empty()) continue;
          const Aabb<T> b = nd.child_box(k);
          if (!(box_box_distance2(b, box) < lim2)) continue;
          if (r.is_leaf())
            items.push_back({b.distance2(c), b, r});
          else
            todo.push(r.index);
        }
      }
    }
    std::sort(items.begin(), items.end(),
              [](const Item& a, const Item& b) { return a.key < b.key; });
    out.clear();
    for (const Item& it : items) out.add(it.b, it.r.index, it.r.count);
    out.pad();
  }

  /// Nearest slot of `p` among the leaves of `list` (a superset of the leaves the per-point
  /// search needs), starting from the block of slot `seed` (or none); its squared distance in
  /// `best2`.
  std::uint32_t scan_list_inline(const LeafList& list, LeafList& pl, const Vec3<T>& p,
                                 std::uint32_t seed, std::vector<T>& d2s, T& best2) const noexcept {
    T b2 = std::numeric_limits<T>::infinity();
    std::uint32_t best = bvh::ChildRef::none;
    std::uint32_t seed_block = bvh::ChildRef::none;
    if (seed != bvh::ChildRef::none) {
      seed_block = seed / std::uint32_t(W);
      s_.template scan_blocks<I>(seed_block, std::uint32_t(W), p, b2, best);
    }
    const std::size_t n = list.size(), np = list.lo_x.size();
    T* EBGEOM_RESTRICT d2 = d2s.data();
    const T* EBGEOM_RESTRICT lx = list.lo_x.data();
    const T* EBGEOM_RESTRICT ly = list.lo_y.data();
    const T* EBGEOM_RESTRICT lz = list.lo_z.data();
    const T* EBGEOM_RESTRICT hx = list.hi_x.data();
    const T* EBGEOM_RESTRICT hy = list.hi_y.data();
    const T* EBGEOM_RESTRICT hz = list.hi_z.data();
    MeshTileKernels<I>::boxes_distance2(np, lx, ly, lz, hx, hy, hz, p, d2);
    // Supporting planes bound each triangle's distance from below (`block_planes`). Rounding: the
    // planes carry errors of a few ulps of the coordinates (`plane_margin_`) and the kernel's
    // squared distances those `prune_limit` allows for; the margins exceed both.
    const T rel = T(256) * std::numeric_limits<T>::epsilon();
    T lim = bvh::prune_limit(b2, s_.slack);
    T r = std::sqrt(lim) * (T(1) + rel) + plane_margin_;
    T lim_b2 = b2; // the b2 that lim and r were computed from
    // Branch-free compaction of the boxes within the bound (few of them), then the scan.
    std::uint32_t* EBGEOM_RESTRICT idx = reinterpret_cast<std::uint32_t*>(d2 + np);
    std::size_t m = 0;
#if EBGEOM_ISA_DISPATCH || defined(__AVX512F__)
    if constexpr (I == Isa::avx512 && (std::is_same_v<T, float> || std::is_same_v<T, double>)) {
      // Padding boxes (at infinity) never pass.
      m = indices_below_avx512(d2, np, lim, idx);
    } else
#endif
    {
      for (std::size_t i = 0; i < n; ++i) {
        idx[m] = std::uint32_t(i);
        m += d2[i] < lim;
      }
    }
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t i = idx[k];
      if (!(d2[i] < lim) || (list.first[i] == seed_block && list.count[i] <= std::uint32_t(W)))
        continue;
      const std::size_t j = list.root[i];
      if (list.count[i] > std::uint32_t(W)) {
        s_.template scan_blocks<I>(list.first[i], list.count[i], p, b2, best);
      } else {
        // One block: its lanes' boxes and, once known, supporting planes decide whether the
        // distance kernel runs; then `scan_blocks`'s update (ties: lowest triangle id).
        const bool has = pl.planes[j] != 0;
        const std::uint32_t blk = list.first[i];
        const LaneMin<T, W> lm = MeshTileKernels<I>::block_min_planes(
            s_.blocks[blk], p, b2, lim, has ? pl.pnx.data() + j * W : nullptr,
            pl.pny.data() + j * W, pl.pnz.data() + j * W, pl.poff.data() + j * W, r);
        if (lm.mask != 0 && (lm.min < b2 || best != bvh::ChildRef::none)) {
          const std::uint32_t slot =
              blk * std::uint32_t(W) + std::uint32_t(detail::lowest_bit(lm.mask));
          if (lm.min < b2 || s_.tri[slot] < s_.tri[best]) {
            b2 = lm.min;
            best = slot;
          }
        }
        if (has) {
          if (b2 != lim_b2) {
            lim_b2 = b2;
            lim = bvh::prune_limit(b2, s_.slack);
            r = std::sqrt(lim) * (T(1) + rel) + plane_margin_;
          }
          continue;
        }
      }
      if (list.count[i] <= std::uint32_t(W) && !pl.planes[j]) {
        T(&nx)[W] = *reinterpret_cast<T(*)[W]>(pl.pnx.data() + j * W);
        T(&ny)[W] = *reinterpret_cast<T(*)[W]>(pl.pny.data() + j * W);
        T(&nz)[W] = *reinterpret_cast<T(*)[W]>(pl.pnz.data() + j * W);
        T(&of)[W] = *reinterpret_cast<T(*)[W]>(pl.poff.data() + j * W);
        block_planes<T, W, I>(s_.blocks[list.first[i]], p, nx, ny, nz, of);
        pl.planes[j] = 1;
      }
      if (b2 != lim_b2) {
        lim_b2 = b2;
        lim = bvh::prune_limit(b2, s_.slack);
        r = std::sqrt(lim) * (T(1) + rel) + plane_margin_;
      }
    }
    best2 = b2;
    return best;
  }

  /// Samples [a, b) of the job's tile; `parent` lists the candidate leaves of an
  /// enclosing octant (nullptr: the whole BVH).
  EBGEOM_FORCE_INLINE void solve_lattice_inline(LatticeJob& job,
                                                const std::array<std::size_t, 3>& a,
                                                const std::array<std::size_t, 3>& b,
                                                LeafList* parent, int level) const {
    const auto& dims = job.dims;
    auto index = [&](std::size_t x, std::size_t y, std::size_t z) {
      return x + dims[0] * (y + dims[1] * z);
    };
    const Vec3<T> c0 = job.pts[index(a[0], a[1], a[2])];
    const Vec3<T> c1 = job.pts[index(b[0] - 1, b[1] - 1, b[2] - 1)];
    const Aabb<T> box(min(c0, c1), max(c0, c1));
    const std::size_t nsamples = (b[0] - a[0]) * (b[1] - a[1]) * (b[2] - a[2]);
    LeafList& list = job.lists[level];
    // One search at the middle sample bounds every sample's distance.
    const std::size_t qi = index((a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2);
    const Vec3<T> q = job.pts[qi];
    if (job.slot[qi] == bvh::ChildRef::none) {
      if (parent == nullptr) {
        T b2 = std::numeric_limits<T>::infinity();
        std::uint32_t best = bvh::ChildRef::none;
        MeshSearchKernels<I>::nearest_slot(s_, q, b2, best);
        job.slot[qi] = best;
        if (job.best2 != nullptr) job.best2[qi] = b2;
      } else {
        T b2;
        job.slot[qi] =
            MeshTileKernels<I>::scan_list(*this, *parent, job.lists[0], q, job.last, job.d2, b2);
        if (job.best2 != nullptr) job.best2[qi] = b2;
      }
      job.last = job.slot[qi];
    }
    {
      T dq2 = std::numeric_limits<T>::infinity();
      std::uint32_t dummy = bvh::ChildRef::none;
      s_.template scan_blocks<I>(job.slot[qi] / std::uint32_t(W), std::uint32_t(W), q, dq2, dummy);
      const T eps = std::numeric_limits<T>::epsilon();
      const T u = (std::sqrt(dq2) + std::sqrt(box.max_distance2(q))) * (T(1) + T(64) * eps);
      const T lim2 = bvh::prune_limit(u * u, s_.slack);
      if (parent == nullptr) {
        MeshTileKernels<I>::collect_leaves(*this, box, lim2, box.center(), list);
      } else {
        // The parent's leaves within the bound: a vectorised box test, then a copy of those.
        const std::size_t np = parent->lo_x.size();
        if (job.d2.size() < np) job.d2.resize(np);
        MeshTileKernels<I>::boxes_box_distance2(
            np, parent->lo_x.data(), parent->lo_y.data(), parent->lo_z.data(), parent->hi_x.data(),
            parent->hi_y.data(), parent->hi_z.data(), box, job.d2.data());
        list.filter_from(*parent, job.d2.data(), lim2);
      }
    }
    // Box distances, then their indices (and 16 entries of slack, `indices_below_avx512`).
    if (job.d2.size() < 2 * list.lo_x.size() + 16) job.d2.resize(2 * list.lo_x.size() + 16);
    if (list.size() > lattice_split_leaves && nsamples > 8 && level < 7) {
      std::array<std::size_t, 3> m;
      for (int d = 0; d < 3; ++d) m[d] = b[d] - a[d] > 1 ? (a[d] + b[d]) / 2 : b[d];
      for (int o = 0; o < 8; ++o) {
        std::array<std::size_t, 3> ca, cb;
        bool empty = false;
        for (int d = 0; d < 3; ++d) {
          const bool hi = (o >> d) & 1;
          ca[d] = hi ? m[d] : a[d];
          cb[d] = hi ? b[d] : m[d];
          empty = empty || ca[d] >= cb[d];
        }
        if (!empty) MeshTileKernels<I>::solve_lattice(*this, job, ca, cb, &list, level + 1);
      }
      return;
    }
    for (std::size_t z = a[2]; z < b[2]; ++z)
      for (std::size_t y = a[1]; y < b[1]; ++y)
        for (std::size_t x = a[0]; x < b[0]; ++x) {
          const std::size_t l = index(x, y, z);
          if (job.slot[l] != bvh::ChildRef::none) continue;
          T b2;
          job.slot[l] = MeshTileKernels<I>::scan_list(*this, list, job.lists[0], job.pts[l],
                                                      job.last, job.d2, b2);
          if (job.best2 != nullptr) job.best2[l] = b2;
          job.last = job.slot[l];
        }
  }

  static constexpr std::size_t lattice_split_leaves = 256;

  BlockSearch<T, K, W> s_;
  T plane_margin_;
};

/// Tile evaluation compiled for instruction set I: the recursion over parts of the tile, the leaf
/// collection, the per-sample scan (`flatten` inlines its block scans) and the box test, each one
/// function with I's target attribute.
#define EBGEOM_MESH_TILE_KERNELS(I, TARGET)                                                        \
  template <class T>                                                                               \
  TARGET EBGEOM_VECTOR_KERNEL EBGEOM_NOINLINE static void boxes_distance2(                         \
      std::size_t n, const T* EBGEOM_RESTRICT lx, const T* EBGEOM_RESTRICT ly,                     \
      const T* EBGEOM_RESTRICT lz, const T* EBGEOM_RESTRICT hx, const T* EBGEOM_RESTRICT hy,       \
      const T* EBGEOM_RESTRICT hz, const Vec3<T>& p, T* EBGEOM_RESTRICT out) noexcept {            \
    boxes_distance2_inline(n, lx, ly, lz, hx, hy, hz, p, out);                                     \
  }                                                                                                \
  template <class T>                                                                               \
  TARGET EBGEOM_VECTOR_KERNEL EBGEOM_NOINLINE static void boxes_box_distance2(                     \
      std::size_t n, const T* EBGEOM_RESTRICT lx, const T* EBGEOM_RESTRICT ly,                     \
      const T* EBGEOM_RESTRICT lz, const T* EBGEOM_RESTRICT hx, const T* EBGEOM_RESTRICT hy,       \
      const T* EBGEOM_RESTRICT hz, const Aabb<T>& b, T* EBGEOM_RESTRICT out) noexcept {            \
    boxes_box_distance2_inline(n, lx, ly, lz, hx, hy, hz, b, out);                                 \
  }                                                                                                \
  template <class T, int W>                                                                        \
  TARGET EBGEOM_VECTOR_KERNEL EBGEOM_NOINLINE static LaneMin<T, W> block_min_planes(               \
      const TriBlock<T, W>& t, const Vec3<T>& p, T b2, T lim, const T* nx, const T* ny,            \
      const T* nz, const T* off, T r) noexcept {                                                   \
    return block_min_planes_inline<T, W, I>(t, p, b2, lim, nx, ny, nz, off, r);                    \
  }                                                                                                \
  template <class E, class Job>                                                                    \
  TARGET static void solve_lattice(const E& e, Job& job, const std::array<std::size_t, 3>& a,      \
                                   const std::array<std::size_t, 3>& b,                            \
                                   typename E::LeafList* parent, int level) {                      \
    e.solve_lattice_inline(job, a, b, parent, level);                                              \
  }                                                                                                \
  template <class E, class T>                                                                      \
  TARGET static void collect_leaves(const E& e, const Aabb<T>& box, T lim2, const Vec3<T>& c,      \
                                    typename E::LeafList& out) {                                   \
    e.collect_leaves_inline(box, lim2, c, out);                                                    \
  }                                                                                                \
  template <class E, class List, class T>                                                          \
  TARGET EBGEOM_FLATTEN static std::uint32_t scan_list(const E& e, const List& list, List& pl,     \
                                                       const Vec3<T>& p, std::uint32_t seed,       \
                                                       std::vector<T>& d2s, T& best2) noexcept {   \
    return e.scan_list_inline(list, pl, p, seed, d2s, best2);                                      \
  }

template <Isa I> struct MeshTileKernels { EBGEOM_MESH_TILE_KERNELS(I, ) };
#if EBGEOM_ISA_DISPATCH
template <> struct MeshTileKernels<Isa::avx2> {
  EBGEOM_MESH_TILE_KERNELS(Isa::avx2, EBGEOM_TARGET_AVX2)
};
template <> struct MeshTileKernels<Isa::avx512> {
  EBGEOM_MESH_TILE_KERNELS(Isa::avx512, EBGEOM_TARGET_AVX512)
};
#endif
#undef EBGEOM_MESH_TILE_KERNELS

} // namespace detail
} // namespace ebgeom

EBGEOM_END_EXACT_FP
