// `ebgeom sdf INPUT -o OUT`: a dense SDF grid from a mesh file or a JSON scene.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "grid_job.hpp"
#include "scene.hpp"

namespace ebgeom::cli {

namespace {

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
  bool json = false, quiet = false, nodes = false;
};

template <class T> GridSpec<T> make_spec(const SdfOptions& o, const Aabb<T>& bounds) {
  GridSpec<T> spec;
  spec.centering = o.nodes ? Centering::node : Centering::cell;
  if (!o.box.empty()) {
    spec.box =
        Aabb<T>({T(o.box[0]), T(o.box[1]), T(o.box[2])}, {T(o.box[3]), T(o.box[4]), T(o.box[5])});
    for (int a = 0; a < 3; ++a)
      if (!(spec.box.lo[a] < spec.box.hi[a]))
        fail(exit_usage,
             std::string("--box: X0 Y0 Z0 must be below X1 Y1 Z1 (axis ") + "xyz"[a] + ")");
  } else {
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(bounds.lo[a]) || !std::isfinite(bounds.hi[a]))
        fail(exit_usage, o.input + ": the input is unbounded (e.g. a plane); give --box");
    if (bounds.is_empty()) fail(exit_input, o.input + ": the input is empty");
    const Vec3<T> e = bounds.extent();
    const T big = max_component(e) > T(0) ? max_component(e) : T(1);
    Vec3<T> pad;
    for (int a = 0; a < 3; ++a) pad[a] = T(o.pad) * (e[a] > big * T(1e-3) ? e[a] : big);
    spec.box = Aabb<T>(bounds.lo - pad, bounds.hi + pad);
  }
  if (o.dx > 0) {
    const Vec3<T> e = spec.box.extent();
    for (int a = 0; a < 3; ++a) {
      const double n = std::ceil(double(e[a]) / o.dx - 1e-9);
      if (n > double(1 << 21)) fail(exit_usage, "--dx is too small for the box (over 2^21 cells)");
      spec.dims[a] = std::max<std::size_t>(1, std::size_t(n)) + (o.nodes ? 1 : 0);
      const std::size_t cells = o.nodes ? spec.dims[a] - 1 : spec.dims[a];
      spec.box.hi[a] = spec.box.lo[a] + T(double(std::max<std::size_t>(cells, 1)) * o.dx);
    }
  } else if (o.res.size() == 3) {
    spec.dims = {{o.res[0], o.res[1], o.res[2]}};
  } else {
    const std::size_t n = o.res.empty() ? 64 : o.res[0];
    spec.dims = {{n, n, n}};
  }
  if (auto ok = spec.validate(); !ok) fail(exit_usage, ok.error().what());
  return spec;
}

template <class T> int run_sdf_as(const SdfOptions& o) {
  const bool scene = is_scene_path(o.input);
  const SignMode sign = parse_sign_mode(o.sign, exit_usage, "--sign");
  auto fmt = grid_format_of(o.output);
  if (!fmt) fail(exit_usage, fmt.error().what());
  SliceSpec slice;
  if (!o.png.empty()) slice = parse_slice(o.slice);
  require_input_file(o.input);
  {
    std::error_code ec;
    auto same = [&](const std::string& out) {
      return std::filesystem::exists(out) && std::filesystem::equivalent(out, o.input, ec);
    };
    if (same(o.output) || (*fmt == GridFormat::raw && same(raw_sidecar_path(o.output))) ||
        (!o.png.empty() && same(o.png)))
      fail(exit_usage, o.output + ": writing it would overwrite the input " + o.input);
  }

  const double t0 = now_s();
  Program<T> prog;
  SceneInfo info;
  double t1;
  if (scene) {
    const Json doc = read_json_file(o.input);
    t1 = now_s();
    prog = compile_scene<T>(doc, o.input, &info);
  } else {
    PolygonSoup<T> soup = load_mesh<T>(o.input);
    t1 = now_s();
    prog.box = Aabb<T>::empty();
    auto sdf = std::make_shared<const CliMeshSdf<T>>(build_mesh_sdf(soup, o.input, sign));
    prog.box = sdf->bounds();
    prog.code.push_back({Op::mesh, 0, sign == SignMode::unsigned_distance ? 1u : 0u});
    prog.scene_kind = sdf->sign_kind();
    prog.meshes.push_back(std::move(sdf));
  }
  const double t2 = now_s();

  const GridSpec<T> spec = make_spec(o, prog.bounds());
  const Vec3<T> h = spec.spacing();
  require_memory(std::uint64_t(spec.size()) * sizeof(T),
                 "a " + std::to_string(spec.nx()) + " x " + std::to_string(spec.ny()) + " x " +
                     std::to_string(spec.nz()) + " grid of " +
                     (sizeof(T) == 4 ? "float" : "double"));
  GridOptions gopt;
  gopt.exec.threads = o.threads;
  gopt.band = o.band * double(max_component(h));
  const auto values =
      sample_with_progress(prog, spec, gopt, !o.quiet && !o.json && stderr_is_terminal());
  const double t3 = now_s();
  const Span<const T> v(values);
  write_grid_or_fail(o.output, spec, v, sizeof(T) == 4 ? DType::float32 : DType::float64);
  PngInfo img;
  if (!o.png.empty()) img = write_png_slice(o.png, extract_slice(spec, v, slice));
  const double t4 = now_s();
  const GridStats st = grid_stats(v);
  const int threads = resolve_threads(gopt.exec);

  if (o.json) {
    Json j;
    j["input"] = o.input;
    j["input_kind"] = scene ? "scene" : "mesh";
    j["output"] = o.output;
    j["triangles"] = prog.triangle_count();
    j["dims"] = {spec.nx(), spec.ny(), spec.nz()};
    j["box"] = {{"lo", {double(spec.box.lo.x), double(spec.box.lo.y), double(spec.box.lo.z)}},
                {"hi", {double(spec.box.hi.x), double(spec.box.hi.y), double(spec.box.hi.z)}}};
    j["spacing"] = {double(h.x), double(h.y), double(h.z)};
    const Vec3<T> org = spec.origin();
    j["origin"] = {double(org.x), double(org.y), double(org.z)};
    j["centering"] = to_string(spec.centering);
    j["precision"] = sizeof(T) == 4 ? "float" : "double";
    j["band"] = gopt.band;
    j["timings"] = {
        {"parse_s", t1 - t0}, {"build_s", t2 - t1}, {"eval_s", t3 - t2}, {"write_s", t4 - t3}};
    j["min"] = st.min;
    j["max"] = st.max;
    j["inside_fraction"] = st.inside_fraction;
    j["sign"] = sign_name(sign);
    if (!scene)
      j["sign_used"] = {{"mode", sign_name(prog.meshes[0]->sign())},
                        {"reason", prog.meshes[0]->sign_reason()}};
    j["threads"] = threads;
    if (!o.png.empty()) j["png"] = {{"path", o.png}, {"width", img.width}, {"height", img.height}};
    std::printf("%s\n", j.dump(2).c_str());
  } else if (!o.quiet) {
    std::printf("ebgeom sdf: %s -> %s\n", o.input.c_str(), o.output.c_str());
    std::printf("  input     %s, %zu triangles\n", scene ? "scene" : "mesh", prog.triangle_count());
    std::printf("  grid      %zu x %zu x %zu %s-centred samples, spacing %.4g %.4g %.4g\n",
                spec.nx(), spec.ny(), spec.nz(), to_string(spec.centering), double(h.x),
                double(h.y), double(h.z));
    std::printf("  values    min %.6g  max %.6g  inside fraction %.4f\n", st.min, st.max,
                st.inside_fraction);
    if (!scene)
      std::printf("  sign      %s (%s)\n", sign_name(prog.meshes[0]->sign()),
                  prog.meshes[0]->sign_reason().c_str());
    std::printf("  time      parse %.3f s  build %.3f s  eval %.3f s  write %.3f s  (%d threads)\n",
                t1 - t0, t2 - t1, t3 - t2, t4 - t3, threads);
  }
  return exit_ok;
}

} // namespace

Subcommand add_sdf(CLI::App& app) {
  auto o = std::make_shared<SdfOptions>();
  CLI::App* sub = app.add_subcommand(
      "sdf", "Sample the signed distance of a mesh file or a JSON scene on a dense grid");
  sub->add_option("INPUT", o->input, "mesh file (STL, PLY, OBJ, VTK) or scene file (.json)")
      ->required();
  sub->add_option("-o,--output", o->output,
                  "output grid: .vti (ParaView), .npy (NumPy, shape (NZ, NY, NX)) or .raw "
                  "(with a .json sidecar)")
      ->required();
  auto* res = sub->add_option("--res", o->res,
                              "N cells on every axis, or NX NY NZ (default 64; cell-centred)")
                  ->expected(1, 3);
  auto* dx = sub->add_option("--dx", o->dx, "cubic cells of size H (the box grows to fit)")
                 ->check(CLI::PositiveNumber);
  res->excludes(dx);
  sub->add_option("--box", o->box, "X0 Y0 Z0 X1 Y1 Z1 (default: bounding box + --pad)")
      ->expected(6);
  sub->add_option("--pad", o->pad, "padding per side, as a fraction of the extent")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
  sub->add_option("--band", o->band,
                  "narrow band of W times the largest cell spacing: exact inside, ±band outside")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--sign", o->sign,
                  "sign mode for meshes: pseudonormal, winding, fast-winding, unsigned or auto "
                  "(pseudonormal on closed manifold oriented meshes, fast-winding otherwise)")
      ->capture_default_str();
  sub->add_option("--precision", o->precision, "float or double (computation and output)")
      ->check(CLI::IsMember({"float", "double"}))
      ->capture_default_str();
  sub->add_option("--threads", o->threads, "threads (0 = all cores)")
      ->check(CLI::NonNegativeNumber);
  auto* png = sub->add_option("--png", o->png, "also write a PNG slice of the grid");
  sub->add_option("--slice", o->slice, "slice of the PNG: x, y or z, optionally =FRACTION")
      ->needs(png)
      ->capture_default_str();
  sub->add_flag("--nodes", o->nodes, "node-centred samples (include the box faces)");
  sub->add_flag("--json", o->json, "print a JSON summary on stdout");
  sub->add_flag("-q,--quiet", o->quiet, "no progress bar and no summary");
  sub->footer(
      "Examples:\n"
      "  ebgeom sdf bunny.obj -o bunny.vti --res 128\n"
      "  ebgeom sdf part.stl -o part.npy --dx 0.01 --precision double --json\n"
      "  ebgeom sdf examples/scenes/csg.json -o csg.raw --res 96 --png csg.png --slice y=0.5");
  sub->callback([o, res] {
    if (!o->res.empty() && o->res.size() != 1 && o->res.size() != 3)
      throw CLI::ValidationError("--res", "expects N or NX NY NZ");
    for (std::size_t n : o->res)
      if (n < 1 || n > (std::size_t(1) << 21))
        throw CLI::ValidationError("--res", "each resolution must be in 1..2097152");
    (void)res;
  });
  return {sub, [o] {
            return o->precision == "double" ? run_sdf_as<double>(*o) : run_sdf_as<float>(*o);
          }};
}

} // namespace ebgeom::cli
