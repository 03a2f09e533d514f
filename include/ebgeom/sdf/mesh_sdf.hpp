// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `MeshSdf<T, K, W>`: exact signed distance to a triangle mesh, accelerated by a K-wide BVH whose
/// leaves are structure-of-arrays blocks of W triangles (`TriBlock`, `geom/tri_block.hpp`), one
/// vectorisable kernel per block. Equal to `BruteForceMeshSdf` to the last bit: the block kernel
/// performs the same floating-point operations as `closest_point_triangle` (tested lane by lane),
/// and the winning triangle is finished with that scalar kernel and the same pseudonormals.
/// The search itself is in `sdf/mesh_block_search.hpp`, tile evaluation in
/// `sdf/mesh_tile_eval.hpp`.
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
#include <utility>
#include <vector>

#include "ebgeom/bvh/build.hpp"
#include "ebgeom/bvh/wide_bvh.hpp"
#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/isa.hpp"
#include "ebgeom/core/morton.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/geom/closest_point_triangle.hpp"
#include "ebgeom/geom/tri_block.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"
#include "ebgeom/mesh/triangle_mesh.hpp"
#include "ebgeom/sdf/concepts.hpp"
#include "ebgeom/sdf/mesh_block_search.hpp"
#include "ebgeom/sdf/mesh_closest_point.hpp"
#include "ebgeom/sdf/mesh_tile_eval.hpp"

EBGEOM_BEGIN_EXACT_FP

namespace ebgeom {

/// Default BVH arity of `MeshSdf`: 8 for float (a node's eight child boxes and oriented boxes fill
/// one AVX register per coordinate; a third fewer nodes per query than 4, 0.99-1.12x the
/// throughput), 4 for double (8 was no faster; docs/dev/performance-log.md "Eight children per
/// float node"). Like the block width it is fixed per type, never by the compile flags. Twice the
/// default (16 floats, 8 doubles: one AVX-512 register per coordinate) has AVX-512 node kernels
/// but was 1-12% slower in float and no faster in double (`bench/arity_bench.cpp`).
template <class T> inline constexpr int default_arity = sizeof(T) == 4 ? 8 : 4;

/// Exact signed distance to a triangle mesh through a BVH (see the file comment).
///
/// - `K`: BVH arity (2..16; `default_arity`: 8 for float, 4 for double), `W`: triangles per leaf
///   block.
/// - Sign: the pseudonormal of the closest feature (Bærentzen & Aanæs 2005): exact for closed,
///   consistently oriented, manifold meshes (check with `validate`).
/// - Memory: the `TriangleMesh` (~48 B/triangle in float) + blocks (36 B per lane, leaves padded
///   to whole blocks) + 4 B per lane of triangle ids + nodes + the oriented boxes of their children
///   (`bvh::NodeObbs`, 15 numbers per child of each node) + a seed grid of 8³ triangles (18 KB in
///   float, 36 KB in double, whatever the mesh's size): about 108 B per triangle in float and 198
///   in double; `memory_bytes()` reports it.
/// - Queries are O(log n) on average, allocation-free, and thread-safe (immutable object).
template <class T, int K = default_arity<T>, int W = default_block_width<T>> class MeshSdf {
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
  /// hand-made mesh whose arrays disagree, `invalid_argument` for a `BuildMethod` value outside
  /// the enumeration.
  static Result<MeshSdf> make(TriangleMesh<T> mesh,
                              const bvh::BuildOptions& options = default_build_options()) {
    Error e = check(mesh);
    if (e.code == ErrorCode::ok) e = bvh::check(options);
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
    s.fill_obbs();
    s.slack_ = rounding_slack(s.bvh_.box);
    s.fill_seeds();
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
    return closest_search(p, std::numeric_limits<T>::infinity());
  }

  /// As `closest`, but only looks for surface points within `max_distance` (a narrow band):
  /// returns `triangle == invalid_triangle` and `distance = +inf` when there is none. Faster than
  /// `closest` far from the surface.
  MeshClosestPoint<T> closest_within(const Vec3<T>& p, T max_distance) const noexcept {
    if (!(max_distance >= T(0))) return {};
    const T b2 = max_distance * max_distance;
    return closest_search(p, std::nextafter(b2, std::numeric_limits<T>::infinity()));
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

  /// |`bounded(p, max_abs)`| bit for bit when it is <= `max_abs`, +infinity when the bounded
  /// search finds no surface point (NaN for a non-finite p): the same search and closest point,
  /// without the sign, so no pseudonormal is read (the split-sign protocol's `unsigned_within`).
  T unsigned_bounded(const Vec3<T>& p, T max_abs) const noexcept {
    const T r = max_abs + max_abs * (T(4) * std::numeric_limits<T>::epsilon());
    if (!(r >= T(0))) return std::numeric_limits<T>::infinity();
    if (!all_finite(p)) return std::numeric_limits<T>::quiet_NaN();
    T best2 = std::nextafter(r * r, std::numeric_limits<T>::infinity());
    std::uint32_t best = bvh::ChildRef::none;
    seeded_nearest_slot(p, best2, best);
    if (best == bvh::ChildRef::none) return std::numeric_limits<T>::infinity();
    // best2 is the block kernel's squared distance to the slot `best`, the same bits as
    // `closest_point_triangle` gives (geom/tri_block.hpp): the magnitude `finish` computes,
    // without computing the closest point again.
    return std::sqrt(best2);
  }

  /// Unsigned distance: |(*this)(p)| bit for bit (the search's own squared distance, as
  /// `unsigned_bounded`), with no closest point or sign decision.
  T unsigned_distance(const Vec3<T>& p) const noexcept {
    if (!all_finite(p)) return std::numeric_limits<T>::quiet_NaN();
    T best2 = std::numeric_limits<T>::infinity();
    std::uint32_t best = bvh::ChildRef::none;
    seeded_nearest_slot(p, best2, best);
    return std::sqrt(best2);
  }

  /// Signed distances at many points: `out[i] = (*this)(pts[i])` bit for bit, for i <
  /// min(pts.size(), out.size()) (`evaluate` and `AnySdf` call it; `has_batch_eval_v`).
  ///
  /// How: the points are visited in Morton order (`morton_order`, in pieces of at most
  /// `batch_piece` points), so that consecutive queries read the same nodes and blocks from cache;
  /// each query's search starts from the previous query's nearest triangle, whose distance is an
  /// exact upper bound (raised by the pruning slack, as the seed grid's), in place of the seed
  /// grid's. A seed only prunes: the search still returns the lowest-index triangle at the minimum
  /// distance, and the value is finished exactly as `operator()` finishes it. Faster than a loop of
  /// `operator()` when the points are many and scattered (random input order); a loop of
  /// single queries (and inputs below `batch_order_min` points) keeps the input order.
  /// Memory: 4 + 16 bytes per point of the piece (its order and the sort's scratch), freed on
  /// return; if that allocation fails the points are evaluated in input order. Thread-safe.
  void eval(Span<const Vec3<T>> pts, Span<T> out) const noexcept {
    const std::size_t n = std::min(pts.size(), out.size());
    std::uint32_t prev = bvh::ChildRef::none;
    if (n < batch_order_min) {
      for (std::size_t i = 0; i < n; ++i) out[i] = query_after(pts[i], prev);
      return;
    }
    std::vector<std::uint32_t> order;
    std::vector<std::uint64_t> scratch;
    try {
      order.reserve(std::min(n, batch_piece));
      scratch.reserve(2 * std::min(n, batch_piece));
    } catch (...) { // no memory for the order: input order
      for (std::size_t i = 0; i < n; ++i) out[i] = query_after(pts[i], prev);
      return;
    }
    constexpr std::size_t ahead = 8; // points prefetched ahead of the query in the sorted order
    for (std::size_t s = 0; s < n; s += batch_piece) {
      const std::size_t m = std::min(batch_piece, n - s);
      morton_order(pts.subspan(s, m), order, scratch); // within the reserved capacity
      for (std::size_t k = 0; k < m; ++k) {
        if (k + ahead < m) {
          detail::prefetch(pts.data() + s + order[k + ahead]);
          detail::prefetch(out.data() + s + order[k + ahead]);
        }
        const std::size_t i = s + order[k];
        out[i] = query_after(pts[i], prev);
      }
    }
  }

  /// `eval` sorts its points itself (see `has_ordered_batch_v`): `evaluate` hands it large spans.
  static constexpr bool batch_in_space_order = true;
  /// `eval` keeps the input order below this many points.
  static constexpr std::size_t batch_order_min = 64;
  /// `eval` sorts at most this many points at a time (bounds its scratch memory to 20 MiB).
  static constexpr std::size_t batch_piece = std::size_t(1) << 20;

  /// Exact signed distances at a tile of lattice samples, bit for bit `(*this)(pts[l])` for
  /// every `l` (`sample_grid` detects this method and calls it once per 8^3 tile).
  ///
  /// `pts` holds `dims[0] * dims[1] * dims[2]` points, x fastest (`pts[x + dims[0] * (y +
  /// dims[1] * z)]`), with each coordinate monotone along its axis (a tile of a regular grid);
  /// `out` receives the values in the same order. Other points (a coordinate decreasing along an
  /// axis, or not finite) are answered one query at a time (the tile bounds below assume a
  /// lattice).
  ///
  /// How: one BVH search at a sample near the tile's centre, q, bounds every sample's distance
  /// (1-Lipschitz: |S(p)| <= |S(q)| + |p - q| <= U), so every sample's nearest triangle lies in a
  /// leaf within U of the tile's bounding box; those leaves are collected once (nearest to the
  /// centre first). A long list is split by octants, each filtering its parent's list with its own
  /// bound. Each sample then scans its list (a vectorised box test, then the blocks of the boxes
  /// still within the best distance), starting from the block of the previous sample's nearest
  /// triangle, whose exact distance is a tight initial bound. Every triangle the per-point search
  /// could pick lies in a scanned leaf and the same kernel and tie rule (lowest index) decide, so
  /// the results are the per-point results. Allocates O(candidate leaves) scratch per call;
  /// thread-safe.
  void eval_lattice(Span<const Vec3<T>> pts, const std::array<std::size_t, 3>& dims,
                    Span<T> out) const {
    lattice<false>(pts, dims, out);
  }

  /// `eval_lattice` without the sign: `out[l] = unsigned_distance(pts[l])` bit for bit (the
  /// search's own squared distance, as `unsigned_distance`: no closest point, no pseudonormal).
  /// What grids with a winding sign evaluate before they sign the samples.
  void unsigned_lattice(Span<const Vec3<T>> pts, const std::array<std::size_t, 3>& dims,
                        Span<T> out) const {
    lattice<true>(pts, dims, out);
  }

 private:
  template <bool Unsigned>
  void lattice(Span<const Vec3<T>> pts, const std::array<std::size_t, 3>& dims, Span<T> out) const {
    const std::size_t n = dims[0] * dims[1] * dims[2];
    EBGEOM_ASSERT(pts.size() == n && out.size() == n);
    if (n == 0) return;
    // The tile bounds below take a part's box from its corner samples: they need finite samples
    // whose every coordinate is nondecreasing along each axis of the tile.
    const std::size_t step[3] = {1, dims[0], dims[0] * dims[1]};
    for (std::size_t l = 0; l < n; ++l) {
      const std::size_t c[3] = {l % dims[0], (l / dims[0]) % dims[1], l / step[2]};
      bool ok = all_finite(pts[l]);
      for (int a = 0; a < 3 && ok; ++a)
        if (c[a] > 0) {
          const Vec3<T>& q = pts[l - step[a]];
          ok = q.x <= pts[l].x && q.y <= pts[l].y && q.z <= pts[l].z;
        }
      if (!ok) {
        for (std::size_t i = 0; i < n; ++i)
          out[i] = Unsigned ? unsigned_distance(pts[i]) : (*this)(pts[i]);
        return;
      }
    }
    // Unsigned: each sample's squared distance, written into `out` by the search.
    const std::vector<std::uint32_t> slot = with_active_isa([&](auto isa) {
      return detail::MeshTileEval<T, K, W, decltype(isa)::value>(block_search(), plane_margin_)
          .nearest_slots(pts.data(), dims, Unsigned ? out.data() : nullptr);
    });
    if constexpr (Unsigned) {
      for (std::size_t l = 0; l < n; ++l)
        out[l] =
            slot[l] == bvh::ChildRef::none ? std::numeric_limits<T>::infinity() : std::sqrt(out[l]);
    } else {
      for (std::size_t l = 0; l < n; ++l) out[l] = finish(pts[l], slot[l]).distance;
    }
  }

 public:
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
    fill_obbs();
    fill_seeds();
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
           block_tri_.size() * sizeof(std::uint32_t) +
           seed_tri_.size() * sizeof(std::array<Vec3<T>, 3>) + bvh_.memory_bytes() +
           obbs_.size() * sizeof(bvh::NodeObbs<T, K>);
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

  /// Corner j (0..2) of the triangle in block slot `s`, as the block holds it.
  Vec3<T> slot_corner(std::size_t s, int j) const noexcept {
    const TriBlock<T, W>& b = blocks_[s / W];
    const int l = int(s % W);
    if (j == 0) return {b.ax[l], b.ay[l], b.az[l]};
    if (j == 1) return {b.bx[l], b.by[l], b.bz[l]};
    return {b.cx[l], b.cy[l], b.cz[l]};
  }

  /// The closest point to `p` on the triangle in block slot `s`, from the corners as the block
  /// holds them (what `finish` returns, and what the search's seeds and `unsigned_bounded` read).
  TriangleClosestPoint<T> slot_closest(const Vec3<T>& p, std::size_t s) const noexcept {
    return closest_point_triangle(p, slot_corner(s, 0), slot_corner(s, 1), slot_corner(s, 2));
  }

  /// The oriented boxes of every node's children (`bvh::NodeObbs`): around the corners of the
  /// triangles below the child (a leaf's, or all the leaves' of an inner child's subtree), one
  /// axis along their summed normals. Bounding inner children too lets the search drop whole
  /// subtrees that only their axis-aligned boxes bring near: 1.2-1.9x fewer nodes per query.
  /// Subtrees of more than `obb_max_triangles` get none: their patches are too curved for a box
  /// much thinner than the axis-aligned one, and each level of them would cost one more pass over
  /// the mesh at build time (for the extents: the orientation comes from sums over the children).
  void fill_obbs() {
    const std::size_t nn = bvh_.nodes.size();
    obbs_.resize(nn);
    for (bvh::NodeObbs<T, K>& o : obbs_) o.clear();
    // Per node, the sums of the corners below it (`bvh::PatchStats`) and its run of blocks,
    // children before parents: the nodes are laid out depth first, so an inner child comes after
    // its parent, and the leaves below a node hold one run of consecutive blocks (`pack_blocks`).
    struct Subtree {
      bvh::PatchStats st;
      std::uint32_t first = ~std::uint32_t(0), end = 0, blocks = 0; // its blocks: [first, end)
      std::size_t triangles = 0;
      bool ok = true; // every inner node below comes after its parent
    };
    std::vector<Subtree> sub(nn);
    const Aabb<T> box = bvh_.box;
    const Vec3<double> ref =
        Vec3<double>{double(box.lo.x), double(box.lo.y), double(box.lo.z)} * 0.5 +
        Vec3<double>{double(box.hi.x), double(box.hi.y), double(box.hi.z)} * 0.5;
    const auto corner = [this](std::size_t s, int j) {
      const Vec3<T> x = slot_corner(s, j);
      return Vec3<double>{double(x.x), double(x.y), double(x.z)};
    };
    for (std::size_t i = nn; i-- > 0;) {
      Subtree& node = sub[i];
      node.st.ref = ref;
      for (int k = 0; k < K; ++k) {
        const bvh::ChildRef c = bvh_.nodes[i].child[k];
        Subtree leaf;
        const Subtree* ch = &leaf;
        if (c.is_leaf()) {
          leaf.st.ref = ref;
          leaf.first = c.index;
          leaf.blocks = (c.count + std::uint32_t(W) - 1) / std::uint32_t(W);
          leaf.end = c.index + leaf.blocks;
          leaf.triangles = c.count;
          for (std::uint32_t t = 0; t < c.count; ++t) {
            const std::size_t slot = std::size_t(c.index) * W + t;
            leaf.st.add_triangle(corner(slot, 0), corner(slot, 1), corner(slot, 2));
          }
        } else if (c.is_inner() && c.index > i && c.index < nn) {
          ch = &sub[c.index];
        } else {
          if (!c.is_empty()) node.ok = false;
          continue;
        }
        node.st.merge(ch->st);
        node.first = std::min(node.first, ch->first);
        node.end = std::max(node.end, ch->end);
        node.blocks += ch->blocks;
        node.triangles += ch->triangles;
        node.ok = node.ok && ch->ok;
        // The box of child k: around every lane of its run of blocks (padding lanes repeat a
        // triangle of their leaf).
        if (!ch->ok || ch->triangles > obb_max_triangles || ch->end - ch->first != ch->blocks)
          continue;
        const std::size_t first_slot = std::size_t(ch->first) * W;
        obbs_[i].fit_from_sums(k, ch->st, std::size_t(ch->blocks) * W * 3, [&](std::size_t j) {
          return corner(first_slot + j / 3, int(j % 3));
        });
      }
    }
  }

  /// The nearest-triangle search over this object's arrays.
  detail::BlockSearch<T, K, W> block_search() const noexcept {
    return {&bvh_, blocks_.data(), block_tri_.data(), slack_,
            obbs_.empty() ? nullptr : obbs_.data()};
  }

  /// The search with the kernels of the active instruction set (`core/isa.hpp`).
  void nearest_slot(const Vec3<T>& p, T& best2, std::uint32_t& best) const noexcept {
    const detail::BlockSearch<T, K, W> s = block_search();
    with_active_isa([&](auto isa) {
      detail::MeshSearchKernels<decltype(isa)::value>::nearest_slot(s, p, best2, best);
    });
  }

  MeshClosestPoint<T> closest_search(const Vec3<T>& p, T bound2) const noexcept {
    if (!all_finite(p)) {
      MeshClosestPoint<T> r;
      r.distance = std::numeric_limits<T>::quiet_NaN();
      return r;
    }
    T best2 = bound2;
    std::uint32_t best = bvh::ChildRef::none;
    seeded_nearest_slot(p, best2, best);
    return finish(p, best);
  }

  /// `nearest_slot` from an initial bound lowered by the seed of `p`'s cell (`fill_seeds`): the
  /// squared distance to the triangle nearest to the cell's centre, computed as `finish` computes
  /// it and raised by the search's pruning slack twice over, so that the block kernel's value of
  /// that triangle, and so the minimum, lies strictly below it (the search's own assumption on the
  /// kernel's rounding). The search then returns what it returns from `best2` itself: every
  /// triangle at the minimum distance is below both bounds. A tighter first bound than the first
  /// leaf's prunes more of the tree before the nearest leaf is reached.
  /// `hint`: a slot whose triangle is likely near `p` (the previous query's nearest, `eval`): its
  /// distance, raised the same way, seeds the search in place of the seed grid's.
  void seeded_nearest_slot(const Vec3<T>& p, T& best2, std::uint32_t& best,
                           std::uint32_t hint = bvh::ChildRef::none) const noexcept {
    const T bound2 = best2;
    bool seeded = false;
    if (hint != bvh::ChildRef::none) {
      const T d2 = slot_closest(p, hint).distance2;
      const T seed2 = bvh::prune_limit(d2, T(2) * slack_);
      if (seed2 < best2) best2 = seed2, seeded = true;
    } else if (!seed_tri_.empty()) {
      int c[3];
      for (int k = 0; k < 3; ++k) {
        T f = (p[k] - seed_lo_[k]) * seed_scale_[k];
        f = f > T(0) ? f : T(0); // NaN (inf * 0 on a flat axis) too
        f = f < T(seed_cells - 1) ? f : T(seed_cells - 1);
        c[k] = int(f);
      }
      const std::array<Vec3<T>, 3>& t =
          seed_tri_[std::size_t((c[2] * seed_cells + c[1]) * seed_cells + c[0])];
      // A search bounded by a band seldom finds its seed within the bound: the triangle's box
      // first, which rules it out for a fraction of the closest point's cost. (A seed only
      // prunes, so leaving one out never changes the result.)
      if (!(best2 < std::numeric_limits<T>::infinity()) ||
          Aabb<T>(min(min(t[0], t[1]), t[2]), max(max(t[0], t[1]), t[2])).distance2(p) < best2) {
        const T d2 = closest_point_triangle(p, t[0], t[1], t[2]).distance2;
        const T seed2 = bvh::prune_limit(d2, T(2) * slack_);
        if (seed2 < best2) best2 = seed2, seeded = true;
      }
    }
    nearest_slot(p, best2, best);
    if (seeded && best == bvh::ChildRef::none) { // never expected: the seed's own triangle is
      best2 = bound2;                            // below its bound
      nearest_slot(p, best2, best);
    }
  }

  /// `(*this)(p)`, its search seeded by slot `prev` (see `eval`), which becomes `p`'s nearest slot
  /// (unchanged when `p` is not finite).
  T query_after(const Vec3<T>& p, std::uint32_t& prev) const noexcept {
    if (!all_finite(p)) return std::numeric_limits<T>::quiet_NaN();
    T best2 = std::numeric_limits<T>::infinity();
    std::uint32_t best = bvh::ChildRef::none;
    seeded_nearest_slot(p, best2, best, prev);
    prev = best;
    return finish(p, best).distance;
  }

  /// Cells per axis of the seed grid.
  static constexpr int seed_cells = 8;

  /// The seed grid: over the mesh's box, `seed_cells`³ cells, each holding the corners of the
  /// triangle nearest to its centre (a query outside the box takes the nearest cell).
  void fill_seeds() {
    const Aabb<T> box = bvh_.box;
    const Vec3<T> e = box.extent();
    seed_lo_ = box.lo;
    for (int k = 0; k < 3; ++k) seed_scale_[k] = e[k] > T(0) ? T(seed_cells) / e[k] : T(0);
    seed_tri_.assign(std::size_t(seed_cells) * seed_cells * seed_cells, {});
    for (int z = 0; z < seed_cells; ++z)
      for (int y = 0; y < seed_cells; ++y)
        for (int x = 0; x < seed_cells; ++x) {
          const int i[3] = {x, y, z};
          Vec3<T> c;
          for (int k = 0; k < 3; ++k)
            c[k] = box.lo[k] + e[k] * ((T(i[k]) + T(0.5)) / T(seed_cells));
          T best2 = std::numeric_limits<T>::infinity();
          std::uint32_t best = bvh::ChildRef::none;
          nearest_slot(c, best2, best);
          if (best == bvh::ChildRef::none) { // a non-finite centre (a box beyond the range of T)
            seed_tri_.clear();
            return;
          }
          seed_tri_[std::size_t((z * seed_cells + y) * seed_cells + x)] = {
              slot_corner(best, 0), slot_corner(best, 1), slot_corner(best, 2)};
        }
  }

  /// Signed distance etc. at `p` from its nearest slot (as `search`).
  MeshClosestPoint<T> finish(const Vec3<T>& p, std::uint32_t best) const noexcept {
    MeshClosestPoint<T> r;
    if (best == bvh::ChildRef::none) return r;
    const std::uint32_t t = block_tri_[best];
    // What the pseudonormal of any feature reads, loaded while the closest point is computed.
    detail::prefetch(mesh_.face_normals.data() + t);
    detail::prefetch(mesh_.triangles.data() + t);
    detail::prefetch(mesh_.edge_links.data() + t);
    // The corners as the block holds them (the mesh's values, copied by `fill_blocks`): the
    // search has just read that block, where the mesh's arrays would be a cache miss each.
    const TriangleClosestPoint<T> cp = slot_closest(p, best);
    r.distance =
        signed_distance_from(p, cp.point, cp.distance2, feature_pseudonormal(mesh_, t, cp.feature));
    r.point = cp.point;
    r.triangle = t;
    r.feature = cp.feature;
    return r;
  }

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
  Vec3<T> seed_lo_{0, 0, 0};    ///< seed grid: lower corner
  Vec3<T> seed_scale_{0, 0, 0}; ///< seed grid: cells per unit length, per axis
  /// Seed grid: per cell, the corners of the triangle nearest to its centre (`fill_seeds`; a few
  /// tens of KB, which stay in cache from query to query).
  std::vector<std::array<Vec3<T>, 3>> seed_tri_;
  T plane_margin_ = 0;
  bvh::WideBvh<T, K> bvh_;
  std::vector<TriBlock<T, W>> blocks_;
  std::vector<std::uint32_t> block_tri_; ///< triangle id of each block lane
  /// The largest subtree (in triangles) that `fill_obbs` bounds with an oriented box.
  static constexpr std::size_t obb_max_triangles = 2048;
  std::vector<bvh::NodeObbs<T, K>> obbs_; ///< per node: its children's oriented boxes
};

} // namespace ebgeom

EBGEOM_END_EXACT_FP
