// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// The grid-job rules that `ebgeom sdf`, `ebgeom-mpi sdf` and the Python package share: the
// options, the grid they describe, and loading the input (mesh or scene) into a `SceneSdf<T>`.
// All three turn the same options into the same grid, so their values agree bit for bit.
// Errors are thrown as `scene::ToolError` with the tools' exit codes.

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "ebgeom/eval/grid_spec.hpp"
#include "ebgeom/jobs/number_options.hpp"
#include "ebgeom/scene/error.hpp"
#include "ebgeom/scene/mesh_input.hpp"
#include "ebgeom/scene/scene.hpp"
#include "ebgeom/scene/system.hpp"

namespace ebgeom::jobs {

/// Options of `ebgeom sdf` (and `ebgeom-mpi sdf`).
struct SdfOptions {
  std::string input, output;
  std::vector<std::size_t> res;
  double dx = 0;
  std::vector<double> box;
  double pad = 0.1;
  double band = 0;
  std::string sign = "auto";
  std::string precision = "float";
  int threads = 0;
  std::string png, slice = "z";
  bool json = false, quiet = false, nodes = false, cubic = false;
};

/// Adds the options of `ebgeom sdf` to `sub`, writing into `*o`, with their validation.
inline void add_sdf_options(CLI::App* sub, const std::shared_ptr<SdfOptions>& o) {
  sub->add_option("INPUT", o->input, "mesh file (STL, PLY, OBJ, OFF, VTK) or scene file (.json)")
      ->required();
  sub->add_option(
         "-o,--output", o->output,
         "output grid: .vti (ParaView), .npy (NumPy, shape (NZ, NY, NX)), .raw "
         "(with a .json sidecar), .npz (the grid with its origin and spacing; with --band the "
         "sparse narrow band of 8^3 tiles) or .vdb (OpenVDB level set, needs --band)")
      ->required();
  auto* res = sub->add_option("--res", o->res,
                              "N cells on every axis, or NX NY NZ (default 64; cell-centred)")
                  ->expected(1, 3);
  auto* dx = sub->add_option("--dx", o->dx, "cubic cells of size H (the box grows to fit)")
                 ->check(number_rule(NumberRule::positive));
  res->excludes(dx);
  sub->add_flag("--cubic", o->cubic,
                "cubic cells: --res N (or 64) cells on the longest axis, the other axes get as "
                "many cells of that size as cover the box (which grows to fit)")
      ->excludes(dx);
  sub->add_option("--box", o->box, "X0 Y0 Z0 X1 Y1 Z1 (default: bounding box + --pad)")
      ->expected(6);
  sub->add_option("--pad", o->pad, "padding per side, as a fraction of the extent")
      ->check(number_rule(NumberRule::percent_range))
      ->capture_default_str();
  sub->add_option("--band", o->band,
                  "narrow band of W times the largest cell spacing: exact inside, ±band outside")
      ->check(number_rule(NumberRule::non_negative));
  sub->add_option("--sign", o->sign,
                  "sign mode for meshes: pseudonormal, winding, fast-winding, unsigned or auto "
                  "(pseudonormal on closed manifold oriented meshes, fast-winding otherwise)")
      ->capture_default_str();
  sub->add_option("--precision", o->precision, "float or double (computation and output)")
      ->check(CLI::IsMember({"float", "double"}))
      ->capture_default_str();
  sub->add_option("--threads", o->threads, "threads (0 = all cores)")
      ->check(number_rule(NumberRule::non_negative, /*integer=*/true));
  auto* png = sub->add_option("--png", o->png, "also write a PNG slice of the grid");
  sub->add_option("--slice", o->slice, "slice of the PNG: x, y or z, optionally =FRACTION")
      ->needs(png)
      ->capture_default_str();
  sub->add_flag("--nodes", o->nodes, "node-centred samples (include the box faces)");
  sub->add_flag("--json", o->json, "print a JSON summary on stdout");
  sub->add_flag("-q,--quiet", o->quiet, "no progress bar and no summary");
  sub->callback([o] {
    if (!o->res.empty() && o->res.size() != 1 && o->res.size() != 3)
      throw CLI::ValidationError("--res", "expects N or NX NY NZ");
    if (o->cubic && o->res.size() == 3)
      throw CLI::ValidationError("--cubic", "takes one --res N (cells on the longest axis)");
    for (std::size_t n : o->res)
      if (n < 1 || n > (std::size_t(1) << 21))
        throw CLI::ValidationError("--res", "each resolution must be in 1..2097152");
  });
}

/// The grid the options describe around `bounds` (the input's bounds). Throws scene::ToolError
/// (usage or input).
template <class T> GridSpec<T> make_spec(const SdfOptions& o, const Aabb<T>& bounds) {
  GridSpec<T> spec;
  spec.centering = o.nodes ? Centering::node : Centering::cell;
  if (!o.box.empty()) {
    for (double v : o.box)
      if (!std::isfinite(v) || std::abs(v) > scene::max_magnitude<T>())
        scene::fail(scene::exit_usage,
                    "--box: every value must be a finite number of magnitude at most " +
                        std::to_string(scene::max_magnitude<T>()) + " in " +
                        scene::precision_name<T>() + " precision");
    spec.box =
        Aabb<T>({T(o.box[0]), T(o.box[1]), T(o.box[2])}, {T(o.box[3]), T(o.box[4]), T(o.box[5])});
    for (int a = 0; a < 3; ++a)
      if (!(spec.box.lo[a] < spec.box.hi[a]))
        scene::fail(scene::exit_usage,
                    std::string("--box: X0 Y0 Z0 must be below X1 Y1 Z1 (axis ") + "xyz"[a] + ")");
  } else {
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(bounds.lo[a]) || !std::isfinite(bounds.hi[a]))
        scene::fail(scene::exit_usage,
                    o.input + ": the input is unbounded (e.g. a plane); give --box");
    if (bounds.is_empty()) scene::fail(scene::exit_input, o.input + ": the input is empty");
    const Vec3<T> e = bounds.extent();
    const T big = max_component(e) > T(0) ? max_component(e) : T(1);
    Vec3<T> pad;
    for (int a = 0; a < 3; ++a) pad[a] = T(o.pad) * (e[a] > big * T(1e-3) ? e[a] : big);
    spec.box = Aabb<T>(bounds.lo - pad, bounds.hi + pad);
  }
  double dx = o.dx;
  if (o.cubic) {
    // the cell size that puts N cells on the longest axis
    const std::size_t n = o.res.empty() ? 64 : o.res[0];
    const std::size_t cells = o.nodes ? n - 1 : n;
    if (cells < 1) scene::fail(scene::exit_usage, "--cubic with --nodes needs --res N >= 2");
    dx = double(max_component(spec.box.extent())) / double(cells);
  }
  if (dx > 0) {
    const Vec3<T> e = spec.box.extent();
    for (int a = 0; a < 3; ++a) {
      // --cubic: the extents are of T precision, so a whole number of cells may come out a few
      // ulps above it; a relative tolerance keeps it whole
      const double x = double(e[a]) / dx;
      const double tol = o.cubic ? 4 * double(std::numeric_limits<T>::epsilon()) * x : 1e-9;
      const double n = std::ceil(x - tol);
      if (n > double(1 << 21))
        scene::fail(scene::exit_usage, "--dx is too small for the box (over 2^21 cells)");
      spec.dims[a] = std::max<std::size_t>(1, std::size_t(n)) + (o.nodes ? 1 : 0);
      const std::size_t cells = o.nodes ? spec.dims[a] - 1 : spec.dims[a];
      spec.box.hi[a] = spec.box.lo[a] + T(double(std::max<std::size_t>(cells, 1)) * dx);
    }
  } else if (o.res.size() == 3) {
    spec.dims = {{o.res[0], o.res[1], o.res[2]}};
  } else {
    const std::size_t n = o.res.empty() ? 64 : o.res[0];
    spec.dims = {{n, n, n}};
  }
  if (auto ok = spec.validate(); !ok) scene::fail(scene::exit_usage, ok.error().what());
  return spec;
}

/// Refuses to write a grid with NaN or infinite samples (counted by `grid_stats`): they come from
/// values the working precision cannot carry (e.g. nested scales), never from a valid SDF.
/// `non_finite` is `GridStats::non_finite`. Throws scene::ToolError (input) naming the count.
inline void require_finite_grid(std::uint64_t non_finite, std::uint64_t samples,
                                const std::string& input) {
  if (non_finite == 0) return;
  scene::fail(scene::exit_input,
              input + ": " + std::to_string(non_finite) + " of " + std::to_string(samples) +
                  " samples are NaN or infinite (values too extreme for the working "
                  "precision); nothing written. Try --precision double or rescale the input");
}

/// An input loaded for sampling, with the times its phases took.
template <class T> struct SdfInput {
  scene::SceneSdf<T> prog; ///< a scene, or one mesh (`prog.mesh()`)
  scene::SceneInfo info;
  bool scene = false;
  double parse_s = 0, build_s = 0;
};

/// Reads `o.input` (a scene by extension, otherwise a mesh with sign mode `sign`) into a
/// `SceneSdf<T>`. Throws scene::ToolError (input, usage) with the reader's message.
template <class T> SdfInput<T> load_sdf_input(const SdfOptions& o, SignMode sign) {
  SdfInput<T> in;
  in.scene = scene::is_scene_path(o.input);
  const double t0 = scene::now_s();
  double t1;
  if (in.scene) {
    const scene::Json doc = scene::read_json_file(o.input);
    t1 = scene::now_s();
    in.prog = scene::compile_scene<T>(doc, o.input, &in.info);
  } else {
    PolygonSoup<T> soup = scene::load_mesh<T>(o.input);
    t1 = scene::now_s();
    in.prog = scene::mesh_scene(soup, o.input, sign);
  }
  in.parse_s = t1 - t0;
  in.build_s = scene::now_s() - t1;
  return in;
}

/// The fields of the `--json` summary that `ebgeom sdf` and `ebgeom-mpi sdf` share: the input,
/// the output, the grid (dims, box, spacing, origin, centering), the precision and the band
/// (length units).
template <class T>
scene::Json grid_job_json(const SdfOptions& o, const SdfInput<T>& in, const GridSpec<T>& spec,
                          double band) {
  scene::Json j;
  j["input"] = o.input;
  j["input_kind"] = in.scene ? "scene" : "mesh";
  j["output"] = o.output;
  j["triangles"] = in.prog.triangle_count();
  j["dims"] = {spec.nx(), spec.ny(), spec.nz()};
  j["box"] = {{"lo", {double(spec.box.lo.x), double(spec.box.lo.y), double(spec.box.lo.z)}},
              {"hi", {double(spec.box.hi.x), double(spec.box.hi.y), double(spec.box.hi.z)}}};
  const Vec3<T> h = spec.spacing(), org = spec.origin();
  j["spacing"] = {double(h.x), double(h.y), double(h.z)};
  j["origin"] = {double(org.x), double(org.y), double(org.z)};
  j["centering"] = to_string(spec.centering);
  j["precision"] = sizeof(T) == 4 ? "float" : "double";
  j["band"] = band;
  return j;
}

} // namespace ebgeom::jobs
