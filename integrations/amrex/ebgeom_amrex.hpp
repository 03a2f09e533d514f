#pragma once
/// \file
/// ebgeom SDFs as AMReX EB2 implicit functions.
///
/// ```cpp
/// auto sdf = ...;                                   // any ebgeom SDF: mesh, analytic, CSG
/// ebgeom::AmrexImplicitFunction<decltype(sdf)> f(sdf);   // fluid outside the object
/// auto gshop = amrex::EB2::makeShop(f);
/// amrex::EB2::Build(gshop, geom, max_level, max_level);
/// ```
/// AMReX reads value < 0 as fluid. The adapter returns -S when the fluid is outside the object
/// (default) and +S when it is inside (`EbOptions::fluid`). In 2D builds (AMREX_SPACEDIM == 2) it
/// evaluates the plane z = `EbOptions::z_slice`. Copies share the geometry (AMReX copies implicit
/// functions by value), and concurrent calls are thread-safe. All logic lives in
/// `ebgeom/adapters/eb_function.hpp`, which is unit-tested without AMReX.

#include <AMReX_Array.H>
#include <AMReX_REAL.H>
#include <AMReX_SPACE.H>

#include <utility>

#include "ebgeom/adapters/eb_function.hpp"

namespace ebgeom {

/// AMReX EB2 implicit function over the ebgeom SDF `S`.
template <class S> class AmrexImplicitFunction {
 public:
  explicit AmrexImplicitFunction(S sdf, const EbOptions& opt = {}) : f_(std::move(sdf), opt) {}
  explicit AmrexImplicitFunction(EbFunction<S> f) : f_(std::move(f)) {}

  ::amrex::Real operator()(AMREX_D_DECL(::amrex::Real x, ::amrex::Real y,
                                        ::amrex::Real z)) const noexcept {
    return f_(AMREX_D_DECL(x, y, z));
  }
  ::amrex::Real operator()(const ::amrex::RealArray& p) const noexcept {
    return f_(AMREX_D_DECL(p[0], p[1], p[2]));
  }

  const EbFunction<S>& function() const noexcept { return f_; }

 private:
  EbFunction<S> f_;
};

} // namespace ebgeom
