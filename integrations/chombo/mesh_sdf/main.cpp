// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// ebgeom + Chombo3 EB: reads a surface mesh (STL, PLY, OBJ or VTK; a generated icosphere when no
// file is given), builds its signed distance once, builds the EB index space with GeometryShop +
// EBIndexSpace::define, and writes the implicit function at cell centres (HDF5 builds).
//
//   mpirun -np 4 ./main3d.*.ex mesh_sdf.inputs
//
// Parameters (ParmParse, prefix `mesh_sdf.`): file (none -> icosphere), n_cells (64), grid_size
// (16), padding (0.1), fluid_inside (0), z_slice (0.0, for 2D builds), output ("mesh_sdf.hdf5").
//
// Not compiled in ebgeom's CI (Chombo is not installed there); the adapter it uses is tested
// against stand-ins of the Chombo API. See docs/integrations.md.

// ebgeom
#include "ebgeom/adapters/shared_mesh_sdf.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom_chombo.hpp"

// Chombo
#include "BRMeshRefine.H"
#include "DisjointBoxLayout.H"
#include "EBAMRIO.H"
#include "EBCellFactory.H"
#include "EBISLayout.H"
#include "EBIndexSpace.H"
#include "EBLevelDataOps.H"
#include "GeometryShop.H"
#include "LoadBalance.H"
#include "ParmParse.H"
#include "parstream.H"

#include "UsingNamespace.H"

#include <algorithm>
#include <string>

namespace {

using T = double; // precision of the mesh SDF (float halves its memory)
using Sdf = ebgeom::MeshSdf<T>;

ebgeom::SharedMeshSdf<T> load_geometry(const std::string& file) {
  ebgeom::Result<ebgeom::SharedMeshSdf<T>> sdf =
      file.empty() ? ebgeom::make_shared_mesh_sdf(ebgeom::make_icosphere<T>(4, T(1)).value())
                   : ebgeom::read_shared_mesh_sdf<T>(file);
  if (!sdf) MayDay::Error(("mesh_sdf: " + sdf.error().what()).c_str());
  return *sdf;
}

} // namespace

int main(int argc, char* argv[]) {
#ifdef CH_MPI
  MPI_Init(&argc, &argv);
#endif
  {
    // The first argument, if any, is an input file; later ones override it (key=value).
    const char* in_file = argc > 1 ? argv[1] : nullptr;
    ParmParse pp(argc > 1 ? argc - 2 : 0, argc > 1 ? argv + 2 : argv, nullptr, in_file);
    std::string file, output = "mesh_sdf.hdf5";
    int n_cells = 64, grid_size = 16, fluid_inside = 0;
    Real padding = 0.1, z_slice = 0.0;
    pp.query("mesh_sdf.file", file);
    pp.query("mesh_sdf.n_cells", n_cells);
    pp.query("mesh_sdf.grid_size", grid_size);
    pp.query("mesh_sdf.padding", padding);
    pp.query("mesh_sdf.fluid_inside", fluid_inside);
    pp.query("mesh_sdf.z_slice", z_slice);
    pp.query("mesh_sdf.output", output);

    // 1. The geometry: read and build once, then share (every clone points at it).
    const ebgeom::SharedMeshSdf<T> mesh = load_geometry(file);
    pout() << "mesh_sdf: " << (file.empty() ? std::string("icosphere") : file) << ", "
           << mesh->memory_bytes() / 1024 << " KiB of SDF" << std::endl;

    // 2. The implicit function: negative in the fluid.
    ebgeom::EbOptions opt;
    opt.fluid = fluid_inside ? ebgeom::FluidSide::inside : ebgeom::FluidSide::outside;
    opt.z_slice = z_slice;
    const ebgeom::ChomboImplicitFunction<Sdf> implicit_function(mesh, opt);

    // 3. A cubic domain around the mesh, with `padding` * extent on each side.
    const ebgeom::Aabb<T> b = mesh->bounds();
    const Real ext =
        std::max({Real(b.hi.x - b.lo.x), Real(b.hi.y - b.lo.y), Real(b.hi.z - b.lo.z)});
    const Real half = ext * (0.5 + padding);
    const Real centre[3] = {Real(0.5 * (b.lo.x + b.hi.x)), Real(0.5 * (b.lo.y + b.hi.y)),
                            Real(0.5 * (b.lo.z + b.hi.z))};
    RealVect lo_corner;
    for (int d = 0; d < SpaceDim; ++d) lo_corner[d] = centre[d] - half;
    const Real dx = 2 * half / n_cells;
    const ProblemDomain domain(IntVect::Zero, (n_cells - 1) * IntVect::Unit);

    // 4. The EB index space. GeometryShop clones the function (newImplicitFunction): cheap.
    const GeometryShop workshop(implicit_function, 0, dx * RealVect::Unit);
    EBIndexSpace* ebis = Chombo_EBIS::instance();
    ebis->define(domain, lo_corner, dx, workshop, grid_size, -1);

    // 5. Grids, the EBIS layout, and the implicit function at cell centres.
    Vector<int> procs;
    Vector<Box> boxes;
    domainSplit(domain, boxes, grid_size, grid_size);
    mortonOrdering(boxes);
    LoadBalance(procs, boxes);
    const DisjointBoxLayout dbl(boxes, procs);
    EBISLayout ebisl;
    ebis->fillEBISLayout(ebisl, dbl, domain, 1);

    LevelData<EBCellFAB> data(dbl, 1, IntVect::Zero, EBCellFactory(ebisl));
    for (DataIterator dit(dbl); dit.ok(); ++dit) {
      EBCellFAB& fab = data[dit()];
      fab.setVal(0.0);
      BaseFab<Real>& values = fab.getSingleValuedFAB();
      for (BoxIterator bit(dbl[dit()]); bit.ok(); ++bit) {
        const IntVect iv = bit();
        RealVect x;
        for (int d = 0; d < SpaceDim; ++d) x[d] = lo_corner[d] + (iv[d] + 0.5) * dx;
        values(iv, 0) = implicit_function.value(x);
      }
    }

#ifdef CH_USE_HDF5
    Vector<LevelData<EBCellFAB>*> levels(1, &data);
    writeEBAMRname(&levels, output.c_str());
    pout() << "mesh_sdf: wrote " << output << std::endl;
#else
    pout() << "mesh_sdf: built without HDF5, nothing written" << std::endl;
#endif
    ebis->clear();
  }
#ifdef CH_MPI
  MPI_Finalize();
#endif
  return 0;
}
