// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// ebgeom-mpi: `ebgeom sdf` distributed over MPI ranks (docs/distributed.md).
//
//   mpirun -n P ebgeom-mpi sdf INPUT -o OUT.pvti|.npy|.raw [the options of ebgeom sdf]
//
// Every rank reads the input and builds the same SDF; the grid is cut into bricks, the bricks into
// one box per rank (weighted by a coarse estimate of the narrow band's work), and each rank samples
// its box with `sample_grid_box`, which gives the serial values bit for bit. Errors are agreed on
// collectively: every rank ends with the same exit code and rank 0 prints one message.
#include <mpi.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "ebgeom/core/config.hpp"
#include "ebgeom/eval/decompose.hpp"
#include "ebgeom/eval/grid.hpp"
#include "ebgeom/jobs/sdf_job.hpp"
#include "grid_output.hpp"
#include "mpi_support.hpp"

namespace ebgeom::mpi {

using jobs::SdfOptions;
using scene::fail;
using Json = nlohmann::json;

struct World {
  MPI_Comm comm = MPI_COMM_WORLD;
  int rank = 0, size = 1, local_size = 1;
};

OutputKind output_kind(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".pvti") return OutputKind::pvti;
  if (ext == ".npy") return OutputKind::npy;
  if (ext == ".raw") return OutputKind::raw;
  if (ext == ".vti")
    fail(scene::exit_usage, path + ": ebgeom-mpi writes a parallel VTK file; name it .pvti (one "
                                   ".vti piece per rank is written beside it)");
  if (ext == ".npz")
    fail(scene::exit_usage, path + ": the sparse .npz output is written by the serial ebgeom sdf "
                                   "only; ebgeom-mpi writes .pvti, .npy or .raw");
  fail(scene::exit_usage, path + ": unknown output format (expected .pvti, .npy or .raw)");
}

/// Fails (output) unless a file can be created beside `path`, before hours of sampling.
void require_writable(const std::string& path) {
  const std::string probe = path + ".ebgeom-mpi-probe";
  {
    std::ofstream f(probe, std::ios::binary | std::ios::trunc);
    if (!f)
      fail(scene::exit_output,
           path + ": cannot open for writing (" + std::string(std::strerror(errno)) + ")");
  }
  std::remove(probe.c_str());
}

template <class T> int run(const SdfOptions& o, const World& w) {
  const bool root = w.rank == 0;
  const double t0 = scene::now_s();
  OutputKind kind = OutputKind::npy;
  jobs::SdfInput<T> in;
  GridSpec<T> spec;
  // 1. Options, input (read by every rank), grid, and a writable output.
  phase(w.comm, [&] {
    if (!o.png.empty())
      fail(scene::exit_usage,
           "--png is not supported by ebgeom-mpi (no rank holds the whole grid); "
           "slice the output, or run ebgeom sdf --png on a coarser grid");
    kind = output_kind(o.output);
    const SignMode sign = scene::parse_sign_mode(o.sign, scene::exit_usage, "--sign");
    scene::require_input_file(o.input);
    std::error_code ec;
    if (std::filesystem::exists(o.output) && std::filesystem::equivalent(o.output, o.input, ec))
      fail(scene::exit_usage, o.output + ": writing it would overwrite the input " + o.input);
    in = jobs::load_sdf_input<T>(o, sign);
    spec = jobs::make_spec(o, in.prog.bounds());
    if (root) require_writable(o.output);
  });
  const double t1 = scene::now_s();

  // 2. Bricks and their estimated work (narrow band: one SDF value per brick centre, the bricks
  //    shared out evenly between ranks), then one box of bricks per rank.
  const Vec3<T> h = spec.spacing();
  GridOptions gopt;
  gopt.exec.threads = o.threads;
  if (o.threads == 0 && !std::getenv("OMP_NUM_THREADS"))
    gopt.exec.threads =
        std::max(1, int(std::thread::hardware_concurrency()) / std::max(1, w.local_size));
  gopt.band = o.band * double(max_component(h));
  BrickLayout layout;
  std::vector<double> work;
  Decomposition dec;
  phase(w.comm, [&] {
    layout = make_brick_layout(spec);
    const std::size_t n = layout.size();
    work.assign(n, 0.0);
    BrickWorkOptions bw;
    bw.band = gopt.band;
    bw.exec = gopt.exec;
    if (gopt.band > 0) {
      std::vector<int> counts(std::size_t(w.size)), displs(std::size_t(w.size));
      for (int r = 0; r < w.size; ++r) {
        const std::size_t b = n * std::size_t(r) / std::size_t(w.size);
        const std::size_t e = n * std::size_t(r + 1) / std::size_t(w.size);
        counts[std::size_t(r)] = int(e - b);
        displs[std::size_t(r)] = int(b);
      }
      const std::size_t b = std::size_t(displs[std::size_t(w.rank)]);
      std::vector<double> mine(static_cast<std::size_t>(counts[std::size_t(w.rank)]));
      in.prog.visit([&](const auto& sdf) {
        estimate_brick_work(sdf, spec, layout, b, Span<double>(mine), bw);
      });
      MPI_Allgatherv(mine.data(), int(mine.size()), MPI_DOUBLE, work.data(), counts.data(),
                     displs.data(), MPI_DOUBLE, w.comm);
    } else {
      in.prog.visit([&](const auto& sdf) {
        estimate_brick_work(sdf, spec, layout, 0, Span<double>(work), bw);
      });
    }
    dec = decompose(layout, std::size_t(w.size), Span<const double>(work));
  });
  const GridRange owned = dec.parts[std::size_t(w.rank)].range;
  const GridRange evaluated =
      kind == OutputKind::pvti && owned.size() ? piece_range(owned, spec.dims) : owned;
  const double t2 = scene::now_s();

  // 3. Sample this rank's box.
  std::vector<T> values;
  double eval_s = 0;
  phase(w.comm, [&] {
    scene::require_memory(std::uint64_t(evaluated.size()) * sizeof(T),
                          "this rank's part of the grid");
    values.resize(evaluated.size());
    const double s0 = scene::now_s();
    if (evaluated.size()) {
      // A mesh file is sampled through the mesh SDF itself (tile and band searches).
      auto ok = in.prog.visit([&](const auto& sdf) {
        return sample_grid_box(sdf, spec, evaluated, Span<T>(values), gopt);
      });
      if (!ok) fail(scene::exit_failure, ok.error().what());
    }
    eval_s = scene::now_s() - s0;
  });
  // A grid with NaN or infinite samples (values the working precision cannot carry) is never
  // written, as in the serial tool: every rank counts its owned samples and all refuse together.
  {
    std::uint64_t bad = 0, total = 0;
    for (std::size_t k = owned.lo[2]; k < owned.hi[2]; ++k)
      for (std::size_t j = owned.lo[1]; j < owned.hi[1]; ++j)
        for (std::size_t i = owned.lo[0]; i < owned.hi[0]; ++i)
          bad += !std::isfinite(values[evaluated.index(i, j, k)]);
    MPI_Allreduce(&bad, &total, 1, MPI_UINT64_T, MPI_SUM, w.comm);
    phase(w.comm, [&] { jobs::require_finite_grid(total, spec.size(), o.input); });
  }
  const double t3 = scene::now_s();

  // 4. Write.
  WriteGridOptions wopt;
  wopt.dtype = sizeof(T) == 4 ? DType::float32 : DType::float64;
  const Span<const T> v(values);
  if (kind == OutputKind::pvti) {
    const std::string piece = piece_path(o.output, w.rank);
    Status st = guarded([&] {
      if (evaluated.size() == 0) return;
      auto ok = write_vti_piece(piece, spec, evaluated, evaluated, v, wopt);
      if (!ok) fail(scene::exit_output, ok.error().what());
    });
    st = agree(st, w.comm);
    if (st && root) {
      auto ok = write_pvti(o.output, spec, pvti_pieces(o.output, dec, spec.dims), wopt);
      if (!ok) st = {scene::exit_output, ok.error().what()};
    }
    st = agree(st, w.comm);
    if (!st) {
      std::remove(piece.c_str()); // no half outputs: the pieces go with the .pvti
      throw Abort{st};
    }
  } else {
    const std::string header =
        kind == OutputKind::npy
            ? npy_header(npy_descr(wopt.dtype), {spec.nz(), spec.ny(), spec.nx()})
            : "";
    // The .raw sidecar waits in a group for the data: it appears only if the data was written.
    std::unique_ptr<OutputGroup> sidecar;
    if (kind == OutputKind::raw) {
      Status st;
      if (root) {
        sidecar = std::make_unique<OutputGroup>();
        const std::string side = raw_sidecar_path(o.output);
        const std::string base = std::filesystem::path(o.output).filename().string();
        AtomicFile f(side);
        const std::string js = raw_sidecar_json(spec, base, wopt);
        if (!f.is_open()) {
          st = {scene::exit_output, f.open_error().what()};
        } else {
          f.stream().write(js.data(), std::streamsize(js.size()));
          auto ok = f.close();
          if (ok) ok = f.commit();
          if (!ok) st = {scene::exit_output, ok.error().what()};
        }
      }
      st = agree(st, w.comm);
      if (!st) throw Abort{st};
    }
    write_collective(o.output, header, spec, owned, v, w.comm);
    Status st;
    if (sidecar)
      if (auto ok = sidecar->commit(); !ok) st = {scene::exit_output, ok.error().what()};
    st = agree(st, w.comm);
    if (!st) {
      if (root) std::remove(o.output.c_str()); // no data without its sidecar
      throw Abort{st};
    }
  }
  const double t4 = scene::now_s();

  // 5. Statistics over the owned samples, and the balance actually achieved.
  double mn = std::numeric_limits<double>::infinity(), mx = -mn, inside = 0;
  for (std::size_t k = owned.lo[2]; k < owned.hi[2]; ++k)
    for (std::size_t j = owned.lo[1]; j < owned.hi[1]; ++j)
      for (std::size_t i = owned.lo[0]; i < owned.hi[0]; ++i) {
        const T x = values[evaluated.index(i, j, k)];
        mn = std::min(mn, double(x));
        mx = std::max(mx, double(x));
        inside += x < 0;
      }
  double gmn = 0, gmx = 0, ginside = 0;
  MPI_Reduce(&mn, &gmn, 1, MPI_DOUBLE, MPI_MIN, 0, w.comm);
  MPI_Reduce(&mx, &gmx, 1, MPI_DOUBLE, MPI_MAX, 0, w.comm);
  MPI_Reduce(&inside, &ginside, 1, MPI_DOUBLE, MPI_SUM, 0, w.comm);
  const std::vector<double> evals = allgather(eval_s, w.comm);
  const std::vector<double> loads = allgather(in.parse_s + in.build_s, w.comm);
  if (!root || (o.quiet && !o.json)) return scene::exit_ok;

  double emax = 0, esum = 0;
  for (double e : evals) {
    emax = std::max(emax, e);
    esum += e;
  }
  const double measured = esum > 0 ? emax * double(evals.size()) / esum : 1.0;
  std::size_t band_bricks = 0; // bricks estimated to meet the band (all of them when dense)
  if (gopt.band > 0) {
    for (std::size_t b = 0; b < layout.size(); ++b)
      band_bricks += work[b] == double(layout.brick_range(b).size());
  } else {
    band_bricks = layout.size();
  }
  const double load_max = *std::max_element(loads.begin(), loads.end());
  const double inside_fraction = ginside / double(spec.size());
  if (o.json) {
    Json j = jobs::grid_job_json(o, in, spec, gopt.band);
    j["timings"] = {{"load_s", load_max},
                    {"decompose_s", t2 - t1},
                    {"eval_s", emax},
                    {"write_s", t4 - t3},
                    {"total_s", t4 - t0}};
    j["min"] = gmn;
    j["max"] = gmx;
    j["inside_fraction"] = inside_fraction;
    j["threads"] = resolve_threads(gopt.exec);
    Json parts = Json::array();
    for (std::size_t r = 0; r < dec.parts.size(); ++r) {
      const auto& p = dec.parts[r];
      parts.push_back({{"lo", {p.range.lo[0], p.range.lo[1], p.range.lo[2]}},
                       {"hi", {p.range.hi[0], p.range.hi[1], p.range.hi[2]}},
                       {"work", p.work},
                       {"eval_s", evals[r]}});
    }
    j["mpi"] = {{"ranks", w.size},
                {"ranks_per_node", w.local_size},
                {"geometry", "read by every rank"},
                {"bricks", layout.size()},
                {"brick", layout.brick[0]},
                {"band_bricks", band_bricks},
                {"imbalance_estimated", dec.imbalance()},
                {"imbalance_measured", measured},
                {"parts", parts}};
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    std::printf("ebgeom-mpi sdf: %s -> %s (%d ranks x %d threads)\n", o.input.c_str(),
                o.output.c_str(), w.size, resolve_threads(gopt.exec));
    std::printf("  grid      %zu x %zu x %zu %s-centred samples, %zu bricks of %zu^3\n", spec.nx(),
                spec.ny(), spec.nz(), to_string(spec.centering), layout.size(), layout.brick[0]);
    std::printf("  values    min %.6g  max %.6g  inside fraction %.4f\n", gmn, gmx,
                inside_fraction);
    std::printf("  balance   work max/mean %.3f estimated, %.3f measured (eval time)\n",
                dec.imbalance(), measured);
    std::printf("  time      load %.3f s  decompose %.3f s  eval %.3f s  write %.3f s\n", load_max,
                t2 - t1, emax, t4 - t3);
  }
  return scene::exit_ok;
}

} // namespace ebgeom::mpi

int main(int argc, char** argv) {
  using namespace ebgeom;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  mpi::World w;
  MPI_Comm_rank(w.comm, &w.rank);
  MPI_Comm_size(w.comm, &w.size);
  MPI_Comm node;
  MPI_Comm_split_type(w.comm, MPI_COMM_TYPE_SHARED, w.rank, MPI_INFO_NULL, &node);
  MPI_Comm_size(node, &w.local_size);
  MPI_Comm_free(&node);

  CLI::App app{"ebgeom-mpi: ebgeom sdf distributed over MPI ranks (S < 0 inside, S > 0 outside)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("ebgeom-mpi ") + EBGEOM_VERSION_STRING);
  app.footer("Exit status: 0 success, 1 internal error, 2 usage, 3 input, 4 output, 5 memory "
             "(the same on every rank).");
  auto o = std::make_shared<jobs::SdfOptions>();
  CLI::App* sub = app.add_subcommand(
      "sdf", "Sample the signed distance of a mesh or scene on a grid split over the ranks");
  jobs::add_sdf_options(sub, o);
  sub->get_option("--output")
      ->description("output: OUT.pvti (one OUT_<rank>.vti piece per rank beside it), .npy or .raw "
                    "(one file written with MPI-IO)");
  sub->footer("Output: OUT.pvti (+ OUT_<rank>.vti pieces), or one .npy / .raw file written with "
              "MPI-IO.\n--threads 0 (default) gives each rank its share of the node's cores.\n"
              "Examples:\n"
              "  mpirun -n 4 ebgeom-mpi sdf bunny.obj -o bunny.pvti --res 512 --band 3\n"
              "  srun ebgeom-mpi sdf part.stl -o part.npy --dx 0.001 --band 4 --json");
  int code = scene::exit_ok;
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) { // --help, --version
    if (w.rank == 0) code = app.exit(e);
    MPI_Finalize();
    return code;
  } catch (const CLI::ParseError& e) {
    if (w.rank == 0) {
      std::fprintf(stderr, "ebgeom-mpi: error: %s\n", e.what());
      std::fprintf(stderr, "Run 'ebgeom-mpi sdf --help' for usage.\n");
    }
    MPI_Finalize();
    return scene::exit_usage;
  }
  try {
    code = o->precision == "double" ? mpi::run<double>(*o, w) : mpi::run<float>(*o, w);
  } catch (const mpi::Abort& a) {
    if (w.rank == 0) std::fprintf(stderr, "ebgeom-mpi: error: %s\n", a.status.message.c_str());
    code = a.status.code;
  } catch (const std::exception& e) {
    // Outside every agreed phase: the other ranks may be waiting in a collective.
    std::fprintf(stderr, "ebgeom-mpi: error (rank %d): %s\n", w.rank, e.what());
    MPI_Abort(w.comm, scene::exit_failure);
  }
  MPI_Finalize();
  return code;
}
