// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `MeshSdf<T, K, W>`: exact signed distance to a triangle mesh, accelerated by a K-wide BVH whose
/// leaves are structure-of-arrays blocks of W triangles (`TriBlock`), one vectorisable kernel per
/// block. Equal to `BruteForceMeshSdf` to the last bit: the block kernel performs the same
/// floating-point operations as `closest_point_triangle` (tested lane by lane), and the winning
/// triangle is finished with that scalar kernel and the same pseudonormals.
///
/// Caveat: compilers may contract a*b+c into fused multiply-adds differently in vector and scalar
/// code when FMA instructions are enabled (`-march=native`, `-mfma`); build with
/// `-ffp-contract=off` where bitwise equality with the brute force matters more than speed.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "ebgeom/bvh/build.hpp"
#include "ebgeom/bvh/simd_nodes.hpp" // <immintrin.h> where the target has SSE2 / AVX
#include "ebgeom/bvh/traverse.hpp"
#include "ebgeom/bvh/wide_bvh.hpp"
#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/geom/closest_point_triangle.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"
#include "ebgeom/mesh/triangle_mesh.hpp"
#include "ebgeom/sdf/concepts.hpp"
#include "ebgeom/sdf/mesh_closest_point.hpp"

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

template <class T, int W>
EBGEOM_VECTOR_KERNEL inline void block_distance2(const TriBlock<T, W>& t, const Vec3<T>& p,
                                                 T (&out)[W]) noexcept {
  detail::block_distance2_inline(t, p, out);
}

namespace detail {
/// Index of the lowest set bit of `x` (x != 0).
template <class U> inline int lowest_bit(U x) noexcept {
#if defined(__GNUC__) || defined(__clang__)
  if constexpr (sizeof(U) > sizeof(unsigned))
    return __builtin_ctzll(x);
  else
    return __builtin_ctz(unsigned(x));
#else
  int i = 0;
  while (!((x >> i) & 1)) ++i;
  return i;
#endif
}
} // namespace detail

/// One bit per lane of a W-wide block.
template <int W> using LaneMask = std::conditional_t<(W > 32), std::uint64_t, std::uint32_t>;

namespace detail {
enum class LaneCmp { le, eq };

/// Bytes per register with which `lane_mask` compares W values of T: 64 with AVX-512, 32 with AVX
/// (W values filling whole registers), else 0 (the plain loop).
template <class T, int W> constexpr int lane_mask_register_bytes() noexcept {
  if constexpr (!std::is_same_v<T, float> && !std::is_same_v<T, double>) return 0;
#if defined(__AVX512F__)
  if (W * sizeof(T) % 64 == 0) return 64;
#endif
#if defined(__AVX__)
  if (W * sizeof(T) % 32 == 0) return 32;
#endif
  return 0;
}

#if defined(__AVX__)
/// `lane_mask` of the Bytes / sizeof(T) values at `v`: one compare, into a mask register with
/// AVX-512, or followed by `movemask` with AVX.
template <int Bytes, LaneCmp C, class T>
EBGEOM_FORCE_INLINE std::uint32_t register_mask(const T* v, T b) noexcept {
  constexpr int pred = C == LaneCmp::le ? _CMP_LE_OQ : _CMP_EQ_OQ;
#if defined(__AVX512F__)
  if constexpr (Bytes == 64) {
    if constexpr (sizeof(T) == 8)
      return _mm512_cmp_pd_mask(_mm512_loadu_pd(v), _mm512_set1_pd(b), pred);
    else
      return _mm512_cmp_ps_mask(_mm512_loadu_ps(v), _mm512_set1_ps(b), pred);
  }
#endif
  if constexpr (Bytes == 32) {
    if constexpr (sizeof(T) == 8)
      return unsigned(
          _mm256_movemask_pd(_mm256_cmp_pd(_mm256_loadu_pd(v), _mm256_set1_pd(b), pred)));
    else
      return unsigned(
          _mm256_movemask_ps(_mm256_cmp_ps(_mm256_loadu_ps(v), _mm256_set1_ps(b), pred)));
  }
  return 0; // not reached: `lane_mask_register_bytes` gives 64 or 32 here
}
#endif

/// Bit l set where `v[l] <= b` (`LaneCmp::le`) or `v[l] == b` (`eq`); false for NaN lanes, as the
/// C++ comparisons. GCC 12 builds such a mask from vector compares with shifts, ors and shuffles
/// (with `lane_min`, 11% of a double ogre query's profile); with AVX-512 one compare gives it (a
/// mask register), with AVX a compare and a `movemask`. The plain loop is the reference and the
/// fallback.
template <LaneCmp C, class T, int W>
EBGEOM_FORCE_INLINE LaneMask<W> lane_mask(const T (&v)[W], T b) noexcept {
  LaneMask<W> mask = 0;
#if defined(__AVX__)
  constexpr int bytes = lane_mask_register_bytes<T, W>();
  if constexpr (bytes > 0) {
    constexpr int n = bytes / int(sizeof(T)); // lanes per register
    for (int r = 0; r < W / n; ++r)
      mask |= LaneMask<W>(register_mask<bytes, C>(v + r * n, b)) << (r * n);
    return mask;
  }
#endif
  for (int l = 0; l < W; ++l) mask |= LaneMask<W>(C == LaneCmp::le ? v[l] <= b : v[l] == b) << l;
  return mask;
}
} // namespace detail

/// The smallest of a block's W lane values and the lanes holding it (bit l of `mask`).
template <class T, int W> struct LaneMin {
  T min;
  LaneMask<W> mask;
};

/// `LaneMin` of W values: a tree of pairwise minima and a compare, plain loops that vectorise,
/// instead of W dependent scalar steps (those were a sixth of a mesh query). Exact: the minimum
/// does not depend on the order. A NaN lane counts as +infinity (a NaN distance never wins, as in
/// the brute force's `d2 < best2`) and hides no other lane.
template <class T, int W>
EBGEOM_VECTOR_KERNEL inline LaneMin<T, W> lane_min(const T (&v)[W]) noexcept {
  T u[W], t[W];
  for (int l = 0; l < W; ++l) u[l] = v[l] == v[l] ? v[l] : std::numeric_limits<T>::infinity();
  for (int l = 0; l < W; ++l) t[l] = u[l];
  if constexpr ((W & (W - 1)) == 0) { // halvings of constant length: each one vectorises
    if constexpr (W >= 64)
      for (int l = 0; l < 32; ++l) t[l] = t[l + 32] < t[l] ? t[l + 32] : t[l];
    if constexpr (W >= 32)
      for (int l = 0; l < 16; ++l) t[l] = t[l + 16] < t[l] ? t[l + 16] : t[l];
    if constexpr (W >= 16)
      for (int l = 0; l < 8; ++l) t[l] = t[l + 8] < t[l] ? t[l + 8] : t[l];
    if constexpr (W >= 8)
      for (int l = 0; l < 4; ++l) t[l] = t[l + 4] < t[l] ? t[l + 4] : t[l];
    if constexpr (W >= 4)
      for (int l = 0; l < 2; ++l) t[l] = t[l + 2] < t[l] ? t[l + 2] : t[l];
    if constexpr (W >= 2) t[0] = t[1] < t[0] ? t[1] : t[0];
  } else {
    for (int n = W; n > 1;) {
      const int h = n / 2, o = n - h; // pairs l with l + o; an odd middle lane waits a round
      for (int l = 0; l < h; ++l) t[l] = t[l + o] < t[l] ? t[l + o] : t[l];
      n = o;
    }
  }
  const T m = t[0];
  return {m, detail::lane_mask<detail::LaneCmp::eq>(u, m)};
}

/// The lanes of a block that can lower a search bound: `lane_min` of `block_distance2(t, p)` when
/// some lane is at squared distance <= `b2`, else `mask == 0` (most blocks a search scans; one
/// vector compare decides it). One out-of-line call.
template <class T, int W>
EBGEOM_VECTOR_KERNEL inline LaneMin<T, W> block_min(const TriBlock<T, W>& t, const Vec3<T>& p,
                                                    T b2) noexcept {
  T d2[W];
  detail::block_distance2_inline(t, p, d2);
  if (detail::lane_mask<detail::LaneCmp::le>(d2, b2) == 0) return {b2, 0};
  return lane_min<T, W>(d2);
}

/// Supporting planes of a block's triangles seen from `p`: for each lane, the unit normal `n` of
/// the plane through the triangle's closest point `c` to `p`, perpendicular to `p - c`, and `off
/// = n · c`. The triangle (convex) lies in the half-space n · x <= off, so `n · x - off` is a lower
/// bound on the distance from any point x to it (distance to a convex set is convex). Lanes with
/// `p` on the triangle get n = 0 and off = -inf... no bound (`n · x - off = -inf`). Approximate
/// (callers add margins); same case analysis as `block_distance2`.
template <class T, int W>
EBGEOM_VECTOR_KERNEL inline void block_planes(const TriBlock<T, W>& t, const Vec3<T>& p,
                                              T (&onx)[W], T (&ony)[W], T (&onz)[W],
                                              T (&ooff)[W]) noexcept {
  T rx[W], ry[W], rz[W], ro[W];
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
    const T g2 = gx * gx + gy * gy + gz * gz;
    const T inv = g2 > T(0) ? T(1) / std::sqrt(g2) : T(0);
    rx[l] = gx * inv, ry[l] = gy * inv, rz[l] = gz * inv;
    ro[l] = g2 > T(0) ? rx[l] * qx + ry[l] * qy + rz[l] * qz : std::numeric_limits<T>::infinity();
  }
  for (int l = 0; l < W; ++l) onx[l] = rx[l], ony[l] = ry[l], onz[l] = rz[l], ooff[l] = ro[l];
}

/// Squared distances from `p` to `n` boxes stored as structure of arrays (`lo_x[i]`, ...).
template <class T>
EBGEOM_VECTOR_KERNEL inline void
boxes_distance2(std::size_t n, const T* EBGEOM_RESTRICT lx, const T* EBGEOM_RESTRICT ly,
                const T* EBGEOM_RESTRICT lz, const T* EBGEOM_RESTRICT hx,
                const T* EBGEOM_RESTRICT hy, const T* EBGEOM_RESTRICT hz, const Vec3<T>& p,
                T* EBGEOM_RESTRICT out) noexcept {
  const T px = p.x, py = p.y, pz = p.z;
  // Ternaries, not std::max: the kernel's optimisation attribute keeps std::max from inlining.
  for (std::size_t i = 0; i < n; ++i) {
    T ax = lx[i] - px, bx = px - hx[i], ay = ly[i] - py, by = py - hy[i], az = lz[i] - pz,
      bz = pz - hz[i];
    ax = ax < bx ? bx : ax, ay = ay < by ? by : ay, az = az < bz ? bz : az;
    ax = ax < T(0) ? T(0) : ax, ay = ay < T(0) ? T(0) : ay, az = az < T(0) ? T(0) : az;
    out[i] = ax * ax + ay * ay + az * az;
  }
}

/// Exact signed distance to a triangle mesh through a BVH (see the file comment).
///
/// - `K`: BVH arity (2..16; 4 is the default, 8 suits AVX-512), `W`: triangles per leaf block.
/// - Sign: the pseudonormal of the closest feature (Bærentzen & Aanæs 2005): exact for closed,
///   consistently oriented, manifold meshes (check with `validate`).
/// - Memory: the `TriangleMesh` (~48 B/triangle in float) + blocks (36 B per lane, leaves padded
///   to whole blocks) + 4 B per lane of triangle ids + nodes; `memory_bytes()` reports it.
/// - Queries are O(log n) on average, allocation-free, and thread-safe (immutable object).
template <class T, int K = 4, int W = default_block_width<T>> class MeshSdf {
 public:
  static_assert(W >= 1 && W <= 64, "MeshSdf: block width W must be in 1..64");
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  static constexpr int arity = K;
  static constexpr int block_width = W;

  /// Default build: binned SAH with leaves of at most one block, filled in whole blocks.
  static bvh::BuildOptions default_build_options() noexcept {
    bvh::BuildOptions o;
    o.max_leaf_size = std::uint32_t(W);
    o.block = std::uint32_t(W);
    return o;
  }

  /// Builds the BVH over `mesh`. Errors: `empty` (no triangles), `non_finite` (a NaN or infinite
  /// coordinate: a NaN box would silently prune everything), `bad_index`/`size_mismatch` for a
  /// hand-made mesh whose arrays disagree.
  static Result<MeshSdf> make(TriangleMesh<T> mesh,
                              const bvh::BuildOptions& options = default_build_options()) {
    Error e = check(mesh);
    if (e.code != ErrorCode::ok) return e;
    MeshSdf s;
    s.mesh_ = std::move(mesh);
    const std::size_t n = s.mesh_.triangle_count();
    std::vector<Aabb<T>> boxes(n);
    std::vector<Vec3<T>> centroids(n);
    for (std::size_t t = 0; t < n; ++t) {
      boxes[t] = s.mesh_.triangle_bounds(t);
      centroids[t] = boxes[t].center();
    }
    s.bvh_ = bvh::flatten<K>(
        bvh::build(Span<const Aabb<T>>(boxes), Span<const Vec3<T>>(centroids), options));
    s.pack_blocks();
    s.slack_ = rounding_slack(s.bvh_.box);
    s.plane_margin_ = plane_margin(s.bvh_.box);
    return s;
  }

  /// Triangulates a polygon soup (`make_triangle_mesh`) and builds.
  static Result<MeshSdf> build(const PolygonSoup<T>& soup,
                               const bvh::BuildOptions& options = default_build_options()) {
    Result<TriangleMesh<T>> m = make_triangle_mesh(soup);
    if (!m) return m.error();
    return make(std::move(*m), options);
  }

  /// Signed distance at `p` (< 0 inside). NaN when `p` has a NaN or infinite coordinate (as every
  /// query of this class: no sign is defined there).
  T operator()(const Vec3<T>& p) const noexcept { return closest(p).distance; }

  /// Closest point, triangle, feature and signed distance. Equal to
  /// `BruteForceMeshSdf::closest` bit for bit, triangle included (exact ties: lowest index).
  MeshClosestPoint<T> closest(const Vec3<T>& p) const noexcept {
    return search(p, std::numeric_limits<T>::infinity());
  }

  /// As `closest`, but only looks for surface points within `max_distance` (a narrow band):
  /// returns `triangle == invalid_triangle` and `distance = +inf` when there is none. Faster than
  /// `closest` far from the surface.
  MeshClosestPoint<T> closest_within(const Vec3<T>& p, T max_distance) const noexcept {
    if (!(max_distance >= T(0))) return {};
    const T b2 = max_distance * max_distance;
    return search(p, std::nextafter(b2, std::numeric_limits<T>::infinity()));
  }

  /// Bounded query for grid samplers (`sample_grid` detects it): returns exactly `(*this)(p)` (bit
  /// for bit) whenever |S(p)| <= `max_abs`; otherwise +infinity, whose sign means nothing (the
  /// sign far from the surface is not cheap here). The search radius is widened by a few ulps so
  /// that rounding never misses a surface point at distance `max_abs`. As `closest_within`:
  /// faster than `operator()` when `max_abs` is small. Thread-safe, allocation-free.
  T bounded(const Vec3<T>& p, T max_abs) const noexcept {
    const T r = max_abs + max_abs * (T(4) * std::numeric_limits<T>::epsilon());
    return closest_within(p, r).distance;
  }

  /// Unsigned distance (no sign decision).
  T unsigned_distance(const Vec3<T>& p) const noexcept {
    if (!all_finite(p)) return std::numeric_limits<T>::quiet_NaN();
    T best2 = std::numeric_limits<T>::infinity();
    std::uint32_t best = bvh::ChildRef::none;
    nearest_slot(p, best2, best);
    return std::sqrt(best2);
  }

  /// Exact signed distances at a block of lattice samples, bit for bit `(*this)(pts[l])` for
  /// every `l` (`sample_grid` detects this method and calls it once per 8^3 tile).
  ///
  /// `pts` holds `dims[0] * dims[1] * dims[2]` points, x fastest (`pts[x + dims[0] * (y +
  /// dims[1] * z)]`), with each coordinate monotone along its axis (a block of a regular grid);
  /// `out` receives the values in the same order. Any points give exact values; the lattice order
  /// only makes it fast.
  ///
  /// How: one BVH search at a sample near the block's centre, q, bounds every sample's distance
  /// (1-Lipschitz: |S(p)| <= |S(q)| + |p - q| <= U), so every sample's nearest triangle lies in a
  /// leaf within U of the block's bounding box; those leaves are collected once (nearest to the
  /// centre first). A long list is split by octants, each filtering its parent's list with its own
  /// bound. Each sample then scans its list (a vectorised box test, then the blocks of the boxes
  /// still within the best distance), starting from the block of the previous sample's nearest
  /// triangle, whose exact distance is a tight initial bound. Every triangle the per-point search
  /// could pick lies in a scanned leaf and the same kernel and tie rule (lowest index) decide, so
  /// the results are the per-point results. Allocates O(candidate leaves) scratch per call;
  /// thread-safe.
  void eval_lattice(Span<const Vec3<T>> pts, const std::array<std::size_t, 3>& dims,
                    Span<T> out) const {
    const std::size_t n = dims[0] * dims[1] * dims[2];
    EBGEOM_ASSERT(pts.size() == n && out.size() == n);
    if (n == 0) return;
    for (std::size_t l = 0; l < n; ++l)
      if (!all_finite(pts[l])) { // the lattice bounds below assume finite samples
        for (std::size_t i = 0; i < n; ++i) out[i] = (*this)(pts[i]);
        return;
      }
    LatticeJob job{pts.data(), dims, std::vector<std::uint32_t>(n, bvh::ChildRef::none),
                   {},         {},   bvh::ChildRef::none};
    job.d2.resize(64);
    solve_lattice(job, {{0, 0, 0}}, dims, nullptr, 0);
    for (std::size_t l = 0; l < n; ++l) out[l] = finish(pts[l], job.slot[l]).distance;
  }

  /// Moves the vertices: `moved` must have the same faces as the mesh was built from (same
  /// triangulation). Normals are recomputed, boxes refitted; the tree topology is kept (queries
  /// stay exact; their speed degrades if the motion is large — rebuild then).
  Error refit(const PolygonSoup<T>& moved) {
    Result<TriangleMesh<T>> m = make_triangle_mesh(moved);
    if (!m) return m.error();
    if (m->triangles != mesh_.triangles)
      return {ErrorCode::invalid_argument,
              "refit: the moved mesh's triangles differ from the built mesh's (same faces "
              "required)"};
    mesh_ = std::move(*m);
    fill_blocks();
    bvh::refit(bvh_, [&](std::uint32_t first_block, std::uint32_t count) {
      Aabb<T> b;
      for (std::uint32_t s = 0; s < count; ++s)
        b.extend(mesh_.triangle_bounds(block_tri_[first_block * std::size_t(W) + s]));
      return b;
    });
    return {};
  }

  Aabb<T> bounds() const noexcept { return bvh_.box; }
  const TriangleMesh<T>& mesh() const noexcept { return mesh_; }
  /// The BVH; its leaves hold (first block, triangle count), not slots of `prim` (cleared).
  const bvh::WideBvh<T, K>& tree() const noexcept { return bvh_; }
  std::size_t triangle_count() const noexcept { return mesh_.triangle_count(); }
  /// Heap bytes of the mesh, the blocks, the block triangle ids and the BVH nodes.
  std::size_t memory_bytes() const noexcept {
    return mesh_.memory_bytes() + blocks_.size() * sizeof(TriBlock<T, W>) +
           block_tri_.size() * sizeof(std::uint32_t) + bvh_.memory_bytes();
  }

 private:
  static Error check(const TriangleMesh<T>& m) {
    const std::size_t nt = m.triangles.size();
    if (nt == 0) return {ErrorCode::empty, "mesh SDF: the mesh has no triangles"};
    if (nt >= std::size_t(std::numeric_limits<std::uint32_t>::max()) / std::size_t(W))
      return {ErrorCode::size_mismatch, "mesh SDF: too many triangles"};
    if (m.face_normals.size() != nt || m.edge_links.size() != nt ||
        m.vertex_normals.size() != m.vertices.size() ||
        (!m.source_faces.empty() && m.source_faces.size() != nt))
      return {ErrorCode::size_mismatch, "mesh SDF: normal arrays do not match the mesh"};
    for (std::size_t v = 0; v < m.vertices.size(); ++v)
      if (!all_finite(m.vertices[v]))
        return {ErrorCode::non_finite,
                "mesh SDF: vertex " + std::to_string(v) + " has a NaN or infinite coordinate"};
    for (std::size_t t = 0; t < nt; ++t) {
      for (Index i : m.triangles[t])
        if (i >= m.vertices.size())
          return {ErrorCode::bad_index, "mesh SDF: triangle " + std::to_string(t) +
                                            " uses vertex " + std::to_string(i) +
                                            " >= " + std::to_string(m.vertices.size())};
      for (Index link : m.edge_links[t])
        if (!m.valid_link(link))
          return {ErrorCode::bad_index, "mesh SDF: triangle " + std::to_string(t) +
                                            " has edge link " + std::to_string(link) +
                                            ", neither a triangle nor a valid code"};
    }
    return {};
  }

  /// Re-points every leaf at whole blocks: (first block, count), padding the last block of each
  /// leaf with copies of the leaf's last triangle (same distance, never preferred: ties keep the
  /// first lane).
  void pack_blocks() {
    std::uint32_t next_block = 0;
    auto remap = [&](bvh::ChildRef& r) {
      const std::uint32_t nb = (r.count + std::uint32_t(W) - 1) / std::uint32_t(W);
      // Ascending ids within the leaf: `scan_blocks` takes the lowest minimal lane as the lowest
      // id.
      std::sort(bvh_.prim.begin() + r.index, bvh_.prim.begin() + r.index + r.count);
      for (std::uint32_t s = 0; s < nb * std::uint32_t(W); ++s)
        block_tri_.push_back(bvh_.prim[r.index + std::min(s, r.count - 1)]);
      r.index = next_block;
      next_block += nb;
    };
    for (auto& node : bvh_.nodes)
      for (auto& c : node.child)
        if (c.is_leaf()) remap(c);
    if (bvh_.root.is_leaf()) remap(bvh_.root);
    blocks_.resize(next_block);
    bvh_.prim.clear();
    bvh_.prim.shrink_to_fit();
    fill_blocks();
  }

  void fill_blocks() {
    for (std::size_t s = 0; s < block_tri_.size(); ++s) {
      const std::uint32_t t = block_tri_[s];
      blocks_[s / W].set(int(s % W), mesh_.corner(t, 0), mesh_.corner(t, 1), mesh_.corner(t, 2));
    }
  }

  /// Nearest triangle slot (block lane) by squared distance; `best2` is the initial bound.
  void nearest_slot(const Vec3<T>& p, T& best2, std::uint32_t& best) const noexcept {
    bvh::nearest<true>(
        bvh_, p, best2,
        [&](std::uint32_t first_block, std::uint32_t count, T& b2) noexcept {
          scan_blocks(first_block, count, p, b2, best);
        },
        slack_);
  }

  MeshClosestPoint<T> search(const Vec3<T>& p, T bound2) const noexcept {
    if (!all_finite(p)) {
      MeshClosestPoint<T> r;
      r.distance = std::numeric_limits<T>::quiet_NaN();
      return r;
    }
    T best2 = bound2;
    std::uint32_t best = bvh::ChildRef::none;
    nearest_slot(p, best2, best);
    return finish(p, best);
  }

  /// Candidate leaves of a lattice block, structure of arrays (boxes padded with empty ones to a
  /// multiple of 16 so the box-distance loop has no remainder).
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
      for (int l = 0; l < W; ++l)
        pnx.push_back(0), pny.push_back(0), pnz.push_back(0), poff.push_back(0);
    }
    void add_from(const LeafList& o, std::size_t i) {
      lo_x.push_back(o.lo_x[i]), lo_y.push_back(o.lo_y[i]), lo_z.push_back(o.lo_z[i]);
      hi_x.push_back(o.hi_x[i]), hi_y.push_back(o.hi_y[i]), hi_z.push_back(o.hi_z[i]);
      first.push_back(o.first[i]), count.push_back(o.count[i]), root.push_back(o.root[i]);
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
  void collect_leaves(const Aabb<T>& box, T lim2, const Vec3<T>& c, LeafList& out) const {
    struct Item {
      T key;
      Aabb<T> b;
      bvh::ChildRef r;
    };
    std::vector<Item> items;
    if (bvh_.root.is_leaf()) {
      items.push_back({T(0), bvh_.box, bvh_.root});
    } else if (!bvh_.root.is_empty()) {
      bvh::FixedStack<std::uint32_t, bvh::WideBvh<T, K>::stack_capacity> todo;
      todo.push(bvh_.root.index);
      while (!todo.empty()) {
        const auto& nd = bvh_.nodes[todo.pop()];
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

  /// Scans blocks [first, first + ceil(count / W)) at `p`, lowering `b2`/`best` (ties: lowest
  /// triangle index, as the brute force).
  EBGEOM_FORCE_INLINE void scan_blocks(std::uint32_t first_block, std::uint32_t count,
                                       const Vec3<T>& p, T& b2,
                                       std::uint32_t& best) const noexcept {
    const TriBlock<T, W>* blocks = blocks_.data();
    const std::uint32_t* tri = block_tri_.data();
    const std::uint32_t nb = (count + std::uint32_t(W) - 1) / std::uint32_t(W);
    for (std::uint32_t i = 0; i < nb; ++i) {
      const LaneMin<T, W> lm = block_min(blocks[first_block + i], p, b2);
      // No lane can win, or only tie with no best yet (as the brute force, which keeps the first
      // triangle strictly below the initial bound).
      if (lm.mask == 0 || !(lm.min < b2 || best != bvh::ChildRef::none)) continue;
      // Lanes of a leaf hold ascending triangle ids (`pack_blocks`): the lowest minimal lane has
      // the lowest id among this block's ties.
      const std::uint32_t slot =
          (first_block + i) * std::uint32_t(W) + std::uint32_t(detail::lowest_bit(lm.mask));
      if (lm.min < b2 || tri[slot] < tri[best]) {
        b2 = lm.min;
        best = slot;
      }
    }
  }

  /// Nearest slot of `p` among the leaves of `list` (a superset of the leaves the per-point
  /// search needs), starting from the block of slot `seed` (or none).
  std::uint32_t scan_list(const LeafList& list, LeafList& pl, const Vec3<T>& p, std::uint32_t seed,
                          std::vector<T>& d2s) const noexcept {
    T b2 = std::numeric_limits<T>::infinity();
    std::uint32_t best = bvh::ChildRef::none;
    std::uint32_t seed_block = bvh::ChildRef::none;
    if (seed != bvh::ChildRef::none) {
      seed_block = seed / std::uint32_t(W);
      scan_blocks(seed_block, std::uint32_t(W), p, b2, best);
    }
    const std::size_t n = list.size(), np = list.lo_x.size();
    T* EBGEOM_RESTRICT d2 = d2s.data();
    const T* EBGEOM_RESTRICT lx = list.lo_x.data();
    const T* EBGEOM_RESTRICT ly = list.lo_y.data();
    const T* EBGEOM_RESTRICT lz = list.lo_z.data();
    const T* EBGEOM_RESTRICT hx = list.hi_x.data();
    const T* EBGEOM_RESTRICT hy = list.hi_y.data();
    const T* EBGEOM_RESTRICT hz = list.hi_z.data();
    boxes_distance2(np, lx, ly, lz, hx, hy, hz, p, d2);
    // Supporting planes bound each triangle's distance from below (`block_planes`). Rounding: the
    // planes carry errors of a few ulps of the coordinates (`plane_margin_`) and the kernel's
    // squared distances those `prune_limit` allows for; the margins exceed both.
    const T rel = T(256) * std::numeric_limits<T>::epsilon();
    T lim = bvh::prune_limit(b2, slack_);
    T r = std::sqrt(lim) * (T(1) + rel) + plane_margin_;
    // Branch-free compaction of the boxes within the bound (few of them), then the scan.
    std::uint32_t* EBGEOM_RESTRICT idx = reinterpret_cast<std::uint32_t*>(d2 + np);
    std::size_t m = 0;
    for (std::size_t i = 0; i < n; ++i) {
      idx[m] = std::uint32_t(i);
      m += d2[i] < lim;
    }
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t i = idx[k];
      if (!(d2[i] < lim) || (list.first[i] == seed_block && list.count[i] <= std::uint32_t(W)))
        continue;
      const std::size_t j = list.root[i];
      if (pl.planes[j]) {
        const T* nx = pl.pnx.data() + j * W;
        const T* ny = pl.pny.data() + j * W;
        const T* nz = pl.pnz.data() + j * W;
        const T* of = pl.poff.data() + j * W;
        T lb = std::numeric_limits<T>::infinity();
        for (int l = 0; l < W; ++l)
          lb = std::min(lb, nx[l] * p.x + ny[l] * p.y + nz[l] * p.z - of[l]);
        if (lb > r) continue;
      }
      scan_blocks(list.first[i], list.count[i], p, b2, best);
      if (list.count[i] <= std::uint32_t(W) && !pl.planes[j]) {
        T(&nx)[W] = *reinterpret_cast<T(*)[W]>(pl.pnx.data() + j * W);
        T(&ny)[W] = *reinterpret_cast<T(*)[W]>(pl.pny.data() + j * W);
        T(&nz)[W] = *reinterpret_cast<T(*)[W]>(pl.pnz.data() + j * W);
        T(&of)[W] = *reinterpret_cast<T(*)[W]>(pl.poff.data() + j * W);
        block_planes(blocks_[list.first[i]], p, nx, ny, nz, of);
        pl.planes[j] = 1;
      }
      lim = bvh::prune_limit(b2, slack_);
      r = std::sqrt(lim) * (T(1) + rel) + plane_margin_;
    }
    return best;
  }

  /// Samples [a, b) of the job's lattice block; `parent` lists the candidate leaves of an
  /// enclosing block (nullptr: the whole BVH).
  void solve_lattice(LatticeJob& job, const std::array<std::size_t, 3>& a,
                     const std::array<std::size_t, 3>& b, LeafList* parent, int level) const {
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
        nearest_slot(q, b2, best);
        job.slot[qi] = best;
      } else {
        job.slot[qi] = scan_list(*parent, job.lists[0], q, job.last, job.d2);
      }
      job.last = job.slot[qi];
    }
    {
      T dq2 = std::numeric_limits<T>::infinity();
      std::uint32_t dummy = bvh::ChildRef::none;
      scan_blocks(job.slot[qi] / std::uint32_t(W), std::uint32_t(W), q, dq2, dummy);
      const T eps = std::numeric_limits<T>::epsilon();
      const T u = (std::sqrt(dq2) + std::sqrt(box.max_distance2(q))) * (T(1) + T(64) * eps);
      const T lim2 = bvh::prune_limit(u * u, slack_);
      if (parent == nullptr) {
        collect_leaves(box, lim2, box.center(), list);
      } else {
        list.clear();
        for (std::size_t i = 0; i < parent->size(); ++i) {
          const Aabb<T> lb({parent->lo_x[i], parent->lo_y[i], parent->lo_z[i]},
                           {parent->hi_x[i], parent->hi_y[i], parent->hi_z[i]});
          if (box_box_distance2(lb, box) < lim2) list.add_from(*parent, i);
        }
        list.pad();
      }
    }
    if (job.d2.size() < 2 * list.lo_x.size()) job.d2.resize(2 * list.lo_x.size());
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
        if (!empty) solve_lattice(job, ca, cb, &list, level + 1);
      }
      return;
    }
    for (std::size_t z = a[2]; z < b[2]; ++z)
      for (std::size_t y = a[1]; y < b[1]; ++y)
        for (std::size_t x = a[0]; x < b[0]; ++x) {
          const std::size_t l = index(x, y, z);
          if (job.slot[l] != bvh::ChildRef::none) continue;
          job.slot[l] = scan_list(list, job.lists[0], job.pts[l], job.last, job.d2);
          job.last = job.slot[l];
        }
  }

  /// Signed distance etc. at `p` from its nearest slot (as `search`).
  MeshClosestPoint<T> finish(const Vec3<T>& p, std::uint32_t best) const noexcept {
    MeshClosestPoint<T> r;
    if (best == bvh::ChildRef::none) return r;
    const std::uint32_t t = block_tri_[best];
    const auto& tri = mesh_.triangles[t];
    const TriangleClosestPoint<T> cp = closest_point_triangle(
        p, mesh_.vertices[tri[0]], mesh_.vertices[tri[1]], mesh_.vertices[tri[2]]);
    r.distance =
        signed_distance_from(p, cp.point, cp.distance2, feature_pseudonormal(mesh_, t, cp.feature));
    r.point = cp.point;
    r.triangle = t;
    r.feature = cp.feature;
    return r;
  }

  static constexpr std::size_t lattice_split_leaves = 128;

  /// Absolute error bound of a supporting plane's value (`block_planes`): 1024 ulps of the largest
  /// coordinate or extent.
  static T plane_margin(const Aabb<T>& box) noexcept {
    const T s = std::max(
        {max_component(abs(box.lo)), max_component(abs(box.hi)), max_component(box.extent())});
    return T(1024) * std::numeric_limits<T>::epsilon() * s;
  }

  /// Absolute pruning slack: a bound on the rounding of a triangle's squared distance near the
  /// surface (about eps · size²), so ties with the brute force are never pruned away.
  static T rounding_slack(const Aabb<T>& box) noexcept {
    const T s = std::max(
        {max_component(abs(box.lo)), max_component(abs(box.hi)), max_component(box.extent())});
    return T(64) * std::numeric_limits<T>::epsilon() * s * s;
  }

  TriangleMesh<T> mesh_;
  T slack_ = 0;
  T plane_margin_ = 0;
  bvh::WideBvh<T, K> bvh_;
  std::vector<TriBlock<T, W>> blocks_;
  std::vector<std::uint32_t> block_tri_; ///< triangle id of each block lane
};

} // namespace ebgeom
