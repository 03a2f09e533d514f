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
/// auto soup = ebgeom::io::read_mesh<double>("part.stl").value();            // read the file
/// auto mesh = ebgeom::make_shared_mesh_sdf(soup).value();                   // built once
/// ebgeom::ChomboImplicitFunction<ebgeom::SignedMeshSdf<double>> f(mesh);    // fluid outside
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
/// - Whole cells and boxes: GeometryShop asks the function first (`fastIntersection`) whether it
///   classifies a box itself. For SDFs whose value bounds the distance (exact shapes, meshes with
///   the pseudonormal sign) the adapter answers yes and `InsideOutside` proves a box far from the
///   surface regular or covered with one evaluation at its centre, instead of one per node; other
///   boxes get their nodes evaluated (8^3 tiles through `eval_lattice` for a mesh) and classified
///   as GeometryShop classifies them. The answer is GeometryShop's own. It assumes cubic cells
///   (a GeometryShop built with an isotropic `vectDx`, as `EBIndexSpace::define`'s single dx and
///   `BaseIF::corners` do). Chombo's CSG IFs ask the other overload and are not affected.
/// - Namespaces: the class lives in `ebgeom`; Chombo built with CH_NAMESPACE is handled by
///   Chombo's own `UsingNamespace.H`, included below as its application codes do.
///
/// All logic lives in `ebgeom/adapters/eb_function.hpp` (unit-tested without Chombo).

// ebgeom first: its headers must not see Chombo's macros (Chombo may define `Real` as one).
#include <memory>
#include <utility>

#include "ebgeom/adapters/eb_function.hpp"

#include "BaseIF.H" // and, through it, Box, ProblemDomain and GeometryService (as Chombo's IFs)
#include "RealVect.H"
#include "UsingNamespace.H"

#include <cmath>
#include <vector>

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
  /// Shares a geometry built once (e.g. `make_shared_mesh_sdf`). Precondition: not null.
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
  /// Yes when one value can prove a box's sign (`EbFunction::proves_boxes`): GeometryShop then
  /// calls `InsideOutside` below instead of evaluating every node itself.
  bool fastIntersection(const ::Box&, const ::ProblemDomain&, const RealVect&,
                        const Real&) const override {
    return f_.proves_boxes();
  }
  using BaseIF::fastIntersection;

  /// Regular (every node fluid), Covered (every node covered) or Irregular, for the nodes of the
  /// cells of `a_region` (cubic cells of size `a_dx` from `a_origin`): GeometryShop's answer for
  /// the same nodes, with one evaluation for a box far from the surface.
  ::GeometryService::InOut InsideOutside(const ::Box& a_region, const ::ProblemDomain&,
                                         const RealVect& a_origin,
                                         const Real& a_dx) const override {
    ::Box nodes(a_region); // qualified: ebgeom::Box is the box shape
    nodes.surroundingNodes();
    Real origin[CH_SPACEDIM], dx[CH_SPACEDIM], lo[CH_SPACEDIM], hi[CH_SPACEDIM];
    for (int d = 0; d < CH_SPACEDIM; ++d) {
      origin[d] = a_origin[d];
      dx[d] = a_dx;
      lo[d] = Real(nodes.smallEnd()[d]) * a_dx + a_origin[d];
      hi[d] = Real(nodes.bigEnd()[d]) * a_dx + a_origin[d];
    }
    const int sign = f_.box_sign(lo, hi, CH_SPACEDIM);
    if (sign != 0) return sign < 0 ? ::GeometryService::Regular : ::GeometryService::Covered;
    std::vector<Real> v(std::size_t(nodes.numPts()));
    f_.node_values(origin, dx, nodes.smallEnd().dataPtr(), nodes.bigEnd().dataPtr(), CH_SPACEDIM,
                   v.data());
    // GeometryShop's rule: the first node's sign (of a zero too) against every node's.
    const Real first = v[0], first_sign = std::copysign(Real(1), first);
    for (const Real x : v) {
      if ((x == 0 || first == 0) && std::copysign(Real(1), x) * first_sign < 0)
        return ::GeometryService::Irregular;
      if (x * first < 0) return ::GeometryService::Irregular;
    }
    return first_sign < 0 ? ::GeometryService::Regular : ::GeometryService::Covered;
  }
  using BaseIF::InsideOutside;

  /// A clone sharing the geometry (the caller owns it). Never copies `S`.
  BaseIF* newImplicitFunction() const override { return new ChomboImplicitFunction(*this); }

  /// The plain C++ adapter (sign, slice, shared geometry).
  const EbFunction<S>& function() const noexcept { return f_; }

 private:
  EbFunction<S> f_;
};

} // namespace ebgeom
