#pragma once
/// \file
/// ebgeom SDFs as Chombo3 `BaseIF` implicit functions (GeometryShop, EBIndexSpace::define).
///
/// ```cpp
/// ebgeom::ChomboImplicitFunction<decltype(sdf)> f(sdf);   // fluid outside the object
/// GeometryShop shop(f, 0, dx * RealVect::Unit);
/// ebis->define(domain, origin, dx, shop, grid_size, max_coarsenings);
/// ```
/// Chombo reads value < 0 as fluid: the adapter returns -S when the fluid is outside the object
/// (default) and +S when it is inside. In 2D builds (CH_SPACEDIM == 2) it evaluates the plane
/// z = `EbOptions::z_slice`. `newImplicitFunction()` clones share the geometry; `value` is
/// thread-safe. All logic lives in `ebgeom/adapters/eb_function.hpp` (unit-tested without Chombo).

#include "BaseIF.H"
#include "RealVect.H"

#include <utility>

#include "ebgeom/adapters/eb_function.hpp"

/// Chombo BaseIF over the ebgeom SDF `S` (in the global namespace, like Chombo's own IFs; Chombo
/// builds with a namespace configure their own via NamespaceHeader.H before including this).
template <class S> class ChomboImplicitFunction : public BaseIF {
 public:
  explicit ChomboImplicitFunction(S sdf, const ebgeom::EbOptions& opt = {})
      : f_(std::move(sdf), opt) {}
  explicit ChomboImplicitFunction(ebgeom::EbFunction<S> f) : f_(std::move(f)) {}

  Real value(const RealVect& a_point) const override {
#if CH_SPACEDIM == 2
    return f_(a_point[0], a_point[1]);
#else
    return f_(a_point[0], a_point[1], a_point[2]);
#endif
  }
  BaseIF* newImplicitFunction() const override { return new ChomboImplicitFunction(*this); }

  const ebgeom::EbFunction<S>& function() const noexcept { return f_; }

 private:
  ebgeom::EbFunction<S> f_;
};

namespace ebgeom {
template <class S> using ChomboImplicitFunction = ::ChomboImplicitFunction<S>;
} // namespace ebgeom
