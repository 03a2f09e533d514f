#pragma once
// Reading meshes for the CLI and turning them into mesh SDFs, with CLI errors.

#include <string>

#include "common.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"

#if __has_include("ebgeom/io/read_mesh.hpp")
#include "ebgeom/io/read_mesh.hpp"
#define EBGEOM_CLI_HAS_IO 1
#else
#define EBGEOM_CLI_HAS_IO 0
#endif

namespace ebgeom::cli {

/// The mesh SDF the CLI uses (the fastest exact one available).
template <class T> using CliMeshSdf = BruteForceMeshSdf<T>;

/// How the sign of a mesh SDF is decided (`--sign`, scene key "sign").
enum class SignMode { pseudonormal, unsigned_distance };

/// Parses a --sign / "sign" value. Modes that do not exist yet are refused with a message.
/// Throws CliError(`code`) prefixed by `where`.
SignMode parse_sign_mode(const std::string& s, int code, const std::string& where);
const char* to_string(SignMode m);

/// Reads a mesh file (STL, PLY, OBJ, legacy VTK; format detected by content). Throws CliError
/// (input) with the reader's `FILE: line/byte: what` message.
template <class T> PolygonSoup<T> load_mesh(const std::string& path) {
#if EBGEOM_CLI_HAS_IO
  auto soup = io::read_mesh<T>(path);
  if (!soup) fail(exit_input, soup.error().what());
  return std::move(*soup);
#else
  fail(exit_input, path + ": reading mesh files needs ebgeom's io module, absent from this build");
#endif
}

/// Builds the CLI's mesh SDF. Throws CliError (input) naming `path` on failure.
template <class T>
CliMeshSdf<T> build_mesh_sdf(const PolygonSoup<T>& soup, const std::string& path) {
  auto sdf = CliMeshSdf<T>::build(soup);
  if (!sdf) fail(exit_input, path + ": " + sdf.error().what());
  return std::move(*sdf);
}

} // namespace ebgeom::cli
