// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `ebgeom::AmrexGeometryShop<S>`: AMReX's EB2 GeometryShop over an ebgeom implicit function, with
/// the whole-box steps evaluated by ebgeom a box at a time (same EB, bit for bit, faster for
/// meshes). A drop-in for `amrex::EB2::makeShop(f)`:
///
/// ```cpp
/// #include "ebgeom_amrex_shop.hpp"
///
/// ebgeom::AmrexImplicitFunction<ebgeom::SignedMeshSdf<double>> f(mesh);
/// auto gshop = ebgeom::make_amrex_shop(f);
/// amrex::EB2::Build(gshop, geom, required_coarsening_level, max_coarsening_level);
/// ```

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

#include "ebgeom_amrex.hpp"

#include <AMReX_BaseFab.H>
#include <AMReX_Box.H>
#include <AMReX_EB2_GeometryShop.H>
#include <AMReX_Geometry.H>
#include <AMReX_GpuControl.H>

namespace ebgeom {

/// AMReX's `EB2::GeometryShop` over an ebgeom implicit function, with the whole-box steps done by
/// ebgeom. `EB2::Build` is a template over the shop type, so it calls these members directly:
/// - `getBoxType`: the nodes of a box are classified by `EbFunction::node_signs` (a box proved by
///   one evaluation at its centre, others split down to 8^3 nodes and evaluated), not node by
///   node; the answer is AMReX's (all fluid, all covered or mixed, NaN counted as fluid).
/// - `fillFab`: the level set at a box's nodes (clamped to the bounding box as AMReX clamps them)
///   by `EbFunction::node_values`: 8^3 tiles through `eval_lattice` for mesh SDFs.
/// Everything else (cut-edge root finding, GPU paths) is the base class's. Values are bit for bit
/// those of the per-point call, so the EB built is the one `EB2::makeShop(f)` builds.
template <class S>
class AmrexGeometryShop : public ::amrex::EB2::GeometryShop<AmrexImplicitFunction<S>> {
  using Base = ::amrex::EB2::GeometryShop<AmrexImplicitFunction<S>>;

 public:
  explicit AmrexGeometryShop(AmrexImplicitFunction<S> f) : Base(std::move(f)) {}

  /// All fluid (`allregular`), all covered (`allcovered`) or `mixedcells`, for the nodes of `bx`.
  [[nodiscard]] int getBoxType(const ::amrex::Box& bx, const ::amrex::Geometry& geom,
                               ::amrex::RunOn) const {
    const ::amrex::Real* problo = geom.ProbLo();
    const ::amrex::Real* dx = geom.CellSize();
    const EbSigns s = this->GetImpFunc().function().node_signs(problo, dx, bx.loVect(), bx.hiVect(),
                                                               AMREX_SPACEDIM);
    if (!s.positive) return Base::allregular;
    if (!s.negative) return Base::allcovered;
    return Base::mixedcells;
  }

  /// The level set at the nodes of `levelset`'s box, indices clamped to `bounding_box`.
  void fillFab(::amrex::BaseFab<::amrex::Real>& levelset, const ::amrex::Geometry& geom,
               ::amrex::RunOn run_on, const ::amrex::Box& bounding_box) const {
#ifdef AMREX_USE_GPU
    if (!levelset.arena()->isHostAccessible()) { // device memory: the base class copies
      Base::fillFab(levelset, geom, run_on, bounding_box);
      return;
    }
#endif
    (void)run_on;
    const ::amrex::Box& bx = levelset.box();
    const ::amrex::Box in = bx & bounding_box; // the distinct nodes; the others are copies
    if (!in.ok()) {
      Base::fillFab(levelset, geom, run_on, bounding_box);
      return;
    }
    std::vector<::amrex::Real> v(std::size_t(in.numPts()));
    this->GetImpFunc().function().node_values(geom.ProbLo(), geom.CellSize(), in.loVect(),
                                              in.hiVect(), AMREX_SPACEDIM, v.data());
    const auto lo = ::amrex::lbound(in);
    const auto hi = ::amrex::ubound(in);
    const long nx = hi.x - lo.x + 1, ny = hi.y - lo.y + 1;
    const auto a = levelset.array();
    ::amrex::LoopOnCpu(bx, [&](int i, int j, int k) noexcept {
      const long ci = std::clamp(i, lo.x, hi.x) - lo.x, cj = std::clamp(j, lo.y, hi.y) - lo.y,
                 ck = std::clamp(k, lo.z, hi.z) - lo.z;
      a(i, j, k) = v[std::size_t(ci + nx * (cj + ny * ck))];
    });
  }
};

/// `AmrexGeometryShop` over `f` (the drop-in for `amrex::EB2::makeShop(f)`).
template <class S> AmrexGeometryShop<S> make_amrex_shop(const AmrexImplicitFunction<S>& f) {
  return AmrexGeometryShop<S>(f);
}

} // namespace ebgeom
