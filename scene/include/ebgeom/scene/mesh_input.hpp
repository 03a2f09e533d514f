// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// Reading meshes for the CLI and turning them into mesh SDFs, with CLI errors.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>

#include "ebgeom/mesh/polygon_soup.hpp"
#include "ebgeom/mesh/triangle_mesh.hpp"
#include "ebgeom/scene/error.hpp"
#include "ebgeom/scene/gltf.hpp"

#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"
#include "ebgeom/sdf/signed_mesh_sdf.hpp"

namespace ebgeom::scene {

/// How the sign of a mesh SDF is decided (`--sign`, scene key "sign"): the library's
/// `ebgeom::SignMode` (sdf/signed_mesh_sdf.hpp).
using ebgeom::SignMode;

/// Parses a --sign / "sign" value with the library's name table (`ebgeom::parse_sign_mode`:
/// pseudonormal, winding, fast-winding, unsigned or auto). Throws ToolError(`code`) prefixed by
/// `where`.
inline SignMode parse_sign_mode(const std::string& s, int code, const std::string& where) {
  Result<SignMode> m = ebgeom::parse_sign_mode(s);
  if (!m) fail(code, where + ": " + m.error().what());
  return *m;
}

/// The CLI spelling of a mode: the library's `to_string` (one name table).
inline const char* sign_name(SignMode m) noexcept { return ebgeom::to_string(m); }

/// The largest coordinate or length a scene or mesh may hold in precision T: squared distances
/// between such points (and sums of three) stay finite. About 2.9e17 in float, 2.1e152 in double.
template <class T> double max_magnitude() noexcept {
  return std::sqrt(double(std::numeric_limits<T>::max())) / 64;
}
template <class T> const char* precision_name() noexcept {
  return sizeof(T) == 4 ? "float" : "double";
}

/// Reads a mesh file (STL, PLY, OBJ, OFF, legacy VTK; format detected by content), or a glTF 2.0
/// file by its extension (.gltf, .glb: `read_gltf`). Throws ToolError (input) with the reader's
/// `FILE: line/byte: what` message.
template <class T> PolygonSoup<T> load_mesh(const std::string& path) {
  if (is_gltf_path(path)) {
    PolygonSoup<double> g = read_gltf(path);
    if constexpr (std::is_same_v<T, double>) {
      return g;
    } else {
      PolygonSoup<T> out;
      out.indices = std::move(g.indices);
      out.offsets = std::move(g.offsets);
      out.vertices.reserve(g.vertices.size());
      for (const Vec3<double>& v : g.vertices) {
        const Vec3<T> w = Vec3<T>::from(v);
        if (!all_finite(w))
          fail(exit_input, path + ": a (transformed) position is outside the range of float; "
                                  "use --precision double");
        out.vertices.push_back(w);
      }
      return out;
    }
  }
  auto soup = io::read_mesh<T>(path);
  if (!soup) fail(exit_input, soup.error().what());
  return std::move(*soup);
}

/// Builds the library's mesh SDF with sign mode `sign` (`automatic`: pseudonormal on closed,
/// manifold, consistently oriented meshes, fast winding otherwise). Throws ToolError (input)
/// naming `path` on failure, and for coordinates the precision cannot carry.
template <class T>
SignedMeshSdf<T> build_mesh_sdf(const PolygonSoup<T>& soup, const std::string& path,
                                SignMode sign = SignMode::automatic) {
  for (std::size_t v = 0; v < soup.vertices.size(); ++v) {
    const Vec3<T>& p = soup.vertices[v];
    const double m =
        std::max({std::abs(double(p.x)), std::abs(double(p.y)), std::abs(double(p.z))});
    if (m > max_magnitude<T>()) { // NaN is left to the mesh SDF's own check
      char buf[200];
      std::snprintf(buf, sizeof buf,
                    ": vertex %zu has a coordinate of magnitude %.6g, too large for %s precision "
                    "(at most %.3g)%s",
                    v, m, precision_name<T>(), max_magnitude<T>(),
                    sizeof(T) == 4 ? "; use --precision double" : "; rescale the mesh");
      fail(exit_input, path + buf);
    }
  }
  SignOptions opt;
  opt.mode = sign;
  auto sdf = SignedMeshSdf<T>::build(soup, opt);
  if (!sdf) fail(exit_input, path + ": " + sdf.error().what());
  return std::move(*sdf);
}

} // namespace ebgeom::scene
