// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// `ebgeom convert IN OUT`: mesh format conversion.
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <string>

#include "commands.hpp"
#include "common.hpp"
#include "ebgeom/eval/write_grid.hpp"
#include "ebgeom/io/write_mesh.hpp"
#include "ebgeom/scene/mesh_input.hpp"

namespace ebgeom::cli {

namespace {

struct ConvertOptions {
  std::string input, output;
  bool ascii = false, quiet = false;
};

io::MeshFormat format_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".stl") return io::MeshFormat::stl;
  if (ext == ".ply") return io::MeshFormat::ply;
  if (ext == ".obj") return io::MeshFormat::obj;
  if (ext == ".vtk") return io::MeshFormat::vtk;
  if (ext == ".off") return io::MeshFormat::off;
  return io::MeshFormat::unknown;
}

int run_convert(const ConvertOptions& o) {
  io::WriteOptions w;
  w.format = format_of(o.output);
  if (w.format == io::MeshFormat::unknown)
    fail(exit_usage, o.output + ": unknown output format; expected .stl, .ply, .obj, .off or .vtk");
  w.encoding = o.ascii ? io::Encoding::ascii : io::Encoding::binary;
  require_input_file(o.input);
  std::error_code ec;
  if (std::filesystem::exists(o.output) && std::filesystem::equivalent(o.input, o.output, ec))
    fail(exit_usage, o.output + ": is the input itself");
  // Double precision keeps PLY/OBJ/OFF/VTK coordinates exact (STL stores float, and
  // encode_mesh refuses coordinates that float cannot hold).
  const PolygonSoup<double> soup = load_mesh<double>(o.input);
  auto bytes = io::encode_mesh(soup, w);
  if (!bytes)
    fail(exit_input, o.input + ": cannot be written as " + io::to_string(w.format) + ": " +
                         bytes.error().what());
  ebgeom::AtomicFile f(o.output);
  if (!f.is_open()) fail(exit_output, f.open_error().what());
  f.stream().write(bytes->data(), std::streamsize(bytes->size()));
  if (auto ok = f.close(); !ok) fail(exit_output, ok.error().what());
  if (auto ok = f.commit(); !ok) fail(exit_output, ok.error().what());
  if (!o.quiet)
    std::printf("ebgeom convert: %s -> %s (%s %s): %zu vertices, %zu faces\n", o.input.c_str(),
                o.output.c_str(), io::to_string(w.format),
                io::effective_encoding(w.format, w.encoding) == io::Encoding::ascii ? "ascii"
                                                                                    : "binary",
                soup.vertex_count(), soup.face_count());
  return exit_ok;
}

} // namespace

Subcommand add_convert(CLI::App& app) {
  auto o = std::make_shared<ConvertOptions>();
  CLI::App* sub =
      app.add_subcommand("convert", "Convert a mesh between STL, PLY, OBJ, OFF and VTK");
  sub->add_option("IN", o->input, "input mesh (format detected from the content)")->required();
  sub->add_option("OUT", o->output, "output mesh: .stl, .ply, .obj, .off or .vtk (by extension)")
      ->required();
  sub->add_flag("--ascii", o->ascii,
                "text STL/PLY/VTK instead of binary (OBJ and OFF are always text)");
  sub->add_flag("-q,--quiet", o->quiet, "no summary");
  sub->footer("Examples:\n  ebgeom convert bunny.obj bunny.stl\n"
              "  ebgeom convert part.stl part.ply --ascii");
  return {sub, [o] { return run_convert(*o); }};
}

} // namespace ebgeom::cli
