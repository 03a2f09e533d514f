// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// In-memory meshes that a scene names by reference, `{"type": "mesh", "ref": "NAME"}`, instead of
// a file: the program that compiles the scene registers them (`MeshRegistry`) and passes the
// registry to `compile_scene`, which takes each mesh as it is in memory (shared, not copied,
// nothing written to disk).

#include <cstddef>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "ebgeom/mesh/polygon_soup.hpp"

namespace ebgeom::scene {

/// Meshes held in memory under names, for the `"ref"` key of a scene's mesh nodes. The scene
/// compiler builds a referenced mesh's SDF exactly as it builds a mesh file's (the node's sign
/// mode; in float precision each vertex coordinate is rounded to float), so a mesh gives the same
/// values whether it comes from a file or from here. The registry only shares the meshes: a
/// compiled scene does not keep them. Not thread-safe for `add`; `find` may be called from
/// several threads.
class MeshRegistry {
 public:
  using MeshPtr = std::shared_ptr<const PolygonSoup<double>>;

  /// Registers `mesh` under `name`, replacing a mesh registered under that name before.
  /// Throws std::invalid_argument for an empty name or a null mesh.
  void add(const std::string& name, MeshPtr mesh) {
    if (name.empty()) throw std::invalid_argument("MeshRegistry::add: empty mesh name");
    if (!mesh) throw std::invalid_argument("MeshRegistry::add: null mesh for \"" + name + "\"");
    meshes_[name] = std::move(mesh);
  }

  /// The mesh registered under `name`, or null.
  MeshPtr find(const std::string& name) const {
    const auto it = meshes_.find(name);
    return it == meshes_.end() ? nullptr : it->second;
  }

  std::size_t size() const noexcept { return meshes_.size(); }
  bool empty() const noexcept { return meshes_.empty(); }

  /// The registered names, sorted.
  std::vector<std::string> names() const {
    std::vector<std::string> n;
    n.reserve(meshes_.size());
    for (const auto& [name, mesh] : meshes_) n.push_back(name);
    return n;
  }

 private:
  std::map<std::string, MeshPtr> meshes_;
};

} // namespace ebgeom::scene
