// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `EbFunction<S>`: the logic shared by the AMReX and Chombo adapters (integrations/), kept in
/// plain C++ so it is tested without those codes: the sign flip to the embedded-boundary
/// convention, 2D slicing, cheap copies sharing one immutable geometry, and thread safety.
///
/// Sign conventions. ebgeom: S(x) < 0 inside the object, > 0 outside. AMReX (EB2 implicit
/// functions: "> 0 body, = 0 boundary, < 0 fluid") and Chombo (`BaseIF::value`: "< 0 is inside
/// the fluid") both read value < 0 as *fluid* (the computational domain) and value > 0 as
/// *covered* (the body). So with the fluid outside the object (the usual case: flow around a part)
/// the EB value is -S; with the fluid inside the object (flow in a pipe or a cavity) it is +S.
///
/// `S` is any ebgeom SDF: `MeshSdf<T>`, an analytic shape, a CSG tree of them (`unite`,
/// `subtract`, `translate`, ...), `BvhUnion<S>`, or a type-erased `AnySdf<T>`.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/sdf/concepts.hpp"

namespace ebgeom {

/// Which side of the ebgeom surface is fluid (the EB code's computational domain).
enum class FluidSide {
  outside, ///< flow around the object: EB value = -S (the default)
  inside   ///< flow inside the object: EB value = +S
};

/// Adapter options.
struct EbOptions {
  /// The side of the surface that the EB code treats as fluid (its negative side).
  FluidSide fluid = FluidSide::outside;
  /// 2D builds (AMReX with AMREX_SPACEDIM = 2, Chombo with CH_SPACEDIM = 2) evaluate the 3D SDF
  /// on the plane z = `z_slice`: the EB code's (x, y) is the point (x, y, z_slice).
  double z_slice = 0.0;
};

/// The factor that turns ebgeom's S into the EB code's value: -1 for fluid outside, +1 inside,
/// and 0 for a `FluidSide` forced out of range by a cast (the adapter then returns NaN at every
/// point rather than silently picking a side).
constexpr int eb_sign(FluidSide fluid) noexcept {
  return fluid == FluidSide::outside ? -1 : (fluid == FluidSide::inside ? 1 : 0);
}

/// Which signs a set of EB values holds (`EbFunction::node_signs`), counted as the EB codes count
/// them: a value is positive (covered) when > 0, zero when == 0, negative (fluid) otherwise, NaN
/// included.
struct EbSigns {
  bool negative = false;
  bool positive = false;
};

/// Wraps an SDF `S` for an embedded-boundary code: value = eb_sign(fluid) * S(x, y, z).
///
/// - Copies are cheap: one shared pointer to the immutable geometry plus two scalars (AMReX copies
///   implicit functions by value, Chombo clones them through `newImplicitFunction`, and both do so
///   per level and per grid). Copying never copies `S` (no deep copy of a mesh or its BVH).
/// - Thread safety: every member is `const`; concurrent calls on one object or on copies are safe
///   whenever `S`'s `const operator()` is (true of every ebgeom SDF: they are immutable and
///   allocation-free). Copying concurrently is safe too (the reference count is atomic).
/// - Cost: one call to `S` (inlined for static shapes) plus a multiply; no allocation.
/// - Whole boxes: `box_sign` proves the sign of a box with one evaluation, `node_values` fills a
///   lattice of nodes (through `S::eval_lattice` when `S` has one), `node_signs` combines both.
///   The EB codes' box hooks (`AmrexGeometryShop`, Chombo's `InsideOutside`) use them; every
///   value is bit for bit the per-point value, so the EB built is the same.
/// - Precision: coordinates of any floating type `R` (the EB code's `Real`) are converted to
///   `S::scalar_type` and the value back to `R`, so a float geometry serves a double code.
template <class S> class EbFunction {
  EBGEOM_REQUIRE_SDF(S);

 public:
  using sdf_type = S;
  using scalar_type = sdf_scalar_t<S>;

  /// Takes the geometry by value (moved once into shared, immutable storage).
  explicit EbFunction(S sdf, const EbOptions& opt = {})
      : EbFunction(std::make_shared<const S>(std::move(sdf)), opt) {}
  /// Shares an existing geometry, e.g. one built once and used on every AMR level, or by two
  /// adapters with different options. Precondition: `sdf` is not null.
  explicit EbFunction(std::shared_ptr<const S> sdf, const EbOptions& opt = {})
      : sdf_(std::move(sdf)),
        sign_(eb_sign(opt.fluid) != 0 ? scalar_type(eb_sign(opt.fluid))
                                      : std::numeric_limits<scalar_type>::quiet_NaN()),
        z_slice_(scalar_type(opt.z_slice)) {
    EBGEOM_ASSERT(sdf_ != nullptr);
  }

  /// The same geometry (shared, not copied) with other options.
  EbFunction with_options(const EbOptions& opt) const { return EbFunction(sdf_, opt); }

  /// EB value at a 3D point (< 0 fluid, > 0 covered, 0 on the boundary).
  template <class R> R operator()(R x, R y, R z) const noexcept {
    static_assert(std::is_floating_point_v<R>, "EbFunction: coordinates must be floating point");
    return R(sign_ * (*sdf_)(Vec3<scalar_type>{scalar_type(x), scalar_type(y), scalar_type(z)}));
  }
  /// EB value in a 2D build: the point (x, y, z_slice).
  template <class R> R operator()(R x, R y) const noexcept {
    static_assert(std::is_floating_point_v<R>, "EbFunction: coordinates must be floating point");
    return R(sign_ * (*sdf_)(Vec3<scalar_type>{scalar_type(x), scalar_type(y), z_slice_}));
  }
  /// EB value from `dim` (2 or 3) coordinates `x[0..dim)`, as AMReX's RealArray and Chombo's
  /// RealVect hold them: 2 coordinates evaluate the z = z_slice plane.
  template <class R> R value(const R* x, int dim) const noexcept {
    EBGEOM_ASSERT(dim == 2 || dim == 3);
    return dim >= 3 ? (*this)(x[0], x[1], x[2]) : (*this)(x[0], x[1]);
  }

  /// True when one value proves the sign of a whole box (`box_sign`): this object's S is `exact`
  /// or a `bound` (1-Lipschitz, |S| <= distance; `kind_of` reads a run-time kind such as
  /// `SignedMeshSdf`'s) and the fluid side is valid.
  bool proves_boxes() const noexcept {
    const SdfKind k = kind_of(*sdf_);
    return (k == SdfKind::exact || k == SdfKind::bound) &&
           (sign_ == scalar_type(1) || sign_ == scalar_type(-1));
  }

  /// The sign of the EB value at every point of the box [lo, hi] (`dim` = 2 or 3 coordinates; a
  /// 2D box lies in the plane z = z_slice), proved by one evaluation at its centre c: -1 when every
  /// value is < 0 (all fluid), +1 when every value is > 0 (all covered), 0 when not proved (the
  /// surface may pass through the box, or `proves_boxes()` is false). Proof: |S(c)| exceeds the
  /// box's half-diagonal r, widened by (1 + 64 eps) and by the rounding of coordinates of the
  /// box's size (as `sample_grid`'s band test), so no point of the box is on the surface.
  template <class R> int box_sign(const R* lo, const R* hi, int dim) const noexcept {
    static_assert(std::is_floating_point_v<R>, "EbFunction: coordinates must be floating point");
    EBGEOM_ASSERT(dim == 2 || dim == 3);
    if (!proves_boxes()) return 0;
    double c[3] = {0, 0, double(z_slice_)}, r2 = 0, big = std::abs(c[2]);
    for (int d = 0; d < dim; ++d) {
      c[d] = 0.5 * (double(lo[d]) + double(hi[d]));
      const double h = 0.5 * (double(hi[d]) - double(lo[d]));
      r2 += h * h;
      big = std::max({big, std::abs(double(lo[d])), std::abs(double(hi[d]))});
    }
    constexpr double eps = double(std::numeric_limits<scalar_type>::epsilon());
    const double margin = std::sqrt(r2) * (1 + 64 * eps) + 8 * eps * big;
    const double v = double(sign_ * (*sdf_)(Vec3<scalar_type>{scalar_type(c[0]), scalar_type(c[1]),
                                                              scalar_type(c[2])}));
    if (v > margin) return 1;
    if (v < -margin) return -1;
    return 0;
  }

  /// EB values at the lattice nodes x_d = origin[d] + R(i_d) * dx[d], i_d in [lo[d], hi[d]]
  /// (`dim` = 2 or 3; the nodes are computed as the EB codes compute them), written to `out`,
  /// x fastest: out[(i - lo[0]) + nx * ((j - lo[1]) + ny * (k - lo[2]))]. Bit for bit the
  /// per-point values. When `S` has a tile evaluation (`MeshSdf`, `SignedMeshSdf`), the lattice
  /// is evaluated in 8^3 tiles, each one `eval_lattice` call (one BVH search for the tile's
  /// candidates instead of one per node). Allocates one tile of scratch; thread-safe.
  template <class R>
  void node_values(const R* origin, const R* dx, const int* lo, const int* hi, int dim,
                   R* out) const {
    static_assert(std::is_floating_point_v<R>, "EbFunction: coordinates must be floating point");
    EBGEOM_ASSERT(dim == 2 || dim == 3);
    std::array<int, 3> l{lo[0], lo[1], dim == 3 ? lo[2] : 0};
    std::array<int, 3> h{hi[0], hi[1], dim == 3 ? hi[2] : 0};
    std::array<std::size_t, 3> n{};
    for (int d = 0; d < 3; ++d) {
      if (h[d] < l[d]) return;
      n[d] = std::size_t(h[d] - l[d]) + 1;
    }
    auto coord = [&](int d, int i) {
      return d < dim ? scalar_type(origin[d] + R(i) * dx[d]) : z_slice_;
    };
    bool tiles = has_lattice_eval_v<S>;
    // A few nodes (one cell's corners, as Chombo asks) cost less per point than a tile search.
    if (n[0] * n[1] * n[2] < 64) tiles = false;
    if (tiles) {
      constexpr int tile = 8;
      std::vector<Vec3<scalar_type>> pts;
      std::vector<scalar_type> vals;
      pts.reserve(tile * tile * tile);
      vals.reserve(tile * tile * tile);
      for (int k0 = l[2]; k0 <= h[2]; k0 += tile)
        for (int j0 = l[1]; j0 <= h[1]; j0 += tile)
          for (int i0 = l[0]; i0 <= h[0]; i0 += tile) {
            const int k1 = std::min(h[2], k0 + tile - 1), j1 = std::min(h[1], j0 + tile - 1),
                      i1 = std::min(h[0], i0 + tile - 1);
            pts.clear();
            for (int k = k0; k <= k1; ++k)
              for (int j = j0; j <= j1; ++j)
                for (int i = i0; i <= i1; ++i)
                  pts.push_back({coord(0, i), coord(1, j), coord(2, k)});
            vals.resize(pts.size());
            lattice_eval(
                *sdf_, Span<const Vec3<scalar_type>>(pts.data(), pts.size()),
                {{std::size_t(i1 - i0 + 1), std::size_t(j1 - j0 + 1), std::size_t(k1 - k0 + 1)}},
                Span<scalar_type>(vals.data(), vals.size()));
            std::size_t t = 0;
            for (int k = k0; k <= k1; ++k)
              for (int j = j0; j <= j1; ++j)
                for (int i = i0; i <= i1; ++i)
                  out[std::size_t(i - l[0]) +
                      n[0] * (std::size_t(j - l[1]) + n[1] * std::size_t(k - l[2]))] =
                      R(sign_ * vals[t++]);
          }
    } else {
      std::size_t t = 0;
      for (int k = l[2]; k <= h[2]; ++k)
        for (int j = l[1]; j <= h[1]; ++j)
          for (int i = l[0]; i <= h[0]; ++i)
            out[t++] = R(sign_ * (*sdf_)(Vec3<scalar_type>{coord(0, i), coord(1, j), coord(2, k)}));
    }
  }

  /// Which signs the EB values take at the lattice nodes of `node_values` (same arguments, no
  /// output), stopping as soon as both are found. Boxes are split in halves along their longest
  /// side; a box proved by `box_sign` counts with one evaluation, and boxes of at most 8^3 nodes
  /// are evaluated (`node_values`). The answer is that of evaluating every node.
  template <class R>
  EbSigns node_signs(const R* origin, const R* dx, const int* lo, const int* hi, int dim) const {
    EbSigns s;
    std::array<int, 3> l{lo[0], lo[1], dim == 3 ? lo[2] : 0};
    std::array<int, 3> h{hi[0], hi[1], dim == 3 ? hi[2] : 0};
    std::vector<R> vals;
    add_node_signs(origin, dx, l, h, dim, s, vals);
    return s;
  }

  /// The wrapped ebgeom SDF (S < 0 inside the object).
  const S& sdf() const noexcept { return *sdf_; }
  /// The shared geometry, to build more adapters over it without copying it.
  const std::shared_ptr<const S>& shared_sdf() const noexcept { return sdf_; }
  /// Bounds of the object (of S's interior for closed shapes), e.g. to choose an EB domain.
  Aabb<scalar_type> bounds() const noexcept { return sdf_->bounds(); }
  FluidSide fluid_side() const noexcept {
    return sign_ < scalar_type(0) ? FluidSide::outside : FluidSide::inside;
  }
  /// The z of the plane that 2D calls evaluate (converted to `scalar_type`).
  double z_slice() const noexcept { return double(z_slice_); }
  EbOptions options() const noexcept {
    EbOptions opt;
    opt.fluid = fluid_side();
    opt.z_slice = z_slice();
    return opt;
  }

 private:
  // eval_lattice when `S` has one (only reached then: `node_values` checks).
  template <class U>
  static void lattice_eval(const U& sdf, Span<const Vec3<scalar_type>> pts,
                           const std::array<std::size_t, 3>& dims, Span<scalar_type> out) {
    if constexpr (has_lattice_eval_v<U>)
      sdf.eval_lattice(pts, dims, out);
    else
      for (std::size_t i = 0; i < pts.size(); ++i) out[i] = sdf(pts[i]);
  }

  template <class R>
  void add_node_signs(const R* origin, const R* dx, std::array<int, 3> l, std::array<int, 3> h,
                      int dim, EbSigns& s, std::vector<R>& vals) const {
    if (s.negative && s.positive) return;
    std::size_t count = 1;
    int longest = 0;
    for (int d = 0; d < 3; ++d) {
      if (h[d] < l[d]) return;
      count *= std::size_t(h[d] - l[d]) + 1;
      if (h[d] - l[d] > h[longest] - l[longest]) longest = d;
    }
    if (count > 8 * 8 * 8) {
      R blo[3], bhi[3];
      for (int d = 0; d < dim; ++d) {
        blo[d] = origin[d] + R(l[d]) * dx[d];
        bhi[d] = origin[d] + R(h[d]) * dx[d];
        if (bhi[d] < blo[d]) std::swap(blo[d], bhi[d]);
      }
      const int sign = box_sign(blo, bhi, dim);
      if (sign != 0) {
        (sign < 0 ? s.negative : s.positive) = true;
        return;
      }
      const int mid = l[longest] + (h[longest] - l[longest]) / 2;
      std::array<int, 3> h1 = h, l2 = l;
      h1[longest] = mid;
      l2[longest] = mid + 1;
      add_node_signs(origin, dx, l, h1, dim, s, vals);
      add_node_signs(origin, dx, l2, h, dim, s, vals);
      return;
    }
    vals.resize(count);
    node_values(origin, dx, l.data(), h.data(), dim, vals.data());
    for (const R v : vals) {
      if (v > R(0))
        s.positive = true;
      else if (!(v == R(0)))
        s.negative = true;
    }
  }

  std::shared_ptr<const S> sdf_;
  scalar_type sign_;
  scalar_type z_slice_;
};

/// `EbFunction` over `sdf` (moved into shared storage), deducing `S`.
template <class S> EbFunction<S> make_eb_function(S sdf, const EbOptions& opt = {}) {
  return EbFunction<S>(std::move(sdf), opt);
}
/// `EbFunction` sharing `sdf` (not null), deducing `S`.
template <class S>
EbFunction<S> make_eb_function(std::shared_ptr<const S> sdf, const EbOptions& opt = {}) {
  return EbFunction<S>(std::move(sdf), opt);
}
template <class S>
EbFunction<S> make_eb_function(std::shared_ptr<S> sdf, const EbOptions& opt = {}) {
  return EbFunction<S>(std::shared_ptr<const S>(std::move(sdf)), opt);
}

} // namespace ebgeom
