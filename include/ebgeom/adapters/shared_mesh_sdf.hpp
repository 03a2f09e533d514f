// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Build a mesh SDF once, in shared immutable storage, for the embedded-boundary adapters
/// (`EbFunction`, integrations/amrex, integrations/chombo). The adapters on every AMR level, every
/// grid and every thread then point at this one object: the mesh and its BVH are never copied.
///
/// The SDF is the library's one mesh SDF with a selectable sign, `SignedMeshSdf`, with the
/// library's default sign (`SignMode::automatic`, the command line's `--sign auto`): the exact
/// pseudonormal sign on closed, manifold, consistently oriented meshes, a winding-number sign on
/// others. Reading the mesh is not done here: read it with `io::read_mesh` (io/read_mesh.hpp),
/// then call `make_shared_mesh_sdf`.

#include <memory>
#include <utility>

#include "ebgeom/core/error.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"
#include "ebgeom/sdf/signed_mesh_sdf.hpp"

namespace ebgeom {

/// A mesh SDF shared by every adapter that evaluates it.
template <class T> using SharedMeshSdf = std::shared_ptr<const SignedMeshSdf<T>>;

/// Triangulates and validates `soup`, builds its `SignedMeshSdf<T>` with the sign `options.mode`
/// (default `automatic`; see `SignedMeshSdf::build` for the errors) and moves it into shared
/// immutable storage. The soup may be freed afterwards. Memory: `memory_bytes()` of the result,
/// once, however many adapters share it. `resolved_mode()` and `reason()` say which sign was
/// chosen and why.
template <class T>
Result<SharedMeshSdf<T>> make_shared_mesh_sdf(const PolygonSoup<T>& soup,
                                              const SignOptions& options = {}) {
  Result<SignedMeshSdf<T>> sdf = SignedMeshSdf<T>::build(soup, options);
  if (!sdf) return std::move(sdf).error();
  return SharedMeshSdf<T>(std::make_shared<const SignedMeshSdf<T>>(std::move(sdf).value()));
}

} // namespace ebgeom
