// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `AnySdf<T>`: type erasure for SDFs at batch granularity (STYLE.md example 2). Wraps any SDF
/// with scalar type T behind one shared immutable model; `eval` makes one virtual call per batch
/// of points, so the wrapped shape's own (statically composed) evaluation stays inlined; a wrapped
/// shape with its own batch `eval` (another `AnySdf`, a run-time composed node) gets the whole
/// batch.

#include <algorithm>
#include <cstddef>
#include <memory>
#include <type_traits>
#include <utility>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/sdf/concepts.hpp"

namespace ebgeom {

/// A type-erased SDF with scalar type `T`. Copies share the wrapped shape (immutable), so copies
/// are cheap and concurrent calls are thread-safe. Its static `kind` is `implicit` (nothing is
/// known at compile time); the object carries what the wrapped shape knows: `dynamic_kind()`
/// (its kind, or its own `dynamic_kind()` for run-time composed shapes), `bounds()`, and
/// `dynamic_prunable()` (`is_prunable` of the wrapped shape). Batch evaluators use the kind (see
/// eval/evaluate.hpp `kind_of`), and `BvhUnion<AnySdf<T>>` puts every prunable object in its
/// tree, so a union of mixed shapes (spheres, boxes, meshes, CSG trees) is a nearest search, not
/// a linear scan; the other objects are evaluated at every query. Construction allocates once (may
/// throw std::bad_alloc); evaluation never allocates or throws.
template <class T> class AnySdf {
 public:
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::implicit;

  // conjunction short-circuits: is_sdf<AnySdf> is never asked while AnySdf is being copied
  template <class S, class = std::enable_if_t<std::conjunction_v<
                         std::negation<std::is_same<S, AnySdf>>, detail::is_sdf<S>>>>
  AnySdf(S shape) // NOLINT(google-explicit-constructor): wrapping is the point
      : impl_(std::make_shared<const Model<S>>(std::move(shape))) {
    static_assert(std::is_same_v<sdf_scalar_t<S>, T>,
                  "ebgeom: AnySdf<T> wraps SDFs whose scalar_type is T");
  }

  /// Writes S(points[i]) to out[i] for i < min(points.size(), out.size()). One virtual call.
  void eval(Span<const Vec3<T>> points, Span<T> out) const noexcept {
    impl_->eval(points.first(std::min(points.size(), out.size())), out);
  }
  /// One point (one virtual call; prefer `eval` for many points).
  T operator()(const Vec3<T>& p) const noexcept { return impl_->value(p); }
  Aabb<T> bounds() const noexcept { return impl_->bounds(); }
  /// The wrapped shape's kind (its `dynamic_kind()` when it has one, else its static `kind`).
  SdfKind dynamic_kind() const noexcept { return impl_->kind(); }
  /// Whether a union may prune the wrapped shape by its bounds (`is_prunable` of it).
  bool dynamic_prunable() const noexcept { return impl_->prunable(); }

 private:
  struct Interface {
    virtual ~Interface() = default;
    virtual void eval(Span<const Vec3<T>>, Span<T>) const noexcept = 0;
    virtual T value(const Vec3<T>&) const noexcept = 0;
    virtual Aabb<T> bounds() const noexcept = 0;
    virtual SdfKind kind() const noexcept = 0;
    virtual bool prunable() const noexcept = 0;
  };
  template <class S> struct Model final : Interface {
    explicit Model(S s) : shape(std::move(s)) {}
    void eval(Span<const Vec3<T>> p, Span<T> out) const noexcept override {
      if constexpr (has_batch_eval_v<S>) { // a run-time composed shape evaluates by batches too
        shape.eval(p, out);
      } else {
        const Vec3<T>* in = p.data();
        T* o = out.data();
        for (std::size_t i = 0, n = p.size(); i < n; ++i) o[i] = shape(in[i]); // inlined
      }
    }
    T value(const Vec3<T>& p) const noexcept override { return shape(p); }
    Aabb<T> bounds() const noexcept override { return shape.bounds(); }
    SdfKind kind() const noexcept override {
      if constexpr (detail::has_dynamic_kind_member<S>::value)
        return shape.dynamic_kind();
      else
        return S::kind;
    }
    bool prunable() const noexcept override { return is_prunable(shape); }
    S shape;
  };
  std::shared_ptr<const Interface> impl_; // never null
};

} // namespace ebgeom
