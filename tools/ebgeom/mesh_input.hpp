// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// Reading meshes for the CLI and turning them into mesh SDFs, with CLI errors.

#include <memory>
#include <string>
#include <utility>

#include "common.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"
#include "ebgeom/mesh/triangle_mesh.hpp"

#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"
#include "ebgeom/sdf/signed_mesh_sdf.hpp"

#define EBGEOM_CLI_HAS_BVH 1

namespace ebgeom::cli {

/// How the sign of a mesh SDF is decided (`--sign`, scene key "sign"): the library's
/// `ebgeom::SignMode` (sdf/signed_mesh_sdf.hpp).
using ebgeom::SignMode;

/// Parses a --sign / "sign" value: pseudonormal, winding, fast-winding, unsigned or auto.
/// Throws CliError(`code`) prefixed by `where`.
inline SignMode parse_sign_mode(const std::string& s, int code, const std::string& where) {
  if (s == "pseudonormal") return SignMode::pseudonormal;
  if (s == "winding") return SignMode::winding;
  if (s == "fast-winding") return SignMode::fast_winding;
  if (s == "unsigned") return SignMode::unsigned_distance;
  if (s == "auto") return SignMode::automatic;
  fail(code, where + ": unknown sign mode '" + s +
                 "' (expected pseudonormal, winding, fast-winding, unsigned or auto)");
}

/// The CLI spelling of a mode (the inverse of `parse_sign_mode`).
inline const char* sign_name(SignMode m) noexcept {
  switch (m) {
  case SignMode::pseudonormal:
    return "pseudonormal";
  case SignMode::winding:
    return "winding";
  case SignMode::fast_winding:
    return "fast-winding";
  case SignMode::unsigned_distance:
    return "unsigned";
  case SignMode::automatic:
    return "auto";
  }
  return "?";
}

/// The mesh SDF the CLI uses: `SignedMeshSdf<T>` (the BVH `MeshSdf<T>`'s exact distance with the
/// chosen sign mode). Keeps the `TriangleMesh` for normals. Immutable; thread-safe queries.
template <class T> class CliMeshSdf {
 public:
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;

  /// Closest point of the surface with the signed distance and the triangle holding it.
  struct Hit {
    T distance;
    Vec3<T> point;
    Index triangle;
  };

  /// `sign = automatic` validates `soup` and picks pseudonormal or fast winding.
  static Result<CliMeshSdf> build(const PolygonSoup<T>& soup, SignMode sign = SignMode::automatic) {
    SignOptions opt;
    opt.mode = sign;
    auto sdf = SignedMeshSdf<T>::build(soup, opt);
    if (!sdf) return sdf.error();
    CliMeshSdf s;
    s.requested_ = sign;
    s.sdf_ = std::make_shared<const SignedMeshSdf<T>>(std::move(*sdf));
    return s;
  }

  T operator()(const Vec3<T>& p) const noexcept { return (*sdf_)(p); }
  Aabb<T> bounds() const noexcept { return sdf_->bounds(); }
  Hit closest(const Vec3<T>& p) const noexcept {
    const auto h = sdf_->closest(p);
    return {h.distance, h.point, h.triangle};
  }
  const TriangleMesh<T>& mesh() const noexcept { return sdf_->mesh(); }
  /// The library's signed mesh SDF (its `closest` also reports the feature).
  const SignedMeshSdf<T>& signed_sdf() const noexcept { return *sdf_; }
  /// The mode asked for, the mode used (never automatic) and why ("requested" unless automatic).
  SignMode requested_sign() const noexcept { return requested_; }
  SignMode sign() const noexcept { return sdf_->resolved_mode(); }
  const std::string& sign_reason() const noexcept { return sdf_->reason(); }
  /// `exact` with the pseudonormal sign; `implicit` otherwise: unsigned, or a winding sign, which
  /// changes across the w = 1/2 surface (filling holes) as well as across the mesh, so the grid
  /// sampler must not propagate signs between far samples or skip far blocks.
  SdfKind sign_kind() const noexcept {
    return sign() == SignMode::pseudonormal ? SdfKind::exact : SdfKind::implicit;
  }
  /// "bvh".
  static const char* method() noexcept { return "bvh"; }

 private:
  std::shared_ptr<const SignedMeshSdf<T>> sdf_;
  SignMode requested_ = SignMode::automatic;
};

/// Reads a mesh file (STL, PLY, OBJ, legacy VTK; format detected by content). Throws CliError
/// (input) with the reader's `FILE: line/byte: what` message.
template <class T> PolygonSoup<T> load_mesh(const std::string& path) {
  auto soup = io::read_mesh<T>(path);
  if (!soup) fail(exit_input, soup.error().what());
  return std::move(*soup);
}

/// Builds the CLI's mesh SDF with sign mode `sign`. Throws CliError (input) naming `path` on
/// failure.
template <class T>
CliMeshSdf<T> build_mesh_sdf(const PolygonSoup<T>& soup, const std::string& path,
                             SignMode sign = SignMode::automatic) {
  auto sdf = CliMeshSdf<T>::build(soup, sign);
  if (!sdf) fail(exit_input, path + ": " + sdf.error().what());
  return std::move(*sdf);
}

} // namespace ebgeom::cli
