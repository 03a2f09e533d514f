#pragma once
/// \file
/// `EbFunction<S>`: the logic shared by the AMReX and Chombo adapters (integrations/), kept in
/// plain C++ so it is tested without those codes: the sign flip to the embedded-boundary
/// convention, 2D slicing, cheap copies sharing one immutable geometry, and thread safety.
///
/// AMReX (EB2 implicit functions) and Chombo (BaseIF) both read value < 0 as *fluid* (inside the
/// computational domain) and value > 0 as *covered* (inside the body). ebgeom's S is < 0 inside
/// the object. So with the fluid outside the object (the usual case: flow around a part) the EB
/// value is -S; with the fluid inside the object (flow in a pipe or cavity) it is +S.

#include <memory>
#include <type_traits>
#include <utility>

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
  FluidSide fluid = FluidSide::outside;
  /// 2D builds (AMReX/Chombo with SPACEDIM = 2) evaluate the plane z = `z_slice`.
  double z_slice = 0.0;
};

/// Wraps an SDF `S` for an embedded-boundary code. Copies are cheap (one shared pointer to the
/// immutable geometry: AMReX copies implicit functions by value, Chombo clones them through
/// `newImplicitFunction`), and concurrent `const` calls are safe as long as `S`'s are (every
/// ebgeom SDF is). Evaluation costs one inlined call to `S` plus a multiply.
template <class S> class EbFunction {
  EBGEOM_REQUIRE_SDF(S);

 public:
  using sdf_type = S;
  using scalar_type = sdf_scalar_t<S>;

  /// Takes the geometry by value (moved into shared, immutable storage).
  explicit EbFunction(S sdf, const EbOptions& opt = {})
      : EbFunction(std::make_shared<const S>(std::move(sdf)), opt) {}
  /// Shares an existing geometry, e.g. one built once and used on every AMR level.
  /// Precondition: `sdf` is not null.
  explicit EbFunction(std::shared_ptr<const S> sdf, const EbOptions& opt = {})
      : sdf_(std::move(sdf)),
        sign_(opt.fluid == FluidSide::outside ? scalar_type(-1) : scalar_type(1)),
        z_slice_(scalar_type(opt.z_slice)) {}

  /// EB value at a 3D point (< 0 fluid, > 0 covered, 0 on the boundary).
  template <class R> R operator()(R x, R y, R z) const noexcept {
    return R(sign_ * (*sdf_)(Vec3<scalar_type>{scalar_type(x), scalar_type(y), scalar_type(z)}));
  }
  /// EB value in a 2D build: the point (x, y, z_slice).
  template <class R> R operator()(R x, R y) const noexcept {
    return R(sign_ * (*sdf_)(Vec3<scalar_type>{scalar_type(x), scalar_type(y), z_slice_}));
  }
  /// EB value from `dim` (2 or 3) coordinates, as AMReX's RealArray and Chombo's RealVect give.
  template <class R> R value(const R* x, int dim) const noexcept {
    return dim >= 3 ? (*this)(x[0], x[1], x[2]) : (*this)(x[0], x[1]);
  }

  /// The wrapped ebgeom SDF (S < 0 inside the object).
  const S& sdf() const noexcept { return *sdf_; }
  const std::shared_ptr<const S>& shared_sdf() const noexcept { return sdf_; }
  FluidSide fluid_side() const noexcept {
    return sign_ < scalar_type(0) ? FluidSide::outside : FluidSide::inside;
  }
  double z_slice() const noexcept { return double(z_slice_); }

 private:
  std::shared_ptr<const S> sdf_;
  scalar_type sign_;
  scalar_type z_slice_;
};

} // namespace ebgeom
