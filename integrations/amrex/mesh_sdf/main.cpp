// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// ebgeom + AMReX EB2: builds the embedded boundary of a preset geometry (EBGeometry's
// `which_geom`), prints the cut-cell count and the fluid volume, and writes a plotfile with the
// volume fraction and the EB implicit function at cell centres.
//
//   ./main3d.gnu.*.ex inputs mesh_sdf.which_geom=mesh mesh_sdf.file=part.stl mesh_sdf.n_cell=128
//
// Presets (`mesh_sdf.which_geom`), each with its domain box:
//   sphere        ebgeom's analytic sphere, centre (0.5, 0.5, 0.5), radius `sphere_radius` (0.3),
//                 in the unit cube [0, 1]^3 (at n_cell = 32 and R = 0.3: 1,760 cut cells in 3D)
//   amrex_sphere  the same sphere given to AMReX directly (`amrex::EB2::SphereIF`): the reference
//                 the ebgeom sphere must match cell for cell
//   mesh          the mesh in `file` (a generated icosphere without one), in a cube around its
//                 bounds with `padding` times its largest extent on each side
//   airfoil, dodecahedron, armadillo
//                 EBGeometry's AMReX example cases: the mesh in `file` (default airfoil.ply,
//                 dodecahedron.ply, armadillo.ply) in EBGeometry's domain box for it
// `prob_lo` / `prob_hi` (3 numbers each) override any preset's box.
//
// Other parameters (prefix `mesh_sdf.`): n_cell (64), max_grid_size (32), fluid_inside (0: flow
// around the object, EBGeometry's flipSign = true; 1: flow inside it, EBGeometry's examples'
// flipSign = false), z_slice (the plane a 2D build cuts through the 3D geometry; default 0, or
// the sphere's centre for the sphere presets), max_coarsening_level (0), plotfile ("plt"),
// eb_shop ("ebgeom": ebgeom::make_amrex_shop, whose whole-box steps ebgeom evaluates a box at a
// time; "amrex": amrex::EB2::makeShop, every node through the per-point call; the same EB),
// profile (1: build the EB once more with the geometry wrapped in ebgeom::TimedSdf and print the
// points evaluated per cell and the time inside ebgeom against AMReX's own work).
//
// AMReX stops with "Domain is completely covered" when no cell is fluid (e.g. a 2D slice that
// misses the object while the fluid is inside it) and with "more than 2 cuts not supported" when
// the surface crosses a cell edge more than twice (features thinner than a cell). This example
// checks the first before building and explains both (a finer grid, or eb2.cover_multiple_cuts=1).

// ebgeom (first: its headers must not see macros from AMReX)
#include "ebgeom/adapters/shared_mesh_sdf.hpp"
#include "ebgeom/adapters/timed_sdf.hpp"
#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/sdf/shapes.hpp"
#include "ebgeom_amrex_shop.hpp"

// AMReX
#include <AMReX.H>
#include <AMReX_EB2.H>
#include <AMReX_EB2_IF.H>
#include <AMReX_EBFabFactory.H>
#include <AMReX_MultiFab.H>
#include <AMReX_ParallelDescriptor.H>
#include <AMReX_ParmParse.H>
#include <AMReX_PlotFileUtil.H>
#include <AMReX_Print.H>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <exception>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace {

using T = double; // precision of the ebgeom geometry (AMReX's Real may differ)

struct Params {
  std::string which_geom = "sphere", file, plotfile = "plt", eb_shop = "ebgeom";
  int n_cell = 64, max_grid_size = 32, fluid_inside = 0, max_coarsening_level = 0, profile = 0;
  double padding = 0.1, z_slice = 0.0, sphere_radius = 0.3;
  bool z_slice_given = false;
  std::vector<double> prob_lo, prob_hi;
};

// The domain box of a preset: EBGeometry's boxes for its mesh cases.
struct Preset {
  const char* name;
  const char* default_file;
  std::array<double, 3> lo, hi;
};
constexpr Preset ebgeometry_presets[] = {
    {"airfoil", "airfoil.ply", {-100, -100, -75}, {400, 100, 125}},
    {"dodecahedron", "dodecahedron.ply", {-2, -2, -2}, {2, 2, 2}},
    {"armadillo", "armadillo.ply", {-100, -75, -100}, {100, 125, 100}},
};

amrex::RealBox make_box(const std::array<double, 3>& lo, const std::array<double, 3>& hi) {
  return amrex::RealBox(AMREX_D_DECL(lo[0], lo[1], lo[2]), AMREX_D_DECL(hi[0], hi[1], hi[2]));
}

// A cubic box around `b` (cubic cells), with `padding` times the largest extent on each side.
amrex::RealBox box_around(const ebgeom::Aabb<T>& b, double padding) {
  const double ext =
      std::max({double(b.hi.x - b.lo.x), double(b.hi.y - b.lo.y), double(b.hi.z - b.lo.z)});
  const double half = ext * (0.5 + padding);
  const std::array<double, 3> c = {0.5 * double(b.lo.x + b.hi.x), 0.5 * double(b.lo.y + b.hi.y),
                                   0.5 * double(b.lo.z + b.hi.z)};
  return make_box({c[0] - half, c[1] - half, c[2] - half}, {c[0] + half, c[1] + half, c[2] + half});
}

// Stops with an explanation when no cell centre of the domain is fluid (every value > 0): AMReX
// would abort with "Domain is completely covered".
template <class F>
void check_not_all_covered(const F& f, const amrex::Geometry& geom, int n_cell, const Params& prm) {
  const auto plo = geom.ProbLoArray();
  const auto dx = geom.CellSizeArray();
  long fluid = 0;
  const int nz = AMREX_SPACEDIM == 3 ? n_cell : 1;
  for (int k = 0; k < nz && fluid == 0; ++k)
    for (int j = 0; j < n_cell && fluid == 0; ++j)
      for (int i = 0; i < n_cell && fluid == 0; ++i) {
        amrex::RealArray p{};
        const int idx[3] = {i, j, k};
        for (int d = 0; d < AMREX_SPACEDIM; ++d) p[d] = plo[d] + (idx[d] + 0.5) * dx[d];
        if (f(p) <= 0) ++fluid;
      }
  if (fluid == 0) {
    amrex::Print() << "mesh_sdf: no cell of the domain is fluid: the object "
                   << (prm.fluid_inside ? "does not reach into the domain and the fluid is "
                                          "inside it (mesh_sdf.fluid_inside = 1)"
                                        : "covers the whole domain")
#if AMREX_SPACEDIM == 2
                   << "; in 2D the geometry is the slice z = " << prm.z_slice
                   << " of the 3D object: choose mesh_sdf.z_slice through it"
#endif
                   << ". AMReX would stop with \"Domain is completely covered\".\n";
    amrex::Abort("mesh_sdf: the domain is completely covered (see the message above)");
  }
}

template <class F> struct is_ebgeom_function : std::false_type {};
template <class S> struct is_ebgeom_function<ebgeom::AmrexImplicitFunction<S>> : std::true_type {};

// EB2::Build for `f` through ebgeom's shop (ebgeom's functions, unless eb_shop = amrex) or AMReX's
// own; returns the seconds it took. AMReX's aborts become exceptions here, so a multiple-cut abort
// can be explained (outside OpenMP regions; with OpenMP the abort message stands on its own).
template <class F> double build_eb(const F& f, const amrex::Geometry& geom, const Params& prm) {
  const auto t0 = std::chrono::steady_clock::now();
  amrex::system::throw_exception = true;
  try {
    if constexpr (is_ebgeom_function<F>::value) {
      if (prm.eb_shop == "ebgeom") {
        const auto gshop = ebgeom::make_amrex_shop(f); // copies f: one shared pointer
        amrex::EB2::Build(gshop, geom, 0, prm.max_coarsening_level);
      } else {
        const auto gshop = amrex::EB2::makeShop(f);
        amrex::EB2::Build(gshop, geom, 0, prm.max_coarsening_level);
      }
    } else {
      const auto gshop = amrex::EB2::makeShop(f);
      amrex::EB2::Build(gshop, geom, 0, prm.max_coarsening_level);
    }
  } catch (const std::exception& e) {
    const std::string what = e.what();
    amrex::Print() << "mesh_sdf: AMReX stopped: " << what << "\n";
    if (what.find("more than 2 cuts") != std::string::npos)
      amrex::Print() << "mesh_sdf: the surface crosses a cell edge more than twice: a feature "
                        "thinner than a cell (ears, fingers, thin walls). Use a finer grid "
                        "(mesh_sdf.n_cell), or let AMReX cover such cells with "
                        "eb2.cover_multiple_cuts=1.\n";
    amrex::system::throw_exception = false;
    amrex::Abort("mesh_sdf: EB2::Build failed (see the message above)");
  }
  amrex::system::throw_exception = false;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Builds the EB once more with the geometry wrapped in ebgeom::TimedSdf: points evaluated per
// cell, time inside ebgeom, and the rest (AMReX's own work).
template <class F> void profile_eb(const F& f, const amrex::Geometry& geom, const Params& prm) {
  if constexpr (is_ebgeom_function<F>::value) {
    using S = typename F::sdf_type;
    auto times = std::make_shared<ebgeom::SdfTimes>();
    const ebgeom::AmrexImplicitFunction<ebgeom::TimedSdf<S>> g(
        ebgeom::TimedSdf<S>(f.function().shared_sdf(), times), f.function().options());
    const double total = build_eb(g, geom, prm);
    double cells = 1;
    for (int d = 0; d < AMREX_SPACEDIM; ++d) cells *= geom.Domain().length(d);
    amrex::Print() << "mesh_sdf: profile (" << prm.eb_shop << " shop): EB build " << total
                   << " s, of which ebgeom " << times->seconds() << " s and AMReX "
                   << total - times->seconds() << " s; " << times->points() << " points ("
                   << double(times->points()) / cells << " per cell: " << times->calls
                   << " per-point calls, " << times->lattice_points << " in "
                   << times->lattice_calls << " tiles), "
                   << 1e6 * times->seconds() / double(std::max<std::uint64_t>(1, times->points()))
                   << " us per point\n";
  } else {
    (void)f, (void)geom, (void)prm;
  }
}

// Builds the EB for implicit function `f`, prints the cut cells and the fluid volume, and
// writes the plotfile. The same code for ebgeom's and AMReX's own functions.
template <class F> void run(const F& f, const amrex::Geometry& geom, const Params& prm) {
  check_not_all_covered(f, geom, prm.n_cell, prm);
  if (prm.profile) profile_eb(f, geom, prm);
  const double seconds = build_eb(f, geom, prm);
  amrex::Print() << "mesh_sdf: EB built in " << seconds << " s ("
                 << (is_ebgeom_function<F>::value ? prm.eb_shop : std::string("amrex"))
                 << " shop)\n";

  amrex::BoxArray ba(geom.Domain());
  ba.maxSize(prm.max_grid_size);
  const amrex::DistributionMapping dm(ba);
  std::unique_ptr<amrex::EBFArrayBoxFactory> factory =
      amrex::makeEBFabFactory(geom, ba, dm, {2, 2, 2}, amrex::EBSupport::full);

  // Cut cells (0 < vfrac < 1) and fluid volume. Host loop: the volume fraction is read on the
  // host (CPU builds; GPU builds would need a device reduction).
  const amrex::MultiFab& vfrac = factory->getVolFrac();
  long cut = 0;
  double volume = 0;
  for (amrex::MFIter mfi(vfrac); mfi.isValid(); ++mfi) {
    const amrex::Box& bx = mfi.validbox();
    const amrex::Array4<const amrex::Real> v = vfrac.const_array(mfi);
    amrex::LoopOnCpu(bx, [&](int i, int j, int k) {
      const amrex::Real x = v(i, j, k);
      if (x > 0 && x < 1) ++cut;
      volume += double(x);
    });
  }
  amrex::ParallelDescriptor::ReduceLongSum(cut);
  amrex::ParallelDescriptor::ReduceRealSum(volume);
  double cell = 1;
  for (int d = 0; d < AMREX_SPACEDIM; ++d) cell *= geom.CellSize(d);
  amrex::Print() << "mesh_sdf: " << cut << " cut cells, fluid volume " << volume * cell << "\n";

  // The implicit function at cell centres. Only that component: EB_WriteSingleLevelPlotfile
  // adds the volume fraction ("vfrac") itself.
  amrex::MultiFab mf(ba, dm, 1, 0, amrex::MFInfo().SetArena(amrex::The_Pinned_Arena()), *factory);
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
      a(i, j, k, 0) = f(p); // concurrent calls on one object: thread-safe
    });
  }
  amrex::EB_WriteSingleLevelPlotfile(prm.plotfile, mf, {"implicit_function"}, geom, 0.0, 0);
  amrex::Print() << "mesh_sdf: wrote " << prm.plotfile << "\n";
}

amrex::Geometry make_geometry(const amrex::RealBox& rb, int n_cell) {
  const amrex::Box domain(amrex::IntVect(AMREX_D_DECL(0, 0, 0)),
                          amrex::IntVect(AMREX_D_DECL(n_cell - 1, n_cell - 1, n_cell - 1)));
  const amrex::Array<int, AMREX_SPACEDIM> is_periodic{AMREX_D_DECL(0, 0, 0)};
  return amrex::Geometry(domain, rb, amrex::CoordSys::cartesian, is_periodic);
}

} // namespace

int main(int argc, char* argv[]) {
  amrex::Initialize(argc, argv);
  {
    Params prm;
    {
      amrex::ParmParse pp("mesh_sdf");
      pp.query("which_geom", prm.which_geom);
      pp.query("file", prm.file);
      pp.query("n_cell", prm.n_cell);
      pp.query("max_grid_size", prm.max_grid_size);
      pp.query("padding", prm.padding);
      pp.query("fluid_inside", prm.fluid_inside);
      prm.z_slice_given = pp.query("z_slice", prm.z_slice);
      pp.query("sphere_radius", prm.sphere_radius);
      pp.query("max_coarsening_level", prm.max_coarsening_level);
      pp.query("plotfile", prm.plotfile);
      pp.query("eb_shop", prm.eb_shop);
      pp.query("profile", prm.profile);
      pp.queryarr("prob_lo", prm.prob_lo);
      pp.queryarr("prob_hi", prm.prob_hi);
    }
    const bool box_given = prm.prob_lo.size() == 3 && prm.prob_hi.size() == 3;
    auto override_box = [&](const amrex::RealBox& preset) {
      return box_given ? make_box({prm.prob_lo[0], prm.prob_lo[1], prm.prob_lo[2]},
                                  {prm.prob_hi[0], prm.prob_hi[1], prm.prob_hi[2]})
                       : preset;
    };
    amrex::Print() << "mesh_sdf: which_geom = " << prm.which_geom << "\n";

    if (prm.which_geom == "sphere" || prm.which_geom == "amrex_sphere") {
      if (!prm.z_slice_given) prm.z_slice = 0.5; // 2D: the slice through the centre
      const amrex::Geometry geom =
          make_geometry(override_box(make_box({0, 0, 0}, {1, 1, 1})), prm.n_cell);
      if (prm.which_geom == "sphere") {
        ebgeom::EbOptions opt;
        opt.fluid = prm.fluid_inside ? ebgeom::FluidSide::inside : ebgeom::FluidSide::outside;
        opt.z_slice = prm.z_slice;
        const ebgeom::AmrexImplicitFunction<ebgeom::Sphere<T>> f(
            ebgeom::Sphere<T>{{0.5, 0.5, 0.5}, T(prm.sphere_radius)}, opt);
        run(f, geom, prm);
      } else {
        const amrex::RealArray center{AMREX_D_DECL(0.5, 0.5, 0.5)};
        // 2D: the circle the plane z = z_slice cuts from the sphere
        const double dz = AMREX_SPACEDIM == 2 ? prm.z_slice - 0.5 : 0.0;
        const double r2 = prm.sphere_radius * prm.sphere_radius - dz * dz;
        const amrex::EB2::SphereIF f(r2 > 0 ? std::sqrt(r2) : 0.0, center, prm.fluid_inside != 0);
        run(f, geom, prm);
      }
    } else {
      // Meshes: `mesh` (any file; an icosphere without one) or one of EBGeometry's cases.
      const Preset* preset = nullptr;
      for (const Preset& p : ebgeometry_presets)
        if (prm.which_geom == p.name) preset = &p;
      if (!preset && prm.which_geom != "mesh")
        amrex::Abort("mesh_sdf: unknown which_geom '" + prm.which_geom +
                     "' (expected sphere, amrex_sphere, mesh, airfoil, dodecahedron or armadillo)");
      if (preset && prm.file.empty()) prm.file = preset->default_file;
      // The mesh: read (any format io::read_mesh knows), then built once with the library's
      // default sign (automatic: pseudonormal on a closed mesh, winding number otherwise).
      ebgeom::PolygonSoup<T> soup;
      if (prm.file.empty()) {
        soup = ebgeom::make_icosphere<T>(4, T(1)).value();
      } else {
        auto read = ebgeom::io::read_mesh<T>(prm.file);
        if (!read) amrex::Abort("mesh_sdf: " + read.error().what());
        soup = std::move(*read);
      }
      ebgeom::Result<ebgeom::SharedMeshSdf<T>> made = ebgeom::make_shared_mesh_sdf(soup);
      if (!made) amrex::Abort("mesh_sdf: " + made.error().what());
      const ebgeom::SharedMeshSdf<T> mesh = *made;
      amrex::Print() << "mesh_sdf: " << (prm.file.empty() ? std::string("icosphere") : prm.file)
                     << ", " << mesh->triangle_count() << " triangles, "
                     << mesh->memory_bytes() / 1024 << " KiB of SDF, sign "
                     << ebgeom::to_string(mesh->resolved_mode()) << " (" << mesh->reason() << ")\n";
      const amrex::RealBox rb = override_box(preset ? make_box(preset->lo, preset->hi)
                                                    : box_around(mesh->bounds(), prm.padding));
      const amrex::Geometry geom = make_geometry(rb, prm.n_cell);
      ebgeom::EbOptions opt;
      opt.fluid = prm.fluid_inside ? ebgeom::FluidSide::inside : ebgeom::FluidSide::outside;
      opt.z_slice = prm.z_slice;
      const ebgeom::AmrexImplicitFunction<ebgeom::SignedMeshSdf<T>> f(mesh, opt);
      run(f, geom, prm);
    }
  }
  amrex::Finalize();
  return 0;
}
