// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// `ebgeom sdf INPUT -o OUT`: an SDF grid from a mesh file or a JSON scene, dense (.vti, .npy,
// .raw) or a sparse narrow band (.npz: only the 8^3 tiles the band keeps).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "ebgeom/jobs/npz.hpp"
#include "ebgeom/jobs/sdf_job.hpp"
#include "ebgeom/jobs/vdb_output.hpp"
#include "ebgeom/scene/scene.hpp"
#include "grid_job.hpp"

namespace ebgeom::cli {

namespace {

/// A grid of either kind, for the statistics, the PNG and the summary.
template <class T> struct SampledGrid {
  std::vector<T> dense;
  SparseGrid<T> sparse;
  std::uint64_t file_bytes = 0; // the .npz's size
};

template <class T> int run_sdf_as(const SdfOptions& o) {
  const bool scene = is_scene_path(o.input);
  const SignMode sign = parse_sign_mode(o.sign, exit_usage, "--sign");
  // .npz: the sparse narrow band with --band, otherwise the dense grid with its geometry
  // .vdb: an OpenVDB level set of the band
  const bool vdb = is_vdb_path(o.output);
  const bool sparse = (is_npz_path(o.output) && o.band > 0) || vdb;
  const bool dense_npz = is_npz_path(o.output) && !sparse;
  auto fmt = grid_format_of(o.output);
  if (!fmt && !is_npz_path(o.output) && !vdb)
    fail(exit_usage, o.output +
                         ": unknown output format; expected an extension .vti, .npy, .raw, "
                         ".npz (dense, or the sparse narrow band with --band) or .vdb (OpenVDB "
                         "level set, with --band)");
  if (vdb && !(o.band > 0))
    fail(exit_usage, o.output + ": .vdb is an OpenVDB narrow-band level set and needs --band W "
                                "(W > 0; the background value is W cell widths)");
  if (vdb && !vdb_available())
    fail(exit_usage, write_vdb(o.output, SparseGrid<T>{}).error().what());
  SliceSpec slice;
  if (!o.png.empty()) slice = parse_slice(o.slice);
  require_input_file(o.input);
  {
    std::error_code ec;
    auto same = [&](const std::string& out) {
      return std::filesystem::exists(out) && std::filesystem::equivalent(out, o.input, ec);
    };
    if (same(o.output) || (fmt && *fmt == GridFormat::raw && same(raw_sidecar_path(o.output))) ||
        (!o.png.empty() && same(o.png)))
      fail(exit_usage, o.output + ": writing it would overwrite the input " + o.input);
  }
  require_output_target(o.output);
  if (fmt && *fmt == GridFormat::raw) require_output_target(raw_sidecar_path(o.output));
  if (!o.png.empty()) require_output_target(o.png);

  const double t0 = now_s();
  const SdfInput<T> in = load_sdf_input<T>(o, sign);
  const SceneSdf<T>& prog = in.prog;
  const double t1 = t0 + in.parse_s;
  const double t2 = now_s();

  const GridSpec<T> spec = make_spec(o, prog.bounds());
  const Vec3<T> h = spec.spacing();
  const std::string grid_name = "a " + std::to_string(spec.nx()) + " x " +
                                std::to_string(spec.ny()) + " x " + std::to_string(spec.nz()) +
                                " grid of " + (sizeof(T) == 4 ? "float" : "double");
  const std::uint64_t dense_bytes = std::uint64_t(spec.size()) * sizeof(T);
  GridOptions gopt;
  gopt.exec.threads = o.threads;
  gopt.band = o.band * double(max_component(h));
  const bool progress = !o.quiet && !o.json && stderr_is_terminal();
  SampledGrid<T> grid;
  if (sparse) {
    // Before sampling only the tile table is known, unless the SDF is an implicit scene: then no
    // tile can be skipped and every one is kept. Kept tiles are otherwise checked as they are
    // allocated (sample_sparse_with_progress).
    std::uint64_t tiles = 1;
    for (std::size_t d : spec.dims) tiles *= (d + grid_tile - 1) / grid_tile;
    // A mesh file with a winding sign is sampled through its own SDF, which signs far tiles by
    // proof (`has_split_sign_v`), so it skips them as an exact SDF does.
    if (kind_of(prog) == SdfKind::implicit && !prog.mesh())
      require_memory(
          tiles * (sizeof(std::int32_t) + 12 + grid_tile * grid_tile * grid_tile * sizeof(T)),
          "a band of " + grid_name + " of an implicit SDF (it keeps every tile)",
          "only the sign of this scene is meaningful, so no tile far from the surface can be "
          "skipped; give its meshes \"sign\": \"pseudonormal\", lower the resolution "
          "(--res/--dx) or shrink --box");
    else
      require_memory(tiles * sizeof(std::int32_t), "the tile table of " + grid_name);
    // A mesh file is sampled through the mesh SDF itself (tile and band searches).
    grid.sparse = prog.visit(
        [&](const auto& sdf) { return sample_sparse_with_progress(sdf, spec, gopt, progress); });
  } else {
    require_memory(dense_bytes, grid_name,
                   "lower the resolution (--res/--dx), shrink --box, or write only a narrow band "
                   "as a sparse grid: -o OUT.npz --band W");
    grid.dense = prog.visit(
        [&](const auto& sdf) { return sample_with_progress(sdf, spec, gopt, progress); });
  }
  const double t3 = now_s();
  const GridStats st = sparse ? grid_stats(grid.sparse) : grid_stats(Span<const T>(grid.dense));
  require_finite_grid(st.non_finite, spec.size(), o.input);
  PngInfo img;
  OutputGroup outputs; // every output appears only once all are written
  if (sparse) {
    const SparseGrid<T>& g = grid.sparse;
    auto ok = vdb ? write_vdb(o.output, g) : write_sparse_npz(o.output, g);
    if (!ok) fail(exit_output, ok.error().what());
    grid.file_bytes = *ok;
    if (!o.png.empty())
      img = write_png_slice(
          o.png,
          extract_slice_of(
              spec, [&](std::size_t i, std::size_t j, std::size_t k) { return g.value(i, j, k); },
              slice));
  } else {
    const Span<const T> v(grid.dense);
    if (dense_npz) {
      auto ok = write_dense_npz(o.output, spec, v);
      if (!ok) fail(exit_output, ok.error().what());
      grid.file_bytes = *ok;
    } else {
      write_grid_or_fail(o.output, spec, v, sizeof(T) == 4 ? DType::float32 : DType::float64);
    }
    if (!o.png.empty()) img = write_png_slice(o.png, extract_slice(spec, v, slice));
  }
  if (auto ok = outputs.commit(); !ok) fail(exit_output, ok.error().what());
  const double t4 = now_s();
  const int threads = resolve_threads(gopt.exec);
  const std::size_t tile_count = grid.sparse.tile_code.size();
  const std::size_t kept = grid.sparse.kept_tile_count();

  if (o.json) {
    Json j = grid_job_json(o, in, spec, gopt.band);
    j["timings"] = {
        {"parse_s", t1 - t0}, {"build_s", t2 - t1}, {"eval_s", t3 - t2}, {"write_s", t4 - t3}};
    j["min"] = st.min;
    j["max"] = st.max;
    j["inside_fraction"] = st.inside_fraction;
    j["sign"] = sign_name(sign);
    if (!scene)
      j["sign_used"] = {{"mode", sign_name(prog.mesh()->resolved_mode())},
                        {"reason", prog.mesh()->reason()}};
    else
      j["meshes"] = mesh_signs_json(in.info);
    j["threads"] = threads;
    if (!o.png.empty())
      j["png"] = {{"path", o.png},
                  {"width", img.width},
                  {"height", img.height},
                  {"legend",
                   {{"colour_min", -img.inside_scale},
                    {"colour_max", img.outside_scale},
                    {"scale_bar", img.scale_bar},
                    {"scale_bar_pixels", img.scale_bar_pixels},
                    {"slice",
                     {{"axis", std::string(1, img.axis)},
                      {"position", img.plane},
                      {"index", img.plane_index},
                      {"count", img.plane_count}}}}}};
    if (sparse) {
      const auto& g = grid.sparse;
      j["format"] = vdb ? "openvdb" : "sparse";
      j["tiles"] = {g.tiles[0], g.tiles[1], g.tiles[2]};
      j["kept_tiles"] = kept;
      j["blocks"] = kept; // the name of `kept_tiles` in 0.1, kept for one release
      j["sparse_bytes"] = g.memory_bytes();
      j["dense_bytes"] = dense_bytes;
      j["output_bytes"] = grid.file_bytes;
    } else {
      j["format"] = "dense";
    }
    std::printf("%s\n", j.dump(2).c_str());
  } else if (!o.quiet) {
    std::printf("ebgeom sdf: %s -> %s\n", o.input.c_str(), o.output.c_str());
    std::printf("  input     %s, %zu triangles\n", scene ? "scene" : "mesh", prog.triangle_count());
    std::printf("  grid      %zu x %zu x %zu %s-centred samples, spacing %.4g %.4g %.4g\n",
                spec.nx(), spec.ny(), spec.nz(), to_string(spec.centering), double(h.x),
                double(h.y), double(h.z));
    std::printf("  values    min %.6g  max %.6g  inside fraction %.4f\n", st.min, st.max,
                st.inside_fraction);
    if (sparse)
      std::printf("  sparse    %zu of %zu tiles of 8^3 kept (%.2f%%): %s in memory, %s written "
                  "(dense: %s)\n",
                  kept, tile_count, tile_count ? 100.0 * double(kept) / double(tile_count) : 0.0,
                  human_bytes(grid.sparse.memory_bytes()).c_str(),
                  human_bytes(grid.file_bytes).c_str(), human_bytes(dense_bytes).c_str());
    if (!scene)
      std::printf("  sign      %s (%s)\n", sign_name(prog.mesh()->resolved_mode()),
                  prog.mesh()->reason().c_str());
    else
      print_mesh_signs(in.info);
    std::printf("  time      parse %.3f s  build %.3f s  eval %.3f s  write %.3f s  (%d threads)\n",
                t1 - t0, t2 - t1, t3 - t2, t4 - t3, threads);
  }
  return exit_ok;
}

} // namespace

Subcommand add_sdf(CLI::App& app) {
  auto o = std::make_shared<SdfOptions>();
  CLI::App* sub = app.add_subcommand(
      "sdf", "Sample the signed distance of a mesh file or a JSON scene on a grid (dense, or a "
             "sparse narrow band with .npz)");
  add_sdf_options(sub, o);
  sub->footer(
      "Examples:\n"
      "  ebgeom sdf bunny.obj -o bunny.vti --res 128\n"
      "  ebgeom sdf part.stl -o part.npy --dx 0.01 --precision double --json\n"
      "  ebgeom sdf examples/scenes/csg.json -o csg.raw --res 96 --png csg.png --slice y=0.5\n"
      "  ebgeom sdf spot.obj -o band.npz --res 2048 --band 3   (sparse: only the band's tiles)\n"
      "  ebgeom sdf spot.obj -o spot.vdb --res 512 --cubic --band 3   (OpenVDB level set)\n"
      "  ebgeom sdf part.stl -o part.npz --res 128 --cubic   (dense .npz with origin and spacing)");
  return {sub, [o] {
            return o->precision == "double" ? run_sdf_as<double>(*o) : run_sdf_as<float>(*o);
          }};
}

} // namespace ebgeom::cli
