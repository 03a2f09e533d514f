// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// ebgeom SDFs as Chombo3 `BaseIF` implicit functions (GeometryShop, EBIndexSpace::define).
///
/// ```cpp
/// #include "GeometryShop.H"
/// #include "EBIndexSpace.H"
/// #include "ebgeom_chombo.hpp"
///
/// auto mesh = ebgeom::read_shared_mesh_sdf<double>("part.stl").value();  // built once
/// ebgeom::ChomboImplicitFunction<ebgeom::MeshSdf<double>> f(mesh);        // fluid outside
/// GeometryShop shop(f, 0, dx * RealVect::Unit);               // clones f: cheap
/// Chombo_EBIS::instance()->define(domain, origin, dx, shop, grid_size, max_coarsenings);
/// ```
/// Any ebgeom SDF works (mesh, analytic shape, CSG tree, `BvhUnion`, `AnySdf`).
///
/// - Sign: Chombo reads value < 0 as fluid, > 0 as covered. The adapter returns -S when the fluid
///   is outside the object (`FluidSide::outside`, the default) and +S when it is inside
///   (`EbOptions::fluid = FluidSide::inside`), where S < 0 inside the object.
/// - 2D (CH_SPACEDIM == 2): Chombo passes (x, y); the adapter evaluates the 3D SDF at
///   (x, y, `EbOptions::z_slice`).
/// - `newImplicitFunction()` clones share the geometry (one shared pointer; GeometryShop and the
///   CSG IFs of Chombo clone their operands, once per use).
/// - Thread safety: `value` is `const` and safe to call concurrently, on one object or on clones.
/// - Namespaces: the class lives in `ebgeom`; Chombo built with CH_NAMESPACE is handled by
///   Chombo's own `UsingNamespace.H`, included below as its application codes do.
///
/// All logic lives in `ebgeom/adapters/eb_function.hpp` (unit-tested without Chombo).

// ebgeom first: its headers must not see Chombo's macros (Chombo may define `Real` as one).
#include <memory>
#include <utility>

#include "ebgeom/adapters/eb_function.hpp"

#include "BaseIF.H"
#include "RealVect.H"
#include "UsingNamespace.H"

#if !defined(CH_SPACEDIM) || (CH_SPACEDIM != 2 && CH_SPACEDIM != 3)
#error "ebgeom_chombo.hpp: Chombo must be built for 2 or 3 dimensions (CH_SPACEDIM)"
#endif

namespace ebgeom {

/// Chombo `BaseIF` over the ebgeom SDF `S` (see the file comment for the contract).
template <class S> class ChomboImplicitFunction : public BaseIF {
 public:
  using sdf_type = S;
  using BaseIF::value; // keep BaseIF's other `value` overloads visible

  /// Takes the geometry by value (moved into shared storage).
  explicit ChomboImplicitFunction(S sdf, const EbOptions& opt = {}) : f_(std::move(sdf), opt) {}
  /// Shares a geometry built once (e.g. `read_shared_mesh_sdf`). Precondition: not null.
  explicit ChomboImplicitFunction(std::shared_ptr<const S> sdf, const EbOptions& opt = {})
      : f_(std::move(sdf), opt) {}
  explicit ChomboImplicitFunction(EbFunction<S> f) : f_(std::move(f)) {}
  ChomboImplicitFunction(const ChomboImplicitFunction&) = default;
  ChomboImplicitFunction& operator=(const ChomboImplicitFunction&) = default;
  ~ChomboImplicitFunction() override = default;

  /// The level-set value: < 0 fluid, > 0 covered.
  Real value(const RealVect& a_point) const override {
#if CH_SPACEDIM == 2
    return f_(Real(a_point[0]), Real(a_point[1]));
#else
    return f_(Real(a_point[0]), Real(a_point[1]), Real(a_point[2]));
#endif
  }
  /// A clone sharing the geometry (the caller owns it). Never copies `S`.
  BaseIF* newImplicitFunction() const override { return new ChomboImplicitFunction(*this); }

  /// The plain C++ adapter (sign, slice, shared geometry).
  const EbFunction<S>& function() const noexcept { return f_; }

 private:
  EbFunction<S> f_;
};

} // namespace ebgeom
