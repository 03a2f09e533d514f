// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Generalized winding numbers of triangle meshes (Jacobson, Kavan & Sorkine-Hornung 2013):
/// w(p) = Σ_t Ω_t(p) / 4π, the signed solid angles of the triangles seen from p over the full
/// sphere. w = 1 inside and 0 outside a closed, outward-oriented surface; it degrades gracefully
/// on holes, duplicates, flipped patches and self-intersections, so "inside where w > 1/2" is a
/// robust inside test for imperfect meshes.
///
/// - `winding_number(mesh, p)`: the exact sum, O(n) per query (the oracle).
/// - `FastWindingNumber<T, K>`: the hierarchical approximation of Barill, Dickson, Schmidt,
///   Levin & Jacobson 2018 ("Fast winding numbers for soups and clouds"): a K-wide BVH over the
///   triangles, one order-2 dipole cluster (`DipoleCluster`, geom/solid_angle.hpp) per child of
///   every node; a child whose cluster centre is farther from p than β times its radius
///   contributes its far-field expansion, a near leaf its exact solid angles. O(log n) per query
///   for points away from the surface; the error decays like β⁻³.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "ebgeom/bvh/build.hpp"
#include "ebgeom/bvh/traverse.hpp"
#include "ebgeom/bvh/wide_bvh.hpp"
#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/geom/solid_angle.hpp"
#include "ebgeom/mesh/triangle_mesh.hpp"

namespace ebgeom {

/// Exact generalized winding number at `p` of the triangles `tri(i, a, b, c)`, i in [0, n): the sum
/// of their signed solid angles (`solid_angle`) over 4π, accumulated in double. Finite for every
/// finite p (on the surface it is some finite value; the distance there is 0 anyway). O(n).
template <class T, class TriFn>
T winding_number(std::size_t n, TriFn&& tri, const Vec3<T>& p) noexcept {
  constexpr double inv4pi = 0.07957747154594767;
  double sum = 0;
  Vec3<T> a, b, c;
  for (std::size_t i = 0; i < n; ++i) {
    tri(i, a, b, c);
    sum += double(solid_angle(p, a, b, c));
  }
  return T(sum * inv4pi);
}

/// Exact generalized winding number of `mesh` at `p` (1 inside, 0 outside a closed outward
/// surface). O(n), thread-safe.
/// Computed in double whatever T.
template <class T> T winding_number(const TriangleMesh<T>& mesh, const Vec3<T>& p) noexcept {
  const auto d = [](const Vec3<T>& v) {
    return Vec3<double>{double(v.x), double(v.y), double(v.z)};
  };
  return T(winding_number<double>(
      mesh.triangle_count(),
      [&](std::size_t t, Vec3<double>& a, Vec3<double>& b, Vec3<double>& c) {
        a = d(mesh.corner(t, 0)), b = d(mesh.corner(t, 1)), c = d(mesh.corner(t, 2));
      },
      d(p)));
}

/// Options of `FastWindingNumber`.
struct WindingOptions {
  /// Accuracy: a cluster is approximated when |p - centre| > beta · radius. Larger is more
  /// accurate and slower; the error decays like beta⁻³. Barill et al. use 2. Must be > 0.
  double beta = 2;
  /// Triangles per BVH leaf (exact solid angles are summed in near leaves).
  std::uint32_t max_leaf_size = 8;
};

/// Dipole data of the K children of one BVH node, structure of arrays so one loop evaluates all
/// K far fields: centre (3), order-1 moment (3), order-2 moment (9) and (beta·radius)² (1):
/// 16·K scalars (K = 4, float: 256 B). Empty slots have `far2 = +inf` and zero moments.
template <class T, int K> struct WindingNode {
  T cx[K], cy[K], cz[K];
  T nx[K], ny[K], nz[K];
  T m[9][K]; ///< m[3 i + j][k] = M_ij of child k
  T far2[K];
};

/// BVH-accelerated generalized winding number (Barill et al. 2018; see the file comment).
/// Owns a copy of the triangles in leaf order (structure of arrays, 36 B per triangle in float),
/// the BVH and one `WindingNode` per BVH node. Immutable; queries are const, allocation-free and
/// thread-safe. `exact(p)` is the O(n) oracle over the same triangles.
template <class T, int K = 4> class FastWindingNumber {
 public:
  static_assert(K >= 2 && K <= 16, "FastWindingNumber<T, K> needs 2 <= K <= 16");
  using scalar_type = T;

  /// Builds over `mesh`'s triangles. Errors: `empty` (no triangles), `invalid_argument`
  /// (beta <= 0 or not finite), `non_finite` (a NaN/inf coordinate). O(n log n).
  static Result<FastWindingNumber> make(const TriangleMesh<T>& mesh,
                                        const WindingOptions& options = {}) {
    const std::size_t n = mesh.triangle_count();
    if (n == 0) return Error{ErrorCode::empty, "winding number: the mesh has no triangles"};
    if (n >= std::size_t(std::numeric_limits<std::uint32_t>::max()))
      return Error{ErrorCode::size_mismatch, "winding number: too many triangles"};
    if (!(options.beta > 0) || !std::isfinite(options.beta))
      return Error{ErrorCode::invalid_argument, "winding number: beta must be finite and > 0"};
    for (const auto& t : mesh.triangles)
      for (Index i : t)
        if (i >= mesh.vertices.size())
          return Error{ErrorCode::bad_index, "winding number: vertex index out of range"};
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
      if (!all_finite(mesh.vertices[v]))
        return Error{ErrorCode::non_finite, "winding number: vertex " + std::to_string(v) +
                                                " has a NaN or infinite coordinate"};
    FastWindingNumber w;
    w.beta_ = options.beta;
    std::vector<Aabb<T>> boxes(n);
    std::vector<Vec3<T>> centroids(n);
    for (std::size_t t = 0; t < n; ++t) {
      boxes[t] = mesh.triangle_bounds(t);
      centroids[t] = boxes[t].center();
    }
    bvh::BuildOptions bo;
    bo.max_leaf_size = std::max<std::uint32_t>(1, options.max_leaf_size);
    w.bvh_ =
        bvh::flatten<K>(bvh::build(Span<const Aabb<T>>(boxes), Span<const Vec3<T>>(centroids), bo));
    // Triangles in leaf order: every leaf (and every subtree) is a contiguous range of slots.
    w.tri_.resize(9 * n);
    for (std::size_t s = 0; s < n; ++s) {
      const std::uint32_t t = w.bvh_.prim[s];
      for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a) w.tri_[(3 * k + a) * n + s] = mesh.corner(t, k)[a];
    }
    w.n_ = n;
    w.nodes_.resize(w.bvh_.nodes.size());
    if (w.bvh_.root.is_inner()) w.fill_node(w.bvh_.root.index);
    return w;
  }

  /// Approximate winding number at `p`. Exact (to rounding) when every cluster is near; error
  /// O(beta⁻³) per far cluster otherwise (beta = 2: mean |error| about 0.004, largest about 0.06
  /// on the test meshes; see docs/sign.md). Finite for finite p with coordinates below ~1e100.
  T operator()(const Vec3<T>& p) const noexcept {
    const bvh::ChildRef root = bvh_.root;
    if (root.is_leaf()) return T(leaf_sum(root.index, root.count, p) * inv4pi);
    if (!root.is_inner()) return T(0);
    constexpr T inv4pi_t = T(0.07957747154594767);
    bvh::FixedStack<std::uint32_t, bvh::WideBvh<T, K>::stack_capacity> todo;
    todo.push(root.index);
    T far_sum = 0;   // Σ far-field terms (already divided by 4π)
    double near = 0; // Σ exact solid angles
    while (!todo.empty()) {
      const std::uint32_t ni = todo.pop();
      const WindingNode<T, K>& c = nodes_[ni];
      const bvh::WideNode<T, K>& node = bvh_.nodes[ni];
      bool is_far[K];
      T f = 0;
      for (int k = 0; k < K; ++k) { // branch-free over the K children: vectorisable
        const T rx = c.cx[k] - p.x, ry = c.cy[k] - p.y, rz = c.cz[k] - p.z;
        const T r2 = rx * rx + ry * ry + rz * rz;
        is_far[k] = r2 > c.far2[k];
        // With u = r/|r|: N·r/|r|³ + Σ M_ij (δ_ij/|r|³ - 3 r_i r_j/|r|⁵)
        //              = (N·u)/|r|² + (tr M - 3 u·M·u)/|r|³.
        // Written with u so that nothing overflows far away (|r|² = inf gives u = 0, term 0).
        const T inv_r = T(1) / std::sqrt(is_far[k] ? r2 : T(1));
        const T ux = rx * inv_r, uy = ry * inv_r, uz = rz * inv_r;
        const T inv_r2 = inv_r * inv_r;
        const T order1 = (c.nx[k] * ux + c.ny[k] * uy + c.nz[k] * uz) * inv_r2;
        const T trace = c.m[0][k] + c.m[4][k] + c.m[8][k];
        const T quad = ux * (c.m[0][k] * ux + c.m[1][k] * uy + c.m[2][k] * uz) +
                       uy * (c.m[3][k] * ux + c.m[4][k] * uy + c.m[5][k] * uz) +
                       uz * (c.m[6][k] * ux + c.m[7][k] * uy + c.m[8][k] * uz);
        const T v = order1 + (trace - T(3) * quad) * inv_r2 * inv_r;
        f += is_far[k] ? v : T(0);
      }
      far_sum += f * inv4pi_t;
      for (int k = 0; k < K; ++k) {
        if (is_far[k]) continue;
        const bvh::ChildRef r = node.child[k];
        if (r.is_leaf())
          near += leaf_sum(r.index, r.count, p);
        else if (r.is_inner())
          todo.push(r.index);
      }
    }
    return T(near * inv4pi) + far_sum;
  }

  /// Exact winding number over the same triangles (the oracle), O(n).
  T exact(const Vec3<T>& p) const noexcept { return T(leaf_sum(0, std::uint32_t(n_), p) * inv4pi); }

  double beta() const noexcept { return beta_; }
  std::size_t triangle_count() const noexcept { return n_; }
  const bvh::WideBvh<T, K>& tree() const noexcept { return bvh_; }
  /// Heap bytes: triangles, BVH nodes and slots, cluster data.
  std::size_t memory_bytes() const noexcept {
    return tri_.size() * sizeof(T) + bvh_.memory_bytes() + nodes_.size() * sizeof(nodes_[0]);
  }

 private:
  static constexpr double inv4pi = 0.07957747154594767;

  /// Σ of the exact solid angles of slots [first, first + count).
  double leaf_sum(std::uint32_t first, std::uint32_t count, const Vec3<T>& p) const noexcept {
    const T* t = tri_.data();
    const std::size_t n = n_;
    const Vec3<double> pd{double(p.x), double(p.y), double(p.z)};
    double s = 0;
    for (std::size_t i = first; i < std::size_t(first) + count; ++i) {
      // In double: no overflow for float coordinates, and one rounding less.
      const Vec3<double> a{double(t[0 * n + i]), double(t[1 * n + i]), double(t[2 * n + i])};
      const Vec3<double> b{double(t[3 * n + i]), double(t[4 * n + i]), double(t[5 * n + i])};
      const Vec3<double> c{double(t[6 * n + i]), double(t[7 * n + i]), double(t[8 * n + i])};
      s += solid_angle(pd, a, b, c);
    }
    return s;
  }

  /// Slot range [lo, hi) covered by a child (subtrees are contiguous in leaf order).
  std::pair<std::uint32_t, std::uint32_t> range_of(const bvh::ChildRef& r) const {
    if (r.is_leaf()) return {r.index, r.index + r.count};
    std::uint32_t lo = std::numeric_limits<std::uint32_t>::max(), hi = 0;
    for (const auto& c : bvh_.nodes[r.index].child) {
      if (c.is_empty()) continue;
      const auto sub = range_of(c);
      lo = std::min(lo, sub.first);
      hi = std::max(hi, sub.second);
    }
    return {lo, hi};
  }

  /// Fills the cluster data of node `ni` and, recursively, of its descendants. The moments of
  /// each child are computed in double from its triangles directly: O(n log n) in all, exact
  /// radii (not a bound from the grandchildren).
  void fill_node(std::uint32_t ni) {
    WindingNode<T, K> wn{};
    const std::size_t n = n_;
    const T* t = tri_.data();
    auto tri = [&](std::size_t i, Vec3<double>& a, Vec3<double>& b, Vec3<double>& c) {
      a = {double(t[0 * n + i]), double(t[1 * n + i]), double(t[2 * n + i])};
      b = {double(t[3 * n + i]), double(t[4 * n + i]), double(t[5 * n + i])};
      c = {double(t[6 * n + i]), double(t[7 * n + i]), double(t[8 * n + i])};
    };
    for (int k = 0; k < K; ++k) {
      const bvh::ChildRef r = bvh_.nodes[ni].child[k];
      if (r.is_empty()) {
        wn.far2[k] = std::numeric_limits<T>::infinity();
        continue;
      }
      const auto [lo, hi] = range_of(r);
      const DipoleCluster<double> cl = make_dipole_cluster<double>(lo, hi, tri);
      wn.cx[k] = T(cl.center.x), wn.cy[k] = T(cl.center.y), wn.cz[k] = T(cl.center.z);
      wn.nx[k] = T(cl.normal.x), wn.ny[k] = T(cl.normal.y), wn.nz[k] = T(cl.normal.z);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) wn.m[3 * i + j][k] = T(cl.m[i][j]);
      // Rounded up a little so float centres never make a near cluster look far.
      const double fr = beta_ * cl.radius * (1 + 1e-5);
      wn.far2[k] = T(fr * fr);
      if (r.is_inner()) fill_node(r.index);
    }
    nodes_[ni] = wn;
  }

  bvh::WideBvh<T, K> bvh_;
  std::vector<WindingNode<T, K>> nodes_; ///< parallel to bvh_.nodes
  std::vector<T> tri_;                   ///< 9 arrays of n: ax, ay, az, bx, ..., cz in leaf order
  std::size_t n_ = 0;
  double beta_ = 2;
};

} // namespace ebgeom
