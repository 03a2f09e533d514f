// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// ebgeom + AMReX EB2: reads a surface mesh (STL, PLY, OBJ or VTK; a generated icosphere when no
// file is given), builds its signed distance once, builds the embedded boundary with EB2 and
// writes a plotfile with the volume fraction and the EB implicit function at cell centres.
//
//   ./main3d.gnu.*.ex inputs mesh_sdf.file=part.stl mesh_sdf.n_cell=128
//
// Parameters (ParmParse, prefix `mesh_sdf.`): file (default: none -> icosphere), n_cell (64),
// max_grid_size (32), padding (0.1: domain margin, as a fraction of the mesh's largest extent),
// fluid_inside (0: flow around the object; 1: flow inside it), z_slice (0.0: the plane that a 2D
// build cuts through the 3D mesh), max_coarsening_level (0), plotfile ("plt").
//
// Not compiled in ebgeom's CI (AMReX is not installed there); the adapter it uses is tested
// against stand-ins of the AMReX API. See docs/integrations.md.

// ebgeom
#include "ebgeom/adapters/shared_mesh_sdf.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom_amrex.hpp"

// AMReX
#include <AMReX.H>
#include <AMReX_EB2.H>
#include <AMReX_EB2_IF.H>
#include <AMReX_EBFabFactory.H>
#include <AMReX_MultiFab.H>
#include <AMReX_ParmParse.H>
#include <AMReX_PlotFileUtil.H>
#include <AMReX_Print.H>

#include <algorithm>
#include <memory>
#include <string>

namespace {

using T = double; // precision of the mesh SDF (float halves its memory; AMReX's Real may differ)
using Sdf = ebgeom::MeshSdf<T>;

// The mesh, built once and shared by every copy of the implicit function AMReX makes.
ebgeom::SharedMeshSdf<T> load_geometry(const std::string& file) {
  ebgeom::Result<ebgeom::SharedMeshSdf<T>> sdf =
      file.empty() ? ebgeom::make_shared_mesh_sdf(ebgeom::make_icosphere<T>(4, T(1)).value())
                   : ebgeom::read_shared_mesh_sdf<T>(file);
  if (!sdf) amrex::Abort("mesh_sdf: " + sdf.error().what());
  return *sdf;
}

// A cubic domain around the mesh's bounds (cubic cells), with `padding` * extent on each side.
amrex::RealBox domain_around(const ebgeom::Aabb<T>& b, double padding) {
  const double ext =
      std::max({double(b.hi.x - b.lo.x), double(b.hi.y - b.lo.y), double(b.hi.z - b.lo.z)});
  const double half = ext * (0.5 + padding);
  const double c[3] = {0.5 * double(b.lo.x + b.hi.x), 0.5 * double(b.lo.y + b.hi.y),
                       0.5 * double(b.lo.z + b.hi.z)};
  return amrex::RealBox(AMREX_D_DECL(c[0] - half, c[1] - half, c[2] - half),
                        AMREX_D_DECL(c[0] + half, c[1] + half, c[2] + half));
}

} // namespace

int main(int argc, char* argv[]) {
  amrex::Initialize(argc, argv);
  {
    std::string file, plotfile = "plt";
    int n_cell = 64, max_grid_size = 32, fluid_inside = 0, max_coarsening_level = 0;
    double padding = 0.1, z_slice = 0.0;
    {
      amrex::ParmParse pp("mesh_sdf");
      pp.query("file", file);
      pp.query("n_cell", n_cell);
      pp.query("max_grid_size", max_grid_size);
      pp.query("padding", padding);
      pp.query("fluid_inside", fluid_inside);
      pp.query("z_slice", z_slice);
      pp.query("max_coarsening_level", max_coarsening_level);
      pp.query("plotfile", plotfile);
    }

    // 1. The geometry: read and build once (O(n log n)), then share.
    const ebgeom::SharedMeshSdf<T> mesh = load_geometry(file);
    amrex::Print() << "mesh_sdf: " << (file.empty() ? std::string("icosphere") : file) << ", "
                   << mesh->memory_bytes() / 1024 << " KiB of SDF\n";

    // 2. The EB implicit function: negative in the fluid. Copies share `mesh`.
    ebgeom::EbOptions opt;
    opt.fluid = fluid_inside ? ebgeom::FluidSide::inside : ebgeom::FluidSide::outside;
    opt.z_slice = z_slice;
    const ebgeom::AmrexImplicitFunction<Sdf> implicit_function(mesh, opt);

    // 3. The domain and the AMReX geometry.
    const amrex::RealBox rb = domain_around(mesh->bounds(), padding);
    const amrex::Box domain(amrex::IntVect(AMREX_D_DECL(0, 0, 0)),
                            amrex::IntVect(AMREX_D_DECL(n_cell - 1, n_cell - 1, n_cell - 1)));
    const amrex::Array<int, AMREX_SPACEDIM> is_periodic{AMREX_D_DECL(0, 0, 0)};
    const amrex::Geometry geom(domain, rb, amrex::CoordSys::cartesian, is_periodic);

    // 4. The embedded boundary (EB2 evaluates the function, from OpenMP threads if enabled).
    auto gshop = amrex::EB2::makeShop(implicit_function);
    amrex::EB2::Build(gshop, geom, 0, max_coarsening_level);

    // 5. Data on the EB grid: volume fraction and the implicit function at cell centres.
    amrex::BoxArray ba(geom.Domain());
    ba.maxSize(max_grid_size);
    const amrex::DistributionMapping dm(ba);
    std::unique_ptr<amrex::EBFArrayBoxFactory> factory =
        amrex::makeEBFabFactory(geom, ba, dm, {2, 2, 2}, amrex::EBSupport::full);
    // Host-accessible memory: the implicit function runs on the host (also in GPU builds).
    amrex::MultiFab mf(ba, dm, 2, 0, amrex::MFInfo().SetArena(amrex::The_Pinned_Arena()), *factory);
    amrex::MultiFab::Copy(mf, factory->getVolFrac(), 0, 0, 1, 0);
    amrex::Gpu::streamSynchronize();

    const auto plo = geom.ProbLoArray();
    const auto dx = geom.CellSizeArray();
#ifdef AMREX_USE_OMP
#pragma omp parallel
#endif
    for (amrex::MFIter mfi(mf, amrex::TilingIfNotGPU()); mfi.isValid(); ++mfi) {
      const amrex::Box& bx = mfi.tilebox();
      const amrex::Array4<amrex::Real> a = mf.array(mfi);
      amrex::LoopOnCpu(bx, [&](int i, int j, int k) {
        const amrex::IntVect iv(AMREX_D_DECL(i, j, k));
        amrex::RealArray p{};
        for (int d = 0; d < AMREX_SPACEDIM; ++d) p[d] = plo[d] + (iv[d] + 0.5) * dx[d];
        a(i, j, k, 1) = implicit_function(p); // concurrent calls on one object: thread-safe
      });
    }

    amrex::EB_WriteSingleLevelPlotfile(plotfile, mf, {"vfrac", "implicit_function"}, geom, 0.0, 0);
    amrex::Print() << "mesh_sdf: wrote " << plotfile << "\n";
  }
  amrex::Finalize();
  return 0;
}
