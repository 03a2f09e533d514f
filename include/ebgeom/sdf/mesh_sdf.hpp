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
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "ebgeom/bvh/build.hpp"
#include "ebgeom/bvh/simd_nodes.hpp"
#include "ebgeom/bvh/traverse.hpp"
#include "ebgeom/bvh/wide_bvh.hpp"
#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/geom/closest_point_triangle.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"
#include "ebgeom/mesh/triangle_mesh.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"
#include "ebgeom/sdf/concepts.hpp"

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

/// Default block width: 8 lanes of float or 4 of double (one 256-bit register of each).
template <class T> inline constexpr int default_block_width = sizeof(T) == 4 ? 8 : 4;

/// Squared distance from `p` to each triangle of a block. Performs exactly the operations of
/// `closest_point_triangle` per lane (same order, same selects), so `d2[l]` equals its
/// `distance2` bit for bit; divisions are computed unconditionally with a safe divisor so the
/// loop has no branch and vectorises (checked with -fopt-info-vec: 8 floats per AVX2 register at
/// -O2 and -O3, 4 with SSE2).
template <class T, int W>
EBGEOM_VECTOR_KERNEL inline void block_distance2(const TriBlock<T, W>& t, const Vec3<T>& p,
                                                 T (&out)[W]) noexcept {
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

/// Exact signed distance to a triangle mesh through a BVH (see the file comment).
///
/// - `K`: BVH arity (2..16; 4 is the default, 8 suits AVX-512), `W`: triangles per leaf block.
/// - Sign: the pseudonormal of the closest feature (Bærentzen & Aanæs 2005): exact for closed,
///   consistently oriented, manifold meshes (check with `validate`).
/// - Memory: the `TriangleMesh` (~76 B/triangle in float) + blocks (36 B per lane, leaves padded
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
    return s;
  }

  /// Triangulates a polygon soup (`make_triangle_mesh`) and builds.
  static Result<MeshSdf> build(const PolygonSoup<T>& soup,
                               const bvh::BuildOptions& options = default_build_options()) {
    Result<TriangleMesh<T>> m = make_triangle_mesh(soup);
    if (!m) return m.error();
    return make(std::move(*m), options);
  }

  /// Signed distance at `p` (< 0 inside).
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
    T best2 = std::numeric_limits<T>::infinity();
    std::uint32_t best = bvh::ChildRef::none;
    nearest_slot(p, best2, best);
    return std::sqrt(best2);
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
    if (m.face_normals.size() != nt || m.edge_normals.size() != nt ||
        m.vertex_normals.size() != m.vertices.size())
      return {ErrorCode::size_mismatch, "mesh SDF: normal arrays do not match the mesh"};
    for (std::size_t v = 0; v < m.vertices.size(); ++v)
      if (!all_finite(m.vertices[v]))
        return {ErrorCode::non_finite,
                "mesh SDF: vertex " + std::to_string(v) + " has a NaN or infinite coordinate"};
    for (std::size_t t = 0; t < nt; ++t)
      for (Index i : m.triangles[t])
        if (i >= m.vertices.size())
          return {ErrorCode::bad_index, "mesh SDF: triangle " + std::to_string(t) +
                                            " uses vertex " + std::to_string(i) +
                                            " >= " + std::to_string(m.vertices.size())};
    return {};
  }

  /// Re-points every leaf at whole blocks: (first block, count), padding the last block of each
  /// leaf with copies of the leaf's last triangle (same distance, never preferred: ties keep the
  /// first lane).
  void pack_blocks() {
    std::uint32_t next_block = 0;
    auto remap = [&](bvh::ChildRef& r) {
      const std::uint32_t nb = (r.count + std::uint32_t(W) - 1) / std::uint32_t(W);
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
    const TriBlock<T, W>* blocks = blocks_.data();
    const std::uint32_t* tri = block_tri_.data();
    bvh::nearest<true>(
        bvh_, p, best2,
        [&](std::uint32_t first_block, std::uint32_t count, T& b2) noexcept {
          const std::uint32_t nb = (count + std::uint32_t(W) - 1) / std::uint32_t(W);
          for (std::uint32_t i = 0; i < nb; ++i) {
            T d2[W];
            block_distance2(blocks[first_block + i], p, d2);
            // Most blocks hold nothing as close as the best: one vector compare skips them.
            for (std::uint32_t m = bvh::lanes_at_most(d2, b2); m != 0; m &= m - 1) {
              const int l = bvh::lowest_lane(m);
              const std::uint32_t slot = (first_block + i) * std::uint32_t(W) + std::uint32_t(l);
              // Exact ties go to the lowest triangle index, as in the brute force,
              // so even the reported triangle (and, on meshes where tied features
              // disagree, the sign) is the same.
              if (d2[l] < b2 ||
                  (d2[l] == b2 && best != bvh::ChildRef::none && tri[slot] < tri[best])) {
                b2 = d2[l];
                best = slot;
              }
            }
          }
        },
        slack_);
  }

  MeshClosestPoint<T> search(const Vec3<T>& p, T bound2) const noexcept {
    T best2 = bound2;
    std::uint32_t best = bvh::ChildRef::none;
    nearest_slot(p, best2, best);
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

  /// Absolute pruning slack: a bound on the rounding of a triangle's squared distance near the
  /// surface (about eps · size²), so ties with the brute force are never pruned away.
  static T rounding_slack(const Aabb<T>& box) noexcept {
    const T s = std::max(
        {max_component(abs(box.lo)), max_component(abs(box.hi)), max_component(box.extent())});
    return T(64) * std::numeric_limits<T>::epsilon() * s * s;
  }

  TriangleMesh<T> mesh_;
  T slack_ = 0;
  bvh::WideBvh<T, K> bvh_;
  std::vector<TriBlock<T, W>> blocks_;
  std::vector<std::uint32_t> block_tri_; ///< triangle id of each block lane
};

} // namespace ebgeom
