// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// `Program<T>`: a scene compiled into a flat post-order tape. Each instruction processes a whole
// batch of points (one `switch` per instruction per batch of up to 256 points): leaves push a
// value buffer, transforms push/pop a transformed point buffer, CSG ops pop their operands and
// push the result. Immutable after compilation; `eval` is thread-safe.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/scene/mesh_input.hpp"
#include "ebgeom/sdf/concepts.hpp"

#if __has_include("ebgeom/sdf/bvh_union.hpp")
#include "ebgeom/sdf/bvh_union.hpp"
#define EBGEOM_CLI_HAS_BVH_UNION 1
#else
#define EBGEOM_CLI_HAS_BVH_UNION 0
#endif

namespace ebgeom::scene {

enum class Op : std::uint8_t {
  sphere,     // p: cx cy cz r
  box,        // p: cx cy cz hx hy hz rounding
  capsule,    // p: ax ay az bx by bz r
  cylinder,   // p: ax ay az bx by bz r           (capped, exact)
  torus,      // p: cx cy cz R r                  (axis z)
  cone,       // p: ax ay az bx by bz ra rb       (capped, exact)
  plane,      // p: nx ny nz d                    (inside: n.p < d)
  mesh,       // a: mesh index; n = 1: unsigned distance
  push_xform, // a: transform index; pushes transformed points
  pop_xform,  // a: transform index; pops points, scales the top value
  unite,      // n operands; p: k (0 = sharp)
  intersect,  // n operands; p: k
  subtract,   // n operands (first minus the others); p: k
  offset,     // p: r        value - r
  shell,      // p: t        |value| - t
  bvh_union,  // a: union index; n = 1: children are exact (pruned), 0: not (linear)
};

/// One tape instruction: 12 B.
struct Instr {
  Op op;
  std::uint32_t a = 0; // first parameter index, or mesh/transform index
  std::uint32_t n = 0; // operand count (CSG)
};

/// Rigid transform plus uniform scale: world = t + R (s * local).
template <class T> struct Xform {
  std::array<T, 9> r{{1, 0, 0, 0, 1, 0, 0, 0, 1}}; // row-major rotation
  Vec3<T> t = Vec3<T>::zero();
  T s = 1;
  Vec3<T> to_local(const Vec3<T>& p) const noexcept {
    const Vec3<T> q = p - t;
    // R^T q / s
    return Vec3<T>{r[0] * q.x + r[3] * q.y + r[6] * q.z, r[1] * q.x + r[4] * q.y + r[7] * q.z,
                   r[2] * q.x + r[5] * q.y + r[8] * q.z} /
           s;
  }
  Vec3<T> to_world(const Vec3<T>& p) const noexcept {
    const Vec3<T> q = p * s;
    return Vec3<T>{r[0] * q.x + r[1] * q.y + r[2] * q.z, r[3] * q.x + r[4] * q.y + r[5] * q.z,
                   r[6] * q.x + r[7] * q.y + r[8] * q.z} +
           t;
  }
};

namespace internal {
template <class T> inline T smin(T a, T b, T k) noexcept {
  if (k <= T(0)) return std::min(a, b);
  const T h = std::max(k - std::abs(a - b), T(0)) / k;
  return std::min(a, b) - h * h * k * T(0.25);
}
template <class T> inline T smax(T a, T b, T k) noexcept { return -smin(-a, -b, k); }
} // namespace internal

template <class T> class Program;

/// A compiled subtree used as one operand of a BVH union. `K` is its kind: `exact` operands let
/// the union prune (S >= distance to the box outside it), others are scanned.
template <class T, SdfKind K> struct Piece {
  using scalar_type = T;
  static constexpr SdfKind kind = K;
  std::shared_ptr<const Program<T>> prog;
  T operator()(const Vec3<T>& p) const noexcept { return (*prog)(p); }
  Aabb<T> bounds() const noexcept { return prog->bounds(); }
};

#if EBGEOM_CLI_HAS_BVH_UNION
template <class T> using ExactUnion = BvhUnion<Piece<T, SdfKind::exact>>;
template <class T> using BoundUnion = BvhUnion<Piece<T, SdfKind::implicit>>;
#endif

template <class T> class Program {
 public:
  using scalar_type = T;
  /// Conservative static kind; `dynamic_kind()` gives the compiled scene's real kind.
  static constexpr SdfKind kind = SdfKind::implicit;
  static constexpr std::size_t batch = 256;

  std::vector<Instr> code;
  std::vector<T> params;
  std::vector<Xform<T>> xforms;
  std::vector<std::shared_ptr<const CliMeshSdf<T>>> meshes;
#if EBGEOM_CLI_HAS_BVH_UNION
  std::vector<std::shared_ptr<const ExactUnion<T>>> exact_unions;
  std::vector<std::shared_ptr<const BoundUnion<T>>> bound_unions;
#endif
  std::size_t union_triangles = 0; // triangles inside accelerated unions
  Aabb<T> box = Aabb<T>::infinite();
  SdfKind scene_kind = SdfKind::exact;
  std::size_t max_values = 1, max_points = 1; // stack depths proven by the compiler

  SdfKind dynamic_kind() const noexcept { return scene_kind; }
  Aabb<T> bounds() const noexcept { return box; }
  std::size_t triangle_count() const noexcept {
    std::size_t n = 0;
    for (const auto& m : meshes) n += m->mesh().triangle_count();
    return n + union_triangles;
  }

  T operator()(const Vec3<T>& p) const noexcept {
    // Small tapes run on stack buffers (no allocation): operands of BVH unions are called per
    // point.
    if (max_values <= 16 && max_points <= 15) {
      T vals[16];
      Vec3<T> pts[16];
      run(Span<const Vec3<T>>(&p, 1), vals, pts, 1);
      return vals[0];
    }
    T v = 0;
    eval(Span<const Vec3<T>>(&p, 1), Span<T>(&v, 1));
    return v;
  }

  /// out[i] = S(points[i]). Thread-safe.
  void eval(Span<const Vec3<T>> points, Span<T> out) const {
    // Buffers sized for this call (one value per point for scalar calls).
    const std::size_t stride = std::max<std::size_t>(1, std::min(batch, points.size()));
    std::vector<T> vals(max_values * stride);
    std::vector<Vec3<T>> pts((max_points + 1) * stride);
    for (std::size_t s = 0; s < points.size(); s += stride) {
      const std::size_t n = std::min(stride, points.size() - s);
      run(points.subspan(s, n), vals.data(), pts.data(), stride);
      for (std::size_t i = 0; i < n; ++i) out[s + i] = vals[i];
    }
  }

 private:
  void run(Span<const Vec3<T>> in, T* vals, Vec3<T>* pts, std::size_t stride) const {
    const std::size_t n = in.size();
    std::size_t vt = 0; // value stack height
    std::size_t pt = 0; // point stack height (0 = the input)
    auto P = [&](std::size_t level) -> const Vec3<T>* {
      return level == 0 ? in.data() : pts + (level - 1) * stride;
    };
    for (const Instr& ins : code) {
      const T* q = params.data() + ins.a;
      const Vec3<T>* p = P(pt);
      T* v = vals + vt * stride;
      switch (ins.op) {
      case Op::sphere: {
        const Vec3<T> c{q[0], q[1], q[2]};
        for (std::size_t i = 0; i < n; ++i) v[i] = norm(p[i] - c) - q[3];
        ++vt;
        break;
      }
      case Op::box: {
        const Vec3<T> c{q[0], q[1], q[2]};
        const Vec3<T> h = Vec3<T>{q[3], q[4], q[5]} - Vec3<T>::constant(q[6]);
        for (std::size_t i = 0; i < n; ++i) {
          const Vec3<T> d = abs(p[i] - c) - h;
          v[i] = norm(max(d, Vec3<T>::zero())) + std::min(max_component(d), T(0)) - q[6];
        }
        ++vt;
        break;
      }
      case Op::capsule: {
        const Vec3<T> a{q[0], q[1], q[2]}, ab = Vec3<T>{q[3], q[4], q[5]} - a;
        const T ab2 = dot(ab, ab);
        for (std::size_t i = 0; i < n; ++i) {
          const T t = ab2 > T(0) ? clamp(dot(p[i] - a, ab) / ab2, T(0), T(1)) : T(0);
          v[i] = norm(p[i] - (a + ab * t)) - q[6];
        }
        ++vt;
        break;
      }
      case Op::cylinder: { // exact capped cylinder (I. Quilez)
        const Vec3<T> a{q[0], q[1], q[2]}, ba = Vec3<T>{q[3], q[4], q[5]} - a;
        const T baba = dot(ba, ba), r = q[6];
        for (std::size_t i = 0; i < n; ++i) {
          const Vec3<T> pa = p[i] - a;
          const T paba = dot(pa, ba);
          const T x = norm(pa * baba - ba * paba) - r * baba;
          const T y = std::abs(paba - baba * T(0.5)) - baba * T(0.5);
          const T x2 = x * x, y2 = y * y * baba;
          const T d = std::max(x, y) < T(0) ? -std::min(x2, y2)
                                            : ((x > T(0) ? x2 : T(0)) + (y > T(0) ? y2 : T(0)));
          v[i] = std::copysign(std::sqrt(std::abs(d)), d) / baba;
        }
        ++vt;
        break;
      }
      case Op::cone: { // exact capped cone between a (radius ra) and b (radius rb) (I. Quilez)
        const Vec3<T> a{q[0], q[1], q[2]}, ba = Vec3<T>{q[3], q[4], q[5]} - a;
        const T ra = q[6], rb = q[7], rba = rb - ra, baba = dot(ba, ba);
        const T kk = rba * rba + baba;
        for (std::size_t i = 0; i < n; ++i) {
          const Vec3<T> pa = p[i] - a;
          const T papa = dot(pa, pa), paba = dot(pa, ba) / baba;
          const T x = std::sqrt(std::max(papa - paba * paba * baba, T(0)));
          const T cax = std::max(T(0), x - (paba < T(0.5) ? ra : rb));
          const T cay = std::abs(paba - T(0.5)) - T(0.5);
          const T f = clamp((rba * (x - ra) + paba * baba) / kk, T(0), T(1));
          const T cbx = x - ra - f * rba, cby = paba - f;
          const T sgn = (cbx < T(0) && cay < T(0)) ? T(-1) : T(1);
          v[i] =
              sgn * std::sqrt(std::min(cax * cax + cay * cay * baba, cbx * cbx + cby * cby * baba));
        }
        ++vt;
        break;
      }
      case Op::torus: {
        const Vec3<T> c{q[0], q[1], q[2]};
        for (std::size_t i = 0; i < n; ++i) {
          const Vec3<T> d = p[i] - c;
          const T qx = std::sqrt(d.x * d.x + d.y * d.y) - q[3];
          v[i] = std::sqrt(qx * qx + d.z * d.z) - q[4];
        }
        ++vt;
        break;
      }
      case Op::plane: {
        const Vec3<T> nn{q[0], q[1], q[2]};
        for (std::size_t i = 0; i < n; ++i) v[i] = dot(nn, p[i]) - q[3];
        ++vt;
        break;
      }
      case Op::mesh: {
        const auto& m = *meshes[ins.a];
        for (std::size_t i = 0; i < n; ++i) v[i] = m(p[i]);
        if (ins.n == 1) // unsigned distance
          for (std::size_t i = 0; i < n; ++i) v[i] = std::abs(v[i]);
        ++vt;
        break;
      }
      case Op::push_xform: {
        const Xform<T>& x = xforms[ins.a];
        Vec3<T>* o = pts + pt * stride;
        for (std::size_t i = 0; i < n; ++i) o[i] = x.to_local(p[i]);
        ++pt;
        break;
      }
      case Op::pop_xform: {
        const T s = xforms[ins.a].s;
        T* top = vals + (vt - 1) * stride;
        if (s != T(1))
          for (std::size_t i = 0; i < n; ++i) top[i] *= s;
        --pt;
        break;
      }
      case Op::unite:
      case Op::intersect:
      case Op::subtract: {
        const T k = q[0];
        T* first = vals + (vt - ins.n) * stride;
        for (std::uint32_t c = 1; c < ins.n; ++c) {
          const T* other = first + c * stride;
          if (ins.op == Op::unite)
            for (std::size_t i = 0; i < n; ++i) first[i] = internal::smin(first[i], other[i], k);
          else if (ins.op == Op::intersect)
            for (std::size_t i = 0; i < n; ++i) first[i] = internal::smax(first[i], other[i], k);
          else
            for (std::size_t i = 0; i < n; ++i) first[i] = internal::smax(first[i], -other[i], k);
        }
        vt -= ins.n - 1;
        break;
      }
      case Op::offset: {
        T* top = vals + (vt - 1) * stride;
        for (std::size_t i = 0; i < n; ++i) top[i] -= q[0];
        break;
      }
      case Op::bvh_union: {
#if EBGEOM_CLI_HAS_BVH_UNION
        if (ins.n == 1) {
          const auto& u = *exact_unions[ins.a];
          for (std::size_t i = 0; i < n; ++i) v[i] = u(p[i]);
        } else {
          const auto& u = *bound_unions[ins.a];
          for (std::size_t i = 0; i < n; ++i) v[i] = u(p[i]);
        }
#endif
        ++vt;
        break;
      }
      case Op::shell: {
        T* top = vals + (vt - 1) * stride;
        for (std::size_t i = 0; i < n; ++i) top[i] = std::abs(top[i]) - q[0];
        break;
      }
      }
    }
  }
};

} // namespace ebgeom::scene
