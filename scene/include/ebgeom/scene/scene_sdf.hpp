// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// `SceneSdf<T>`: a compiled scene (or one mesh file) as an SDF. The tree of the library's shapes,
// transforms, CSG and mesh SDFs built by `compile_scene` (scene.hpp) behind one `AnySdf<T>`, with
// the box the compiler proved, the run-time kind and the facts the tools report. A scene that is
// one mesh also hands out that mesh's own SDF (`visit`), so grids and batch queries reach the mesh
// SDF's tile (`eval_lattice`) and band (`bounded`) searches.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/morton.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/scene/nodes.hpp"
#include "ebgeom/sdf/any_sdf.hpp"
#include "ebgeom/sdf/concepts.hpp"
#include "ebgeom/sdf/signed_mesh_sdf.hpp"

namespace ebgeom::scene {

/// A compiled scene. Immutable; copies share the tree; `operator()` and `eval` are thread-safe.
template <class T> class SceneSdf {
 public:
  using scalar_type = T;
  /// Conservative static kind; `dynamic_kind()` gives the compiled scene's own.
  static constexpr SdfKind kind = SdfKind::implicit;

  /// An empty scene: +infinity everywhere, an empty box.
  SceneSdf() : SceneSdf(AnySdf<T>(EmptyNode<T>{}), Aabb<T>{}, 0) {}
  SceneSdf(AnySdf<T> root, const Aabb<T>& box, std::size_t triangles)
      : root_(std::make_shared<const AnySdf<T>>(std::move(root))), box_(box),
        triangles_(triangles) {}

  /// One mesh: the mesh SDF `mesh` (sign mode `requested` asked for).
  static SceneSdf of_mesh(std::shared_ptr<const SignedMeshSdf<T>> mesh, SignMode requested) {
    SceneSdf s(AnySdf<T>(MeshNode<T>{mesh}), mesh->bounds(), mesh->triangle_count());
    s.mesh_ = std::move(mesh);
    s.requested_ = requested;
    return s;
  }

  T operator()(const Vec3<T>& p) const noexcept { return (*root_)(p); }
  /// out[i] = S(points[i]) for i < min(points.size(), out.size()): one virtual call per node per
  /// chunk of points. A scene with a mesh visits many points (at least `batch_order_min`) in
  /// Morton order (`morton_order`, at most `batch_piece` points at a time), passing its tree
  /// chunks of `sorted_chunk` nearby points, so that consecutive mesh queries read the same nodes
  /// and triangles from cache (a scene of analytic shapes keeps the input order: there is nothing
  /// to gain). The values do not depend on the order. Memory: 4 + 16 bytes per point of a piece
  /// and a copy of one chunk's points and values, freed on return; if that allocation fails, the
  /// input order. Thread-safe.
  void eval(Span<const Vec3<T>> points, Span<T> out) const noexcept {
    const std::size_t n = std::min(points.size(), out.size());
    if (triangles_ == 0 || n < batch_order_min) return root_->eval(points.first(n), out.first(n));
    std::vector<std::uint32_t> order;
    std::vector<std::uint64_t> scratch;
    std::vector<Vec3<T>> p;
    std::vector<T> v;
    try {
      order.reserve(std::min(n, batch_piece));
      scratch.reserve(2 * std::min(n, batch_piece));
      p.resize(std::min(n, sorted_chunk));
      v.resize(std::min(n, sorted_chunk));
    } catch (...) { // no memory for the order: input order
      return root_->eval(points.first(n), out.first(n));
    }
    for (std::size_t s = 0; s < n; s += batch_piece) {
      const std::size_t m = std::min(batch_piece, n - s);
      morton_order(points.subspan(s, m), order, scratch); // within the reserved capacity
      for (std::size_t c = 0; c < m; c += sorted_chunk) {
        const std::size_t k = std::min(sorted_chunk, m - c);
        for (std::size_t i = 0; i < k; ++i) p[i] = points[s + order[c + i]];
        root_->eval(Span<const Vec3<T>>(p.data(), k), Span<T>(v.data(), k));
        for (std::size_t i = 0; i < k; ++i) out[s + order[c + i]] = v[i];
      }
    }
  }
  /// `eval` orders the points of a scene with a mesh itself (`has_ordered_batch_v`): `evaluate`
  /// hands it large spans.
  static constexpr bool batch_in_space_order = true;
  /// `eval` keeps the input order below this many points (as `MeshSdf::eval`).
  static constexpr std::size_t batch_order_min = 64;
  /// `eval` sorts at most this many points at a time.
  static constexpr std::size_t batch_piece = std::size_t(1) << 20;
  /// Sorted points per call of the tree.
  static constexpr std::size_t sorted_chunk = 4096;
  /// The box the compiler proved (contains the zero level set and the inside).
  Aabb<T> bounds() const noexcept { return box_; }
  SdfKind dynamic_kind() const noexcept { return root_->dynamic_kind(); }
  /// Triangles of every mesh in the scene.
  std::size_t triangle_count() const noexcept { return triangles_; }
  const AnySdf<T>& sdf() const noexcept { return *root_; }

  /// The mesh when the scene is one mesh file (`mesh_scene`), else null.
  const SignedMeshSdf<T>* mesh() const noexcept { return mesh_.get(); }
  /// The sign mode asked for the mesh of `mesh()`.
  SignMode requested_sign() const noexcept { return requested_; }

  /// `f(sdf)` with the most direct SDF of the same values: for one mesh, its `MeshSdf` (the
  /// pseudonormal sign: tile and band searches) or `SignedMeshSdf` (other signs); for a scene,
  /// `*this`. Every choice gives the values of `(*this)(p)` bit for bit.
  template <class F> decltype(auto) visit(F&& f) const {
    if (mesh_) {
      if (mesh_->resolved_mode() == SignMode::pseudonormal) return f(mesh_->mesh_sdf());
      return f(*mesh_);
    }
    return f(*this);
  }

 private:
  std::shared_ptr<const AnySdf<T>> root_;
  Aabb<T> box_;
  std::size_t triangles_ = 0;
  std::shared_ptr<const SignedMeshSdf<T>> mesh_;
  SignMode requested_ = SignMode::automatic;
};

} // namespace ebgeom::scene
