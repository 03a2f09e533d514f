// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// The run-time nodes a compiled scene is made of. Every value is the library's: leaves are the
// library's shapes (sdf/shapes.hpp) and `SignedMeshSdf`, wrapped in `AnySdf<T>`; the nodes below
// hold the library's transforms (`RigidTransformed`, `Scaled`, `Offset`, `Shell`), its CSG rules
// (`Union`, `Intersection`, `Difference`: a fold of std::min / std::max from +-infinity) and its
// smooth minimum (`PolynomialBlend`), and `BvhUnion<AnySdf<T>>` for accelerated unions. What the
// nodes add is batch evaluation: `eval(points, out)` makes one virtual call per node per chunk
// of points (the scene tape's cost) instead of one per node per point, with the same values bit
// for bit as the single-point `operator()` (scene/tests/scene_test.cpp checks both against the
// library's static types).
//
// A node's kind is the library's rule applied to its children's run-time kinds
// (`dynamic_kind()`); its box is the one the scene compiler proved (it contains the zero level set
// and the inside, so a BVH union may prune by it).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/rotation.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/sdf/any_sdf.hpp"
#include "ebgeom/sdf/bvh_union.hpp"
#include "ebgeom/sdf/concepts.hpp"
#include "ebgeom/sdf/csg.hpp"
#include "ebgeom/sdf/signed_mesh_sdf.hpp"
#include "ebgeom/sdf/transforms.hpp"

namespace ebgeom::scene {

/// Points per chunk of a node's batch evaluation (its scratch buffers live on the stack).
inline constexpr std::size_t node_chunk = 64;

/// Nothing: +infinity everywhere (the union of no shapes), an empty box.
template <class T> struct EmptyNode {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  T operator()(const Vec3<T>&) const noexcept { return std::numeric_limits<T>::infinity(); }
  Aabb<T> bounds() const noexcept { return {}; }
};

/// A mesh of a scene: the library's `SignedMeshSdf`, shared with the scene's mesh list.
template <class T> struct MeshNode {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::implicit; // the object's own: dynamic_kind()
  std::shared_ptr<const SignedMeshSdf<T>> sdf;

  T operator()(const Vec3<T>& p) const noexcept { return (*sdf)(p); }
  Aabb<T> bounds() const noexcept { return sdf->bounds(); }
  SdfKind dynamic_kind() const noexcept { return sdf->dynamic_kind(); }
};

/// The CSG operations of a scene node.
enum class CsgOp { unite, intersect, subtract };

/// n-ary union, intersection or difference (first minus the others) of run-time children, sharp
/// (`smooth == 0`: the library's `Union`, `Intersection`, `Difference`) or smooth (the library's
/// `SmoothUnion`, `SmoothIntersection`, `SmoothDifference` with `PolynomialBlend`, folded left:
/// op(op(c0, c1), c2) ...). Kind: a single child's kind, else at best `bound` (sdf/csg.hpp).
template <class T> class CsgNode {
 public:
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::implicit; // the object's own: dynamic_kind()

  /// `children` is not empty; `box` contains the result's zero level set and inside.
  CsgNode(CsgOp op, std::vector<AnySdf<T>> children, T smooth, const Aabb<T>& box)
      : op_(op), children_(std::move(children)), k_(smooth), box_(box) {
    kind_ = SdfKind::exact;
    for (const AnySdf<T>& c : children_) kind_ = weakest(kind_, c.dynamic_kind());
    if (children_.size() > 1) kind_ = weakest(kind_, SdfKind::bound);
  }

  T operator()(const Vec3<T>& p) const noexcept {
    T r = start(children_[0](p));
    for (std::size_t c = 1; c < children_.size(); ++c) r = combine(r, children_[c](p));
    return r;
  }
  void eval(Span<const Vec3<T>> points, Span<T> out) const noexcept {
    T tmp[node_chunk];
    for (std::size_t s = 0; s < points.size(); s += node_chunk) {
      const std::size_t n = std::min(node_chunk, points.size() - s);
      const Span<const Vec3<T>> p = points.subspan(s, n);
      T* o = out.data() + s;
      children_[0].eval(p, Span<T>(o, n));
      for (std::size_t i = 0; i < n; ++i) o[i] = start(o[i]);
      for (std::size_t c = 1; c < children_.size(); ++c) {
        children_[c].eval(p, Span<T>(tmp, n));
        for (std::size_t i = 0; i < n; ++i) o[i] = combine(o[i], tmp[i]);
      }
    }
  }
  Aabb<T> bounds() const noexcept { return box_; }
  SdfKind dynamic_kind() const noexcept { return kind_; }

 private:
  /// The first operand as the library's fold starts: std::min(+inf, v) for a sharp union,
  /// std::max(-inf, v) for a sharp intersection, v itself otherwise.
  T start(T v) const noexcept {
    if (k_ > T(0) || op_ == CsgOp::subtract) return v;
    return op_ == CsgOp::unite ? std::min(std::numeric_limits<T>::infinity(), v)
                               : std::max(-std::numeric_limits<T>::infinity(), v);
  }
  T combine(T r, T v) const noexcept {
    if (k_ > T(0)) {
      switch (op_) {
      case CsgOp::unite:
        return PolynomialBlend::smin(r, v, k_);
      case CsgOp::intersect:
        return -PolynomialBlend::smin(-r, -v, k_);
      default:
        return -PolynomialBlend::smin(-r, v, k_);
      }
    }
    switch (op_) {
    case CsgOp::unite:
      return std::min(r, v);
    case CsgOp::intersect:
      return std::max(r, v);
    default:
      return std::max(r, -v);
    }
  }

  CsgOp op_;
  std::vector<AnySdf<T>> children_;
  T k_;
  Aabb<T> box_;
  SdfKind kind_;
};

/// A child under the scene transform world = t + R (s * local): the library's
/// `RigidTransformed<Scaled<...>>`, value s * S(R^T (p - t) / s). Keeps the kind.
template <class T> class TransformNode {
 public:
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::implicit; // the object's own: dynamic_kind()

  TransformNode(AnySdf<T> child, const Mat3<T>& r, const Vec3<T>& t, T s, const Aabb<T>& box)
      : x_(transform(scale(std::move(child), s), r, t)), rt_(r.transposed()), box_(box) {}

  T operator()(const Vec3<T>& p) const noexcept { return x_(p); }
  void eval(Span<const Vec3<T>> points, Span<T> out) const noexcept {
    // The same operations as RigidTransformed then Scaled, a chunk at a time.
    Vec3<T> local[node_chunk];
    const T s = x_.shape.factor;
    for (std::size_t b = 0; b < points.size(); b += node_chunk) {
      const std::size_t n = std::min(node_chunk, points.size() - b);
      for (std::size_t i = 0; i < n; ++i) local[i] = (rt_ * (points[b + i] - x_.t)) / s;
      T* o = out.data() + b;
      x_.shape.shape.eval(Span<const Vec3<T>>(local, n), Span<T>(o, n));
      for (std::size_t i = 0; i < n; ++i) o[i] = s * o[i];
    }
  }
  Aabb<T> bounds() const noexcept { return box_; }
  SdfKind dynamic_kind() const noexcept { return x_.shape.shape.dynamic_kind(); }

 private:
  RigidTransformed<Scaled<AnySdf<T>>> x_;
  Mat3<T> rt_; // R^T, as RigidTransformed computes it
  Aabb<T> box_;
};

/// The library's `Offset` (S - r) or `Shell` (|S| - t) of a child. Kind: at best `bound`.
template <class T> class ModifierNode {
 public:
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::implicit; // the object's own: dynamic_kind()
  enum class Op { offset, shell };

  ModifierNode(Op op, AnySdf<T> child, T amount, const Aabb<T>& box)
      : op_(op), offset_{child, amount}, shell_{std::move(child), amount}, box_(box) {}

  T operator()(const Vec3<T>& p) const noexcept {
    return op_ == Op::offset ? offset_(p) : shell_(p);
  }
  void eval(Span<const Vec3<T>> points, Span<T> out) const noexcept {
    offset_.shape.eval(points, out);
    if (op_ == Op::offset)
      for (std::size_t i = 0; i < points.size(); ++i) out[i] = out[i] - offset_.r;
    else
      for (std::size_t i = 0; i < points.size(); ++i) out[i] = std::abs(out[i]) - shell_.t;
  }
  Aabb<T> bounds() const noexcept { return box_; }
  SdfKind dynamic_kind() const noexcept {
    return weakest(offset_.shape.dynamic_kind(), SdfKind::bound);
  }

 private:
  Op op_;
  Offset<AnySdf<T>> offset_;
  Shell<AnySdf<T>> shell_;
  Aabb<T> box_;
};

/// A sharp union searched through the library's `BvhUnion<AnySdf<T>>` (children that are
/// prunable go in its tree). Kind: a single child's kind, else at best `bound`.
template <class T> class BvhUnionNode {
 public:
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::implicit; // the object's own: dynamic_kind()

  BvhUnionNode(BvhUnion<AnySdf<T>> u, SdfKind kind_of_children, std::size_t count)
      : u_(std::make_shared<const BvhUnion<AnySdf<T>>>(std::move(u))),
        kind_(count > 1 ? weakest(kind_of_children, SdfKind::bound) : kind_of_children) {}

  T operator()(const Vec3<T>& p) const noexcept { return (*u_)(p); }
  Aabb<T> bounds() const noexcept { return u_->bounds(); }
  SdfKind dynamic_kind() const noexcept { return kind_; }

 private:
  std::shared_ptr<const BvhUnion<AnySdf<T>>> u_;
  SdfKind kind_;
};

} // namespace ebgeom::scene
