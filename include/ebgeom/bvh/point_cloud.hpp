// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `PointCloud<T, K>`: nearest-neighbour queries over a point set through a K-wide BVH (a BVH of
/// points), with brute-force twins used as test oracles.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "ebgeom/bvh/build.hpp"
#include "ebgeom/bvh/traverse.hpp"
#include "ebgeom/bvh/wide_bvh.hpp"
#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"

namespace ebgeom::bvh {

/// Index and squared distance of a point of the cloud; `index == none` when there is none.
template <class T> struct PointHit {
  static constexpr std::uint32_t none = ~std::uint32_t(0);
  std::uint32_t index = none;
  T dist2 = std::numeric_limits<T>::infinity();
};

/// Nearest point and k nearest points of a fixed point set. Points are stored in leaf order;
/// results use the input indices. Ties are broken by the smaller input index, exactly as the
/// brute-force twins do. Immutable; concurrent queries are safe.
template <class T, int K = 4> class PointCloud {
 public:
  PointCloud() = default;
  /// O(n log n). Non-finite points are kept but never returned (their boxes are empty).
  explicit PointCloud(std::vector<Vec3<T>> points, std::uint32_t max_leaf_size = 4) {
    const std::size_t n = points.size();
    std::vector<Aabb<T>> boxes(n);
    for (std::size_t i = 0; i < n; ++i)
      boxes[i] = all_finite(points[i]) ? Aabb<T>::of(points[i]) : Aabb<T>();
    std::vector<Vec3<T>> centroids(n);
    for (std::size_t i = 0; i < n; ++i)
      centroids[i] = all_finite(points[i]) ? points[i] : Vec3<T>::zero();
    BuildOptions o;
    o.max_leaf_size = max_leaf_size;
    bvh_ = flatten<K>(build(Span<const Aabb<T>>(boxes), Span<const Vec3<T>>(centroids), o));
    pts_.resize(n);
    // Non-finite points become NaN: every distance to them is NaN, which no comparison accepts.
    for (std::size_t s = 0; s < n; ++s) {
      const Vec3<T>& q = points[bvh_.prim[s]];
      pts_[s] = all_finite(q) ? q : Vec3<T>::constant(std::numeric_limits<T>::quiet_NaN());
    }
  }

  std::size_t size() const noexcept { return pts_.size(); }

  /// The nearest point to `p` within `max_distance` (unbounded by default).
  PointHit<T> nearest(const Vec3<T>& p,
                      T max_distance = std::numeric_limits<T>::infinity()) const noexcept {
    PointHit<T> best;
    T best2 = std::nextafter(max_distance * max_distance, std::numeric_limits<T>::infinity());
    bvh::nearest(bvh_, p, best2, [&](std::uint32_t first, std::uint32_t count, T& b2) {
      for (std::uint32_t s = first; s < first + count; ++s) {
        const T d2 = norm2(pts_[s] - p);
        const std::uint32_t idx = bvh_.prim[s];
        if (d2 < best.dist2 || (d2 == best.dist2 && idx < best.index)) {
          best = {idx, d2};
          b2 = std::nextafter(d2, std::numeric_limits<T>::infinity()); // ties may follow
        }
      }
    });
    return best;
  }

  /// The `k` nearest points, nearest first (ties: smaller index first).
  std::vector<PointHit<T>> k_nearest(const Vec3<T>& p, std::size_t k) const {
    auto r = bvh::k_nearest(
        bvh_, p, k, [&](std::uint32_t s) { return norm2(pts_[s] - p); },
        std::numeric_limits<T>::infinity(), [&](std::uint32_t s) { return bvh_.prim[s]; });
    std::vector<PointHit<T>> out;
    out.reserve(r.size());
    for (const auto& n : r) out.push_back({n.key, n.dist2});
    return out;
  }

  /// Indices of every point within `radius` of `p`, ascending.
  std::vector<std::uint32_t> within(const Vec3<T>& p, T radius) const {
    std::vector<std::uint32_t> out;
    const T r2 = radius * radius;
    for_each_within(bvh_, p, radius, [&](std::uint32_t s) {
      if (norm2(pts_[s] - p) <= r2) out.push_back(bvh_.prim[s]);
    });
    std::sort(out.begin(), out.end());
    return out;
  }

  const WideBvh<T, K>& tree() const noexcept { return bvh_; }

 private:
  WideBvh<T, K> bvh_;
  std::vector<Vec3<T>> pts_; ///< in leaf order
};

/// Brute-force twin of `PointCloud::nearest`.
template <class T> PointHit<T> brute_force_nearest(Span<const Vec3<T>> points, const Vec3<T>& p) {
  PointHit<T> best;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!all_finite(points[i])) continue;
    const T d2 = norm2(points[i] - p);
    if (d2 < best.dist2) best = {std::uint32_t(i), d2};
  }
  return best;
}

/// Brute-force twin of `PointCloud::k_nearest`.
template <class T>
std::vector<PointHit<T>> brute_force_k_nearest(Span<const Vec3<T>> points, const Vec3<T>& p,
                                               std::size_t k) {
  std::vector<PointHit<T>> all;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (all_finite(points[i])) all.push_back({std::uint32_t(i), norm2(points[i] - p)});
  std::sort(all.begin(), all.end(), [](const PointHit<T>& a, const PointHit<T>& b) {
    return a.dist2 < b.dist2 || (a.dist2 == b.dist2 && a.index < b.index);
  });
  if (all.size() > k) all.resize(k);
  return all;
}

} // namespace ebgeom::bvh
