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

#include <limits>
#include <memory>
#include <type_traits>
#include <utility>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
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

/// Wraps an SDF `S` for an embedded-boundary code: value = eb_sign(fluid) * S(x, y, z).
///
/// - Copies are cheap: one shared pointer to the immutable geometry plus two scalars (AMReX copies
///   implicit functions by value, Chombo clones them through `newImplicitFunction`, and both do so
///   per level and per grid). Copying never copies `S` (no deep copy of a mesh or its BVH).
/// - Thread safety: every member is `const`; concurrent calls on one object or on copies are safe
///   whenever `S`'s `const operator()` is (true of every ebgeom SDF: they are immutable and
///   allocation-free). Copying concurrently is safe too (the reference count is atomic).
/// - Cost: one call to `S` (inlined for static shapes) plus a multiply; no allocation.
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
