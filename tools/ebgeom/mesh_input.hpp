#pragma once
// Reading meshes for the CLI and turning them into mesh SDFs, with CLI errors.

#include <memory>
#include <string>
#include <utility>

#include "common.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"
#include "ebgeom/mesh/triangle_mesh.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"

#include "ebgeom/io/read_mesh.hpp"

#if __has_include("ebgeom/sdf/mesh_sdf.hpp")
#include "ebgeom/sdf/mesh_sdf.hpp"
#define EBGEOM_CLI_HAS_BVH 1
#else
#define EBGEOM_CLI_HAS_BVH 0
#endif

namespace ebgeom::cli {

/// The mesh SDF the CLI uses: the BVH-accelerated `MeshSdf<T>` when this build has it, otherwise
/// the brute-force one. Keeps the `TriangleMesh` for normals. Immutable; thread-safe queries.
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

  static Result<CliMeshSdf> build(const PolygonSoup<T>& soup) {
    Result<TriangleMesh<T>> m = make_triangle_mesh(soup);
    if (!m) return m.error();
    CliMeshSdf s;
#if EBGEOM_CLI_HAS_BVH
    auto sdf = MeshSdf<T>::make(*m);
    if (!sdf) return sdf.error();
    s.sdf_ = std::make_shared<const MeshSdf<T>>(std::move(*sdf));
#else
    s.sdf_ = std::make_shared<const BruteForceMeshSdf<T>>(*m);
#endif
    s.mesh_ = std::make_shared<const TriangleMesh<T>>(std::move(*m));
    return s;
  }

  T operator()(const Vec3<T>& p) const noexcept { return (*sdf_)(p); }
  Aabb<T> bounds() const noexcept { return sdf_->bounds(); }
  Hit closest(const Vec3<T>& p) const noexcept {
    const auto h = sdf_->closest(p);
    return {h.distance, h.point, h.triangle};
  }
  const TriangleMesh<T>& mesh() const noexcept { return *mesh_; }
  /// "bvh" or "brute force".
  static const char* method() noexcept { return EBGEOM_CLI_HAS_BVH ? "bvh" : "brute force"; }

 private:
  std::shared_ptr<const TriangleMesh<T>> mesh_;
#if EBGEOM_CLI_HAS_BVH
  std::shared_ptr<const MeshSdf<T>> sdf_;
#else
  std::shared_ptr<const BruteForceMeshSdf<T>> sdf_;
#endif
};

/// How the sign of a mesh SDF is decided (`--sign`, scene key "sign").
enum class SignMode { pseudonormal, unsigned_distance };

/// Parses a --sign / "sign" value. Modes that do not exist yet are refused with a message.
/// Throws CliError(`code`) prefixed by `where`.
SignMode parse_sign_mode(const std::string& s, int code, const std::string& where);
const char* to_string(SignMode m);

/// Reads a mesh file (STL, PLY, OBJ, legacy VTK; format detected by content). Throws CliError
/// (input) with the reader's `FILE: line/byte: what` message.
template <class T> PolygonSoup<T> load_mesh(const std::string& path) {
  auto soup = io::read_mesh<T>(path);
  if (!soup) fail(exit_input, soup.error().what());
  return std::move(*soup);
}

/// Builds the CLI's mesh SDF. Throws CliError (input) naming `path` on failure.
template <class T>
CliMeshSdf<T> build_mesh_sdf(const PolygonSoup<T>& soup, const std::string& path) {
  auto sdf = CliMeshSdf<T>::build(soup);
  if (!sdf) fail(exit_input, path + ": " + sdf.error().what());
  return std::move(*sdf);
}

} // namespace ebgeom::cli
