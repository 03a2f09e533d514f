// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// ebgeom + Chombo3 EB: builds the EB index space (GeometryShop + EBIndexSpace::define) of a
// preset geometry (EBGeometry's `which_geom`), prints the cut-cell count and the fluid volume,
// and writes the implicit function at cell centres (HDF5 builds).
//
//   ./main3d.Linux.64.g++.gfortran.OPT.ex mesh_sdf.inputs mesh_sdf.which_geom=mesh
//   mesh_sdf.file=part.stl
//
// Presets (`mesh_sdf.which_geom`), each with its domain box:
//   sphere         ebgeom's analytic sphere, centre (0.5, 0.5, 0.5), radius `sphere_radius` (0.3),
//                  in the unit cube (at n_cells = 32 and R = 0.3: 1,760 cut cells in 3D)
//   chombo_sphere  the same sphere given to Chombo directly (Chombo's `SphereIF`): the reference
//   mesh           the mesh in `file` (a generated icosphere without one), in a cube around its
//                  bounds with `padding` times its largest extent on each side
//   airfoil, dodecahedron, armadillo
//                  EBGeometry's cases: the mesh in `file` (default airfoil.ply, dodecahedron.ply,
//                  armadillo.ply) in EBGeometry's domain box for it
// `prob_lo` / `prob_hi` (3 numbers each) override any preset's box. Cells are cubes: `n_cells`
// along the box's longest side, as many as fit along the others.
//
// Other parameters (prefix `mesh_sdf.`): grid_size (16), fluid_inside (0: flow around the
// object, EBGeometry's flipSign = true; 1: flow inside it, EBGeometry's examples' flipSign =
// false), z_slice (2D builds: the plane cut through the 3D geometry; default 0, or the sphere's
// centre for the sphere presets), output ("mesh_sdf.hdf5"), box_hook (1: the adapter classifies
// GeometryShop's boxes itself, one evaluation for a box far from the surface; 0: a wrapper
// without that hook, every node through `value`; the same EB), profile (1: build the index space
// once more with the geometry wrapped in ebgeom::TimedSdf and print the points evaluated per cell
// and the time inside ebgeom against Chombo's own work).
//
// Chombo builds an index space even when no cell is fluid (a 2D slice that misses the object
// with the fluid inside it, say); this example then says so instead of writing an all-covered
// field without comment.

// ebgeom (first: its headers must not see macros from Chombo)
#include "ebgeom/adapters/shared_mesh_sdf.hpp"
#include "ebgeom/adapters/timed_sdf.hpp"
#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/sdf/shapes.hpp"
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
#include "SphereIF.H"
#include "parstream.H"

#include "UsingNamespace.H"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace {

using T = double; // precision of the ebgeom geometry (float halves a mesh's memory)

struct Params {
  std::string which_geom = "sphere", file, output = "mesh_sdf.hdf5";
  int n_cells = 64, grid_size = 16, fluid_inside = 0, box_hook = 1, profile = 0;
  Real padding = 0.1, z_slice = 0.0, sphere_radius = 0.3;
  bool z_slice_given = false;
  std::vector<Real> prob_lo, prob_hi;
};

struct Preset {
  const char* name;
  const char* default_file;
  std::array<double, 3> lo, hi;
};
// EBGeometry's domain boxes for its mesh cases.
const Preset ebgeometry_presets[] = {
    {"airfoil", "airfoil.ply", {-100, -100, -75}, {400, 100, 125}},
    {"dodecahedron", "dodecahedron.ply", {-2, -2, -2}, {2, 2, 2}},
    {"armadillo", "armadillo.ply", {-100, -75, -100}, {100, 125, 100}},
};

struct DomainBox {
  std::array<double, 3> lo, hi;
};

DomainBox cube_around(const ebgeom::Aabb<T>& b, double padding) {
  const double ext =
      std::max({double(b.hi.x - b.lo.x), double(b.hi.y - b.lo.y), double(b.hi.z - b.lo.z)});
  const double half = ext * (0.5 + padding);
  const double c[3] = {0.5 * double(b.lo.x + b.hi.x), 0.5 * double(b.lo.y + b.hi.y),
                       0.5 * double(b.lo.z + b.hi.z)};
  return {{c[0] - half, c[1] - half, c[2] - half}, {c[0] + half, c[1] + half, c[2] + half}};
}

// Forwards `value` only, without the adapter's box hook: GeometryShop then evaluates every node
// itself (mesh_sdf.box_hook = 0, to compare).
class PointwiseIF : public BaseIF {
 public:
  explicit PointwiseIF(const BaseIF& f) : m_f(f.newImplicitFunction()) {}
  using BaseIF::value;
  Real value(const RealVect& a_point) const override { return m_f->value(a_point); }
  BaseIF* newImplicitFunction() const override { return new PointwiseIF(*m_f); }

 private:
  std::unique_ptr<BaseIF> m_f;
};

struct Grid {
  ProblemDomain domain;
  RealVect lo_corner;
  Real dx = 1;
};

Grid make_grid(const DomainBox& box, const Params& prm) {
  double longest = 0;
  for (int d = 0; d < SpaceDim; ++d) longest = std::max(longest, box.hi[d] - box.lo[d]);
  Grid g;
  g.dx = Real(longest / prm.n_cells);
  IntVect hi_cell;
  for (int d = 0; d < SpaceDim; ++d) {
    g.lo_corner[d] = Real(box.lo[d]);
    hi_cell[d] = std::max(1, int(std::lround((box.hi[d] - box.lo[d]) / g.dx))) - 1;
  }
  g.domain = ProblemDomain(IntVect::Zero, hi_cell);
  return g;
}

// EBIndexSpace::define for `f` (or its PointwiseIF when box_hook = 0); returns the seconds taken.
double define_ebis(const BaseIF& f, const Grid& g, const Params& prm) {
  const auto t0 = std::chrono::steady_clock::now();
  // GeometryShop clones the function (newImplicitFunction): for ebgeom, one shared pointer.
  if (prm.box_hook) {
    const GeometryShop workshop(f, 0, g.dx * RealVect::Unit);
    Chombo_EBIS::instance()->define(g.domain, g.lo_corner, g.dx, workshop, prm.grid_size, -1);
  } else {
    const PointwiseIF pointwise(f);
    const GeometryShop workshop(pointwise, 0, g.dx * RealVect::Unit);
    Chombo_EBIS::instance()->define(g.domain, g.lo_corner, g.dx, workshop, prm.grid_size, -1);
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

template <class F> struct is_ebgeom_function : std::false_type {};
template <class S> struct is_ebgeom_function<ebgeom::ChomboImplicitFunction<S>> : std::true_type {};

// Defines the index space once more with the geometry wrapped in ebgeom::TimedSdf: points
// evaluated per cell, time inside ebgeom, and the rest (Chombo's own work).
template <class F> void profile_ebis(const F& f, const Grid& g, const Params& prm) {
  if constexpr (is_ebgeom_function<F>::value) {
    using S = typename F::sdf_type;
    auto times = std::make_shared<ebgeom::SdfTimes>();
    const ebgeom::ChomboImplicitFunction<ebgeom::TimedSdf<S>> timed(
        ebgeom::TimedSdf<S>(f.function().shared_sdf(), times), f.function().options());
    const double total = define_ebis(timed, g, prm);
    Chombo_EBIS::instance()->clear();
    const double cells = double(g.domain.domainBox().numPts());
    pout() << "mesh_sdf: profile (box_hook " << prm.box_hook << "): EBIndexSpace::define " << total
           << " s, of which ebgeom " << times->seconds() << " s and Chombo "
           << total - times->seconds() << " s; " << times->points() << " points ("
           << double(times->points()) / cells << " per cell: " << times->calls
           << " per-point calls, " << times->lattice_points << " in " << times->lattice_calls
           << " tiles), "
           << 1e6 * times->seconds() / double(std::max<unsigned long long>(1, times->points()))
           << " us per point" << std::endl;
  } else {
    (void)f, (void)g, (void)prm;
  }
}

// Builds the EB index space for the Chombo implicit function `f`, prints the cut cells and the
// fluid volume, and writes the function at cell centres. The same code for ebgeom's and
// Chombo's own functions.
template <class F> void run(const F& f, const DomainBox& box, const Params& prm) {
  const Grid g = make_grid(box, prm);
  const ProblemDomain& domain = g.domain;
  const RealVect& lo_corner = g.lo_corner;
  const Real dx = g.dx;
  if (prm.profile) profile_ebis(f, g, prm);
  const double seconds = define_ebis(f, g, prm);
  pout() << "mesh_sdf: EB index space built in " << seconds << " s (box_hook "
         << (is_ebgeom_function<F>::value ? prm.box_hook : 0) << ")" << std::endl;
  EBIndexSpace* ebis = Chombo_EBIS::instance();

  Vector<int> procs;
  Vector<Box> boxes;
  domainSplit(domain, boxes, prm.grid_size, prm.grid_size);
  mortonOrdering(boxes);
  LoadBalance(procs, boxes);
  const DisjointBoxLayout dbl(boxes, procs);
  EBISLayout ebisl;
  ebis->fillEBISLayout(ebisl, dbl, domain, 1);

  // Cut cells (irregular volumes) and the fluid volume; the function at cell centres.
  long cut = 0, fluid = 0;
  Real volume = 0;
  LevelData<EBCellFAB> data(dbl, 1, IntVect::Zero, EBCellFactory(ebisl));
  for (DataIterator dit(dbl); dit.ok(); ++dit) {
    const EBISBox& ebis_box = ebisl[dit()];
    EBCellFAB& fab = data[dit()];
    fab.setVal(0.0);
    BaseFab<Real>& values = fab.getSingleValuedFAB();
    for (BoxIterator bit(dbl[dit()]); bit.ok(); ++bit) {
      const IntVect iv = bit();
      RealVect x;
      for (int d = 0; d < SpaceDim; ++d) x[d] = lo_corner[d] + (iv[d] + 0.5) * dx;
      values(iv, 0) = f.value(x);
      if (ebis_box.isCovered(iv)) continue;
      ++fluid;
      if (ebis_box.isRegular(iv)) {
        volume += 1;
        continue;
      }
      const Vector<VolIndex> vofs = ebis_box.getVoFs(iv);
      for (int v = 0; v < int(vofs.size()); ++v) {
        ++cut;
        volume += ebis_box.volFrac(vofs[v]);
      }
    }
  }
#ifdef CH_MPI
  long sums[2] = {cut, fluid}, total[2];
  MPI_Allreduce(sums, total, 2, MPI_LONG, MPI_SUM, Chombo_MPI::comm);
  cut = total[0];
  fluid = total[1];
  double vol = double(volume), vol_total = 0;
  MPI_Allreduce(&vol, &vol_total, 1, MPI_DOUBLE, MPI_SUM, Chombo_MPI::comm);
  volume = Real(vol_total);
#endif
  Real cell = 1;
  for (int d = 0; d < SpaceDim; ++d) cell *= dx;
  pout() << "mesh_sdf: " << cut << " cut cells, fluid volume " << std::setprecision(10)
         << volume * cell << std::setprecision(6) << std::endl;
  if (fluid == 0) {
    pout() << "mesh_sdf: no cell of the domain is fluid: the object "
           << (prm.fluid_inside ? "does not reach into the domain and the fluid is inside it "
                                  "(mesh_sdf.fluid_inside = 1)"
                                : "covers the whole domain")
#if CH_SPACEDIM == 2
           << "; in 2D the geometry is the slice z = " << prm.z_slice
           << " of the 3D object: choose mesh_sdf.z_slice through it"
#endif
           << ". Chombo builds an all-covered index space (AMReX stops on the same input)."
           << std::endl;
  }

#ifdef CH_USE_HDF5
  // Named output with the real cell size (the default writer names it component_0, dx = 1).
  Vector<std::string> names(1, "implicit_function");
  Vector<Real> covered_values(1, 0.0);
  writeEBHDF5(prm.output, dbl, data, names, domain, dx, 1.0, 0.0, false, covered_values);
  pout() << "mesh_sdf: wrote " << prm.output << std::endl;
#else
  pout() << "mesh_sdf: built without HDF5, nothing written" << std::endl;
#endif
  ebis->clear();
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
    Params prm;
    pp.query("mesh_sdf.which_geom", prm.which_geom);
    pp.query("mesh_sdf.file", prm.file);
    pp.query("mesh_sdf.n_cells", prm.n_cells);
    pp.query("mesh_sdf.grid_size", prm.grid_size);
    pp.query("mesh_sdf.padding", prm.padding);
    pp.query("mesh_sdf.fluid_inside", prm.fluid_inside);
    prm.z_slice_given = pp.contains("mesh_sdf.z_slice");
    pp.query("mesh_sdf.z_slice", prm.z_slice);
    pp.query("mesh_sdf.sphere_radius", prm.sphere_radius);
    pp.query("mesh_sdf.output", prm.output);
    pp.query("mesh_sdf.box_hook", prm.box_hook);
    pp.query("mesh_sdf.profile", prm.profile);
    if (pp.contains("mesh_sdf.prob_lo")) pp.queryarr("mesh_sdf.prob_lo", prm.prob_lo, 0, 3);
    if (pp.contains("mesh_sdf.prob_hi")) pp.queryarr("mesh_sdf.prob_hi", prm.prob_hi, 0, 3);
    const bool box_given = prm.prob_lo.size() == 3 && prm.prob_hi.size() == 3;
    auto override_box = [&](const DomainBox& preset) {
      return box_given ? DomainBox{{prm.prob_lo[0], prm.prob_lo[1], prm.prob_lo[2]},
                                   {prm.prob_hi[0], prm.prob_hi[1], prm.prob_hi[2]}}
                       : preset;
    };
    pout() << "mesh_sdf: which_geom = " << prm.which_geom << std::endl;

    ebgeom::EbOptions opt;
    opt.fluid = prm.fluid_inside ? ebgeom::FluidSide::inside : ebgeom::FluidSide::outside;
    if (prm.which_geom == "sphere" || prm.which_geom == "chombo_sphere") {
      if (!prm.z_slice_given) prm.z_slice = 0.5; // 2D: the slice through the centre
      opt.z_slice = prm.z_slice;
      const DomainBox box = override_box({{0, 0, 0}, {1, 1, 1}});
      if (prm.which_geom == "sphere") {
        const ebgeom::ChomboImplicitFunction<ebgeom::Sphere<T>> f(
            ebgeom::Sphere<T>{{0.5, 0.5, 0.5}, T(prm.sphere_radius)}, opt);
        run(f, box, prm);
      } else {
        RealVect centre;
        for (int d = 0; d < SpaceDim; ++d) centre[d] = 0.5;
        // 2D: the circle the plane z = z_slice cuts from the sphere
        const Real dz = SpaceDim == 2 ? prm.z_slice - 0.5 : 0.0;
        const Real r2 = prm.sphere_radius * prm.sphere_radius - dz * dz;
        const SphereIF f(r2 > 0 ? std::sqrt(r2) : 0.0, centre, prm.fluid_inside != 0);
        run(f, box, prm);
      }
    } else {
      const Preset* preset = nullptr;
      for (const Preset& p : ebgeometry_presets)
        if (prm.which_geom == p.name) preset = &p;
      if (!preset && prm.which_geom != "mesh")
        MayDay::Error(
            ("mesh_sdf: unknown which_geom '" + prm.which_geom +
             "' (expected sphere, chombo_sphere, mesh, airfoil, dodecahedron or armadillo)")
                .c_str());
      if (preset && prm.file.empty()) prm.file = preset->default_file;
      // The mesh: read (any format io::read_mesh knows), then built once with the library's
      // default sign (automatic: pseudonormal on a closed mesh, winding number otherwise).
      ebgeom::PolygonSoup<T> soup;
      if (prm.file.empty()) {
        soup = ebgeom::make_icosphere<T>(4, T(1)).value();
      } else {
        auto read = ebgeom::io::read_mesh<T>(prm.file);
        if (!read) MayDay::Error(("mesh_sdf: " + read.error().what()).c_str());
        soup = std::move(*read);
      }
      ebgeom::Result<ebgeom::SharedMeshSdf<T>> made = ebgeom::make_shared_mesh_sdf(soup);
      if (!made) MayDay::Error(("mesh_sdf: " + made.error().what()).c_str());
      const ebgeom::SharedMeshSdf<T> mesh = *made;
      pout() << "mesh_sdf: " << (prm.file.empty() ? std::string("icosphere") : prm.file) << ", "
             << mesh->triangle_count() << " triangles, " << mesh->memory_bytes() / 1024
             << " KiB of SDF, sign " << ebgeom::to_string(mesh->resolved_mode()) << " ("
             << mesh->reason() << ")" << std::endl;
      opt.z_slice = prm.z_slice;
      const ebgeom::ChomboImplicitFunction<ebgeom::SignedMeshSdf<T>> f(mesh, opt);
      run(f,
          override_box(preset ? DomainBox{preset->lo, preset->hi}
                              : cube_around(mesh->bounds(), prm.padding)),
          prm);
    }
  }
#ifdef CH_MPI
  MPI_Finalize();
#endif
  return 0;
}
