// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `TriBlock<T, W>`: W triangles stored as structure of arrays, and the vector forms of the
/// triangle kernel over a block: squared distances (`block_distance2`, the same operations as
/// `closest_point_triangle` lane by lane, so equal bit for bit), the lanes that can lower a search
/// bound (`block_min`) and supporting planes (`block_planes`). The leaves of `MeshSdf`'s BVH are
/// blocks.
///
/// Caveat: compilers may contract a*b+c into fused multiply-adds differently in vector and scalar
/// code when FMA instructions are enabled; the kernels here carry `EBGEOM_VECTOR_KERNEL`, which
/// turns contraction off for GCC (Clang contracts the same way in both).

#include <cmath>
#include <limits>

#include "ebgeom/core/config.hpp"
#include "ebgeom/core/isa.hpp"
#include "ebgeom/core/simd.hpp"
#include "ebgeom/core/vec.hpp"

EBGEOM_BEGIN_EXACT_FP

namespace ebgeom {
/// W triangles, structure of arrays: 9·W scalars (W = 8 float: 288 B; W = 4 double: 288 B).
template <class T, int W> struct TriBlock {
  T ax[W], ay[W], az[W], bx[W], by[W], bz[W], cx[W], cy[W], cz[W];

  void set(int lane, const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c) noexcept {
    ax[lane] = a.x, ay[lane] = a.y, az[lane] = a.z;
    bx[lane] = b.x, by[lane] = b.y, bz[lane] = b.z;
    cx[lane] = c.x, cy[lane] = c.y, cz[lane] = c.z;
  }
};

/// Default block width: 16 floats or 8 doubles (one 512-bit register), whatever the instruction
/// set a translation unit is compiled for. A type's layout must not follow compile flags: two
/// translation units built with different `-m` flags share `MeshSdf<T>` (and any user struct that
/// holds one), and a width that changed with the flags would give them different layouts under
/// one name, which links cleanly and reads garbage. Narrower code paths loop over the lanes
/// (docs/performance.md "Block width" has the measurements).
template <class T> inline constexpr int default_block_width = sizeof(T) == 4 ? 16 : 8;

/// Squared distance from `p` to each triangle of a block. Performs exactly the operations of
/// `closest_point_triangle` per lane (same order, same selects), so `d2[l]` equals its
/// `distance2` bit for bit; divisions are computed unconditionally with a safe divisor so the
/// loop has no branch and vectorises (checked with -fopt-info-vec: 8 floats per AVX2 register at
/// -O2 and -O3, 4 with SSE2).
///
/// `detail::block_distance2_inline` is the kernel itself, always inlined, for callers that carry
/// the same `EBGEOM_VECTOR_KERNEL` options (`block_min` keeps the distances in registers);
/// inlined anywhere else it would take that caller's options (FP contraction included).
namespace detail {
template <class T, int W>
EBGEOM_VECTOR_KERNEL EBGEOM_FORCE_INLINE void
block_distance2_inline(const TriBlock<T, W>& t, const Vec3<T>& p, T (&out)[W]) noexcept {
  T res[W]; // a local result array: no aliasing with `t`, so no runtime alias check is needed
  for (int l = 0; l < W; ++l) {
    const T ax = t.ax[l], ay = t.ay[l], az = t.az[l];
    const T bx = t.bx[l], by = t.by[l], bz = t.bz[l];
    const T cx = t.cx[l], cy = t.cy[l], cz = t.cz[l];
    const T abx = bx - ax, aby = by - ay, abz = bz - az;
    const T bcx = cx - bx, bcy = cy - by, bcz = cz - bz;
    const T cax = ax - cx, cay = ay - cy, caz = az - cz;
    const T apx = p.x - ax, apy = p.y - ay, apz = p.z - az;
    const T bpx = p.x - bx, bpy = p.y - by, bpz = p.z - bz;
    const T cpx = p.x - cx, cpy = p.y - cy, cpz = p.z - cz;
    const T acx = cx - ax, acy = cy - ay, acz = cz - az;
    // n = cross(ab, c - a)
    const T nx = aby * acz - abz * acy, ny = abz * acx - abx * acz, nz = abx * acy - aby * acx;
    const T nn = nx * nx + ny * ny + nz * nz;

    // Edge 0: a -> b
    const T ee0 = abx * abx + aby * aby + abz * abz;
    const T num0 = apx * abx + apy * aby + apz * abz;
    const T r0 = num0 / (ee0 > T(0) ? ee0 : T(1));
    const T t0 = num0 <= T(0) ? T(0) : (num0 >= ee0 ? T(1) : r0);
    const bool e0 = t0 >= T(1);
    const T q0x = e0 ? bx : ax + abx * t0, q0y = e0 ? by : ay + aby * t0,
            q0z = e0 ? bz : az + abz * t0;
    const T d0x = p.x - q0x, d0y = p.y - q0y, d0z = p.z - q0z;
    const T d0 = d0x * d0x + d0y * d0y + d0z * d0z;
    // Edge 1: b -> c
    const T ee1 = bcx * bcx + bcy * bcy + bcz * bcz;
    const T num1 = bpx * bcx + bpy * bcy + bpz * bcz;
    const T r1 = num1 / (ee1 > T(0) ? ee1 : T(1));
    const T t1 = num1 <= T(0) ? T(0) : (num1 >= ee1 ? T(1) : r1);
    const bool e1 = t1 >= T(1);
    const T q1x = e1 ? cx : bx + bcx * t1, q1y = e1 ? cy : by + bcy * t1,
            q1z = e1 ? cz : bz + bcz * t1;
    const T d1x = p.x - q1x, d1y = p.y - q1y, d1z = p.z - q1z;
    const T d1 = d1x * d1x + d1y * d1y + d1z * d1z;
    // Edge 2: c -> a
    const T ee2 = cax * cax + cay * cay + caz * caz;
    const T num2 = cpx * cax + cpy * cay + cpz * caz;
    const T r2 = num2 / (ee2 > T(0) ? ee2 : T(1));
    const T t2 = num2 <= T(0) ? T(0) : (num2 >= ee2 ? T(1) : r2);
    const bool e2 = t2 >= T(1);
    const T q2x = e2 ? ax : cx + cax * t2, q2y = e2 ? ay : cy + cay * t2,
            q2z = e2 ? az : cz + caz * t2;
    const T d2x = p.x - q2x, d2y = p.y - q2y, d2z = p.z - q2z;
    const T d2 = d2x * d2x + d2y * d2y + d2z * d2z;

    T m = d0;
    m = d1 < m ? d1 : m;
    m = d2 < m ? d2 : m;

    // Face region: w_k = n · (edge_k x (p - start_k))
    const T w0 =
        nx * (aby * apz - abz * apy) + ny * (abz * apx - abx * apz) + nz * (abx * apy - aby * apx);
    const T w1 =
        nx * (bcy * bpz - bcz * bpy) + ny * (bcz * bpx - bcx * bpz) + nz * (bcx * bpy - bcy * bpx);
    const T w2 =
        nx * (cay * cpz - caz * cpy) + ny * (caz * cpx - cax * cpz) + nz * (cax * cpy - cay * cpx);
    const T h = nx * apx + ny * apy + nz * apz;
    const T fd2 = h * h / (nn > T(0) ? nn : T(1));
    // `&`, not `&&`: no short circuit, so the loop has no control flow and vectorises.
    const bool inside = (nn > T(0)) & (w0 >= T(0)) & (w1 >= T(0)) & (w2 >= T(0)) & (fd2 <= m);
    res[l] = inside ? fd2 : m;
  }
  for (int l = 0; l < W; ++l) out[l] = res[l];
}
} // namespace detail

namespace detail {
/// Supporting planes of a block's triangles seen from `p`: for each lane, the unit normal `n` of
/// the plane through the triangle's closest point `c` to `p`, perpendicular to `p - c`, and `off
/// = n · c`. The triangle (convex) lies in the half-space n · x <= off, so `n · x - off` is a lower
/// bound on the distance from any point x to it (distance to a convex set is convex). Lanes with
/// `p` on the triangle get n = 0 and off = -inf... no bound (`n · x - off = -inf`). Approximate
/// (callers add margins); same case analysis as `block_distance2`.
template <class T, int W, Isa I>
EBGEOM_VECTOR_KERNEL EBGEOM_FORCE_INLINE void
block_planes_inline(const TriBlock<T, W>& t, const Vec3<T>& p, T (&onx)[W], T (&ony)[W],
                    T (&onz)[W], T (&ooff)[W]) noexcept {
  // Two passes around the square roots (`lane_sqrt`: a library call per lane in a plain loop).
  T qxs[W], qys[W], qzs[W], gxs[W], gys[W], gzs[W], g2s[W];
  for (int l = 0; l < W; ++l) {
    const T ax = t.ax[l], ay = t.ay[l], az = t.az[l];
    const T bx = t.bx[l], by = t.by[l], bz = t.bz[l];
    const T cx = t.cx[l], cy = t.cy[l], cz = t.cz[l];
    const T abx = bx - ax, aby = by - ay, abz = bz - az;
    const T bcx = cx - bx, bcy = cy - by, bcz = cz - bz;
    const T cax = ax - cx, cay = ay - cy, caz = az - cz;
    const T apx = p.x - ax, apy = p.y - ay, apz = p.z - az;
    const T bpx = p.x - bx, bpy = p.y - by, bpz = p.z - bz;
    const T cpx = p.x - cx, cpy = p.y - cy, cpz = p.z - cz;
    const T acx = cx - ax, acy = cy - ay, acz = cz - az;
    const T nx = aby * acz - abz * acy, ny = abz * acx - abx * acz, nz = abx * acy - aby * acx;
    const T nn = nx * nx + ny * ny + nz * nz;
    auto edge = [&](T sx, T sy, T sz, T ex, T ey, T ez, T px, T py, T pz, T& qx, T& qy, T& qz) {
      const T ee = ex * ex + ey * ey + ez * ez;
      const T num = px * ex + py * ey + pz * ez;
      const T r = num / (ee > T(0) ? ee : T(1));
      const T u = num <= T(0) ? T(0) : (num >= ee ? T(1) : r);
      qx = sx + ex * u, qy = sy + ey * u, qz = sz + ez * u;
      const T dx = p.x - qx, dy = p.y - qy, dz = p.z - qz;
      return dx * dx + dy * dy + dz * dz;
    };
    T q0x, q0y, q0z, q1x, q1y, q1z, q2x, q2y, q2z;
    const T d0 = edge(ax, ay, az, abx, aby, abz, apx, apy, apz, q0x, q0y, q0z);
    const T d1 = edge(bx, by, bz, bcx, bcy, bcz, bpx, bpy, bpz, q1x, q1y, q1z);
    const T d2 = edge(cx, cy, cz, cax, cay, caz, cpx, cpy, cpz, q2x, q2y, q2z);
    T m = d0, qx = q0x, qy = q0y, qz = q0z;
    const bool s1 = d1 < m;
    m = s1 ? d1 : m, qx = s1 ? q1x : qx, qy = s1 ? q1y : qy, qz = s1 ? q1z : qz;
    const bool s2 = d2 < m;
    m = s2 ? d2 : m, qx = s2 ? q2x : qx, qy = s2 ? q2y : qy, qz = s2 ? q2z : qz;
    const T w0 =
        nx * (aby * apz - abz * apy) + ny * (abz * apx - abx * apz) + nz * (abx * apy - aby * apx);
    const T w1 =
        nx * (bcy * bpz - bcz * bpy) + ny * (bcz * bpx - bcx * bpz) + nz * (bcx * bpy - bcy * bpx);
    const T w2 =
        nx * (cay * cpz - caz * cpy) + ny * (caz * cpx - cax * cpz) + nz * (cax * cpy - cay * cpx);
    const T h = nx * apx + ny * apy + nz * apz;
    const T hn = h / (nn > T(0) ? nn : T(1));
    const T fd2 = h * hn;
    const bool inside = (nn > T(0)) & (w0 >= T(0)) & (w1 >= T(0)) & (w2 >= T(0)) & (fd2 <= m);
    qx = inside ? p.x - nx * hn : qx, qy = inside ? p.y - ny * hn : qy;
    qz = inside ? p.z - nz * hn : qz;
    const T gx = p.x - qx, gy = p.y - qy, gz = p.z - qz;
    qxs[l] = qx, qys[l] = qy, qzs[l] = qz, gxs[l] = gx, gys[l] = gy, gzs[l] = gz;
    g2s[l] = gx * gx + gy * gy + gz * gz;
  }
  T g[W];
  lane_sqrt<I>(g2s, g);
  T rx[W], ry[W], rz[W], ro[W];
  for (int l = 0; l < W; ++l) {
    const T g2 = g2s[l];
    const T inv = g2 > T(0) ? T(1) / g[l] : T(0);
    rx[l] = gxs[l] * inv, ry[l] = gys[l] * inv, rz[l] = gzs[l] * inv;
    ro[l] = g2 > T(0) ? rx[l] * qxs[l] + ry[l] * qys[l] + rz[l] * qzs[l]
                      : std::numeric_limits<T>::infinity();
  }
  for (int l = 0; l < W; ++l) onx[l] = rx[l], ony[l] = ry[l], onz[l] = rz[l], ooff[l] = ro[l];
}

/// `block_min`'s body on instruction set I, always inlined into a kernel of the same options.
template <class T, int W, Isa I>
EBGEOM_VECTOR_KERNEL EBGEOM_FORCE_INLINE LaneMin<T, W>
block_min_inline(const TriBlock<T, W>& t, const Vec3<T>& p, T b2) noexcept {
  T d2[W];
  block_distance2_inline(t, p, d2);
  if (lane_mask<LaneCmp::le, I>(d2, b2) == 0) return {b2, 0};
  return lane_min<T, W, I>(d2);
}

/// Lanes whose triangle's box (the box of its three corners) is at squared distance <= `lim`
/// from `p`, computed as the BVH computes a node's box distance (`bvh::child_dist2`): a lane
/// outside it is one that a search pruning with `lim` would skip were the triangle a leaf of its
/// own. A few operations per lane against the ~170 of `block_distance2`.
template <class T, int W, Isa I>
EBGEOM_VECTOR_KERNEL EBGEOM_FORCE_INLINE LaneMask<W>
block_box_mask_inline(const TriBlock<T, W>& t, const Vec3<T>& p, T lim) noexcept {
  T d2[W];
  for (int l = 0; l < W; ++l) {
    // Ternaries, not std::min/max: those would not inline into a function of other options.
    // One statement per axis (no table of pointers): GCC vectorises this at -O2 as well.
    const T ax = t.ax[l], bx = t.bx[l], cx = t.cx[l];
    const T ay = t.ay[l], by = t.by[l], cy = t.cy[l];
    const T az = t.az[l], bz = t.bz[l], cz = t.cz[l];
    T lox = bx < ax ? bx : ax, hix = ax < bx ? bx : ax;
    T loy = by < ay ? by : ay, hiy = ay < by ? by : ay;
    T loz = bz < az ? bz : az, hiz = az < bz ? bz : az;
    lox = cx < lox ? cx : lox, hix = hix < cx ? cx : hix;
    loy = cy < loy ? cy : loy, hiy = hiy < cy ? cy : hiy;
    loz = cz < loz ? cz : loz, hiz = hiz < cz ? cz : hiz;
    const T ex = lox - p.x, fx = p.x - hix, ey = loy - p.y, fy = p.y - hiy;
    const T ez = loz - p.z, fz = p.z - hiz;
    const T gx = ex < fx ? fx : ex, gy = ey < fy ? fy : ey, gz = ez < fz ? fz : ez;
    const T dx = gx < T(0) ? T(0) : gx, dy = gy < T(0) ? T(0) : gy, dz = gz < T(0) ? T(0) : gz;
    d2[l] = dx * dx + dy * dy + dz * dz;
  }
  return lane_mask<LaneCmp::le, I>(d2, lim);
}

/// `block_min` of a search that prunes with `lim` (>= `b2`, `bvh::prune_limit`): blocks none of
/// whose triangle boxes lies within `lim` return `mask == 0` without the distance kernel (about
/// half the blocks a mesh query scans). Same result as `block_min` whenever no triangle's computed
/// distance falls below its box's by more than the pruning slack, the search's own assumption.
template <class T, int W, Isa I>
EBGEOM_VECTOR_KERNEL EBGEOM_FORCE_INLINE LaneMin<T, W>
block_min_pruned_inline(const TriBlock<T, W>& t, const Vec3<T>& p, T b2, T lim) noexcept {
  if (block_box_mask_inline<T, W, I>(t, p, lim) == 0) return {b2, 0};
  return block_min_inline<T, W, I>(t, p, b2);
}

/// The block kernels compiled for instruction set I (`core/isa.hpp`): one out-of-line function
/// per kernel and block, with the target's attribute, so the loops vectorise for that target.
#define EBGEOM_TRI_BLOCK_KERNELS(I, TARGET)                                                        \
  template <class T, int W>                                                                        \
  TARGET EBGEOM_VECTOR_KERNEL EBGEOM_NOINLINE static void block_distance2(                         \
      const TriBlock<T, W>& t, const Vec3<T>& p, T(&out)[W]) noexcept {                            \
    block_distance2_inline(t, p, out);                                                             \
  }                                                                                                \
  template <class T, int W>                                                                        \
  TARGET EBGEOM_VECTOR_KERNEL EBGEOM_NOINLINE static LaneMin<T, W> block_min(                      \
      const TriBlock<T, W>& t, const Vec3<T>& p, T b2) noexcept {                                  \
    return block_min_inline<T, W, I>(t, p, b2);                                                    \
  }                                                                                                \
  template <class T, int W>                                                                        \
  TARGET EBGEOM_VECTOR_KERNEL EBGEOM_NOINLINE static LaneMin<T, W> block_min_pruned(               \
      const TriBlock<T, W>& t, const Vec3<T>& p, T b2, T lim) noexcept {                           \
    return block_min_pruned_inline<T, W, I>(t, p, b2, lim);                                        \
  }                                                                                                \
  template <class T, int W>                                                                        \
  TARGET EBGEOM_VECTOR_KERNEL EBGEOM_NOINLINE static void block_planes(                            \
      const TriBlock<T, W>& t, const Vec3<T>& p, T(&nx)[W], T(&ny)[W], T(&nz)[W],                  \
      T(&off)[W]) noexcept {                                                                       \
    block_planes_inline<T, W, I>(t, p, nx, ny, nz, off);                                           \
  }

/// The translation unit's own flags (`Isa::baseline`, or `native_isa` without dispatch).
template <Isa I> struct TriBlockKernels { EBGEOM_TRI_BLOCK_KERNELS(I, ) };
#if EBGEOM_ISA_DISPATCH
template <> struct TriBlockKernels<Isa::avx2> {
  EBGEOM_TRI_BLOCK_KERNELS(Isa::avx2, EBGEOM_TARGET_AVX2)
};
template <> struct TriBlockKernels<Isa::avx512> {
  EBGEOM_TRI_BLOCK_KERNELS(Isa::avx512, EBGEOM_TARGET_AVX512)
};
#endif
#undef EBGEOM_TRI_BLOCK_KERNELS
} // namespace detail

/// Squared distances from `p` to the triangles of a block (see `detail::block_distance2_inline`),
/// on instruction set I.
template <class T, int W, Isa I = native_isa>
inline void block_distance2(const TriBlock<T, W>& t, const Vec3<T>& p, T (&out)[W]) noexcept {
  detail::TriBlockKernels<I>::block_distance2(t, p, out);
}

/// The lanes of a block that can lower a search bound: `lane_min` of `block_distance2(t, p)` when
/// some lane is at squared distance <= `b2`, else `mask == 0` (most blocks a search scans; one
/// vector compare decides it). One out-of-line call, on instruction set I.
template <class T, int W, Isa I = native_isa>
inline LaneMin<T, W> block_min(const TriBlock<T, W>& t, const Vec3<T>& p, T b2) noexcept {
  return detail::TriBlockKernels<I>::block_min(t, p, b2);
}

/// `block_min` of a search pruning with `lim` (see `detail::block_min_pruned_inline`), on
/// instruction set I.
template <class T, int W, Isa I = native_isa>
inline LaneMin<T, W> block_min_pruned(const TriBlock<T, W>& t, const Vec3<T>& p, T b2,
                                      T lim) noexcept {
  return detail::TriBlockKernels<I>::block_min_pruned(t, p, b2, lim);
}

/// Supporting planes of a block's triangles seen from `p` (see `detail::block_planes_inline`), on
/// instruction set I.
template <class T, int W, Isa I = native_isa>
inline void block_planes(const TriBlock<T, W>& t, const Vec3<T>& p, T (&onx)[W], T (&ony)[W],
                         T (&onz)[W], T (&ooff)[W]) noexcept {
  detail::TriBlockKernels<I>::block_planes(t, p, onx, ony, onz, ooff);
}

} // namespace ebgeom

EBGEOM_END_EXACT_FP
