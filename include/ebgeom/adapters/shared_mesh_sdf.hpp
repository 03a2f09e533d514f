// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Build a mesh SDF once, in shared immutable storage, for the embedded-boundary adapters
/// (`EbFunction`, integrations/amrex, integrations/chombo). The adapters on every AMR level, every
/// grid and every thread then point at this one object: the mesh and its BVH are never copied.

#include <memory>
#include <string>
#include <utility>

#include "ebgeom/core/error.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"

namespace ebgeom {

/// A mesh SDF shared by every adapter that evaluates it.
template <class T> using SharedMeshSdf = std::shared_ptr<const MeshSdf<T>>;

/// Triangulates `soup`, builds its `MeshSdf<T>` (see `MeshSdf::build` for the errors) and moves it
/// into shared immutable storage. The soup may be freed afterwards. Memory: `memory_bytes()` of
/// the result, once, however many adapters share it. The sign is exact for closed, consistently
/// oriented, manifold meshes (check with `validate`).
template <class T>
Result<SharedMeshSdf<T>>
make_shared_mesh_sdf(const PolygonSoup<T>& soup,
                     const bvh::BuildOptions& options = MeshSdf<T>::default_build_options()) {
  Result<MeshSdf<T>> sdf = MeshSdf<T>::build(soup, options);
  if (!sdf) return std::move(sdf).error();
  return SharedMeshSdf<T>(std::make_shared<const MeshSdf<T>>(std::move(sdf).value()));
}

/// Reads the mesh file `path` (STL, PLY, OBJ, OFF or VTK: `io::read_mesh`) and builds its shared
/// `MeshSdf<T>`. Errors: the reader's (converted to `Error`, message with path and location) or
/// the build's. The file's bytes and the polygon soup are freed before returning.
template <class T>
Result<SharedMeshSdf<T>>
read_shared_mesh_sdf(const std::string& path,
                     const bvh::BuildOptions& options = MeshSdf<T>::default_build_options()) {
  Result<PolygonSoup<T>, ParseError> soup = io::read_mesh<T>(path);
  if (!soup) return Error(std::move(soup).error());
  return make_shared_mesh_sdf(*soup, options);
}

} // namespace ebgeom
