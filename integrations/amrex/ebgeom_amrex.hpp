// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// ebgeom SDFs as AMReX EB2 implicit functions.
///
/// ```cpp
/// #include <AMReX_EB2.H>
/// #include "ebgeom_amrex.hpp"
///
/// auto soup = ebgeom::io::read_mesh<double>("part.stl").value();           // read the file
/// auto mesh = ebgeom::make_shared_mesh_sdf(soup).value();                  // built once
/// ebgeom::AmrexImplicitFunction<ebgeom::SignedMeshSdf<double>> f(mesh);    // fluid outside
/// auto gshop = amrex::EB2::makeShop(f);     // copies f: cheap (or make_amrex_shop, below)
/// amrex::EB2::Build(gshop, geom, required_coarsening_level, max_coarsening_level);
/// ```
/// Any ebgeom SDF works (mesh, analytic shape, CSG tree, `BvhUnion`, `AnySdf`).
///
/// `ebgeom::make_amrex_shop(f)` (ebgeom_amrex_shop.hpp) gives an `AmrexGeometryShop`: AMReX's own
/// `EB2::GeometryShop` with two of its whole-box steps done by ebgeom (same results, bit for bit):
/// the box classification
/// (`getBoxType`: one evaluation proves a box far from the surface all fluid or all covered) and
/// the level-set fill (`fillFab`: a mesh's nodes evaluated in 8^3 tiles, one BVH search per tile).
/// The cut-edge root finding stays AMReX's, through the per-point call.
///
/// - Sign: AMReX reads value > 0 as body, = 0 as boundary, < 0 as fluid. The adapter returns -S
///   when the fluid is outside the object (`FluidSide::outside`, the default) and +S when it is
///   inside (`EbOptions::fluid = FluidSide::inside`), where S < 0 inside the object.
/// - 2D (AMREX_SPACEDIM == 2): AMReX passes (x, y); the adapter evaluates the 3D SDF at
///   (x, y, `EbOptions::z_slice`).
/// - Copies share the geometry (AMReX stores implicit functions by value in the GeometryShop and
///   copies them): one shared pointer, no copy of a mesh or its BVH.
/// - Thread safety: `const` calls from any number of threads (AMReX's OpenMP tiles) are safe.
/// - GPU builds: the adapter does not derive from `amrex::GPUable` (it holds a host pointer), so
///   AMReX evaluates it on the host. Build the EB once; it is not on the time-step path.
///
/// All logic lives in `ebgeom/adapters/eb_function.hpp`, which is unit-tested without AMReX; this
/// header only maps AMReX's types onto it.

// ebgeom first: its headers must not see macros from the EB code.
#include <memory>
#include <utility>

#include "ebgeom/adapters/eb_function.hpp"

#include <AMReX_Array.H>
#include <AMReX_REAL.H>
#include <AMReX_SPACE.H>

#if !defined(AMREX_SPACEDIM) || (AMREX_SPACEDIM != 2 && AMREX_SPACEDIM != 3)
#error "ebgeom_amrex.hpp: AMReX must be built for 2 or 3 dimensions (AMREX_SPACEDIM)"
#endif

namespace ebgeom {

/// AMReX EB2 implicit function over the ebgeom SDF `S` (see the file comment for the contract).
template <class S> class AmrexImplicitFunction {
 public:
  using sdf_type = S;

  /// Takes the geometry by value (moved into shared storage).
  explicit AmrexImplicitFunction(S sdf, const EbOptions& opt = {}) : f_(std::move(sdf), opt) {}
  /// Shares a geometry built once (e.g. `make_shared_mesh_sdf`). Precondition: not null.
  explicit AmrexImplicitFunction(std::shared_ptr<const S> sdf, const EbOptions& opt = {})
      : f_(std::move(sdf), opt) {}
  explicit AmrexImplicitFunction(EbFunction<S> f) : f_(std::move(f)) {}

  /// The EB2 implicit function: < 0 fluid, > 0 body.
  ::amrex::Real operator()(AMREX_D_DECL(::amrex::Real x, ::amrex::Real y,
                                        ::amrex::Real z)) const noexcept {
    return f_(AMREX_D_DECL(x, y, z));
  }
  /// The same at a point given as an array (AMReX calls both forms).
  ::amrex::Real operator()(const ::amrex::RealArray& p) const noexcept {
    return f_(AMREX_D_DECL(p[0], p[1], p[2]));
  }

  /// The plain C++ adapter (sign, slice, shared geometry).
  const EbFunction<S>& function() const noexcept { return f_; }

 private:
  EbFunction<S> f_;
};

/// `AmrexImplicitFunction` over `sdf`, deducing `S`.
template <class S>
AmrexImplicitFunction<S> make_amrex_implicit_function(S sdf, const EbOptions& opt = {}) {
  return AmrexImplicitFunction<S>(std::move(sdf), opt);
}
/// `AmrexImplicitFunction` sharing `sdf` (not null), deducing `S`.
template <class S>
AmrexImplicitFunction<S> make_amrex_implicit_function(std::shared_ptr<const S> sdf,
                                                      const EbOptions& opt = {}) {
  return AmrexImplicitFunction<S>(std::move(sdf), opt);
}

} // namespace ebgeom
