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
#include "sdf_job.hpp"

namespace ebgeom::cli {

namespace {

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
  const SdfInput<T> in = load_sdf_input<T>(o, sign);
  const Program<T>& prog = in.prog;
  const double t1 = t0 + in.parse_s;
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
  add_sdf_options(sub, o);
  sub->footer(
      "Examples:\n"
      "  ebgeom sdf bunny.obj -o bunny.vti --res 128\n"
      "  ebgeom sdf part.stl -o part.npy --dx 0.01 --precision double --json\n"
      "  ebgeom sdf examples/scenes/csg.json -o csg.raw --res 96 --png csg.png --slice y=0.5");
  return {sub, [o] {
            return o->precision == "double" ? run_sdf_as<double>(*o) : run_sdf_as<float>(*o);
          }};
}

} // namespace ebgeom::cli
