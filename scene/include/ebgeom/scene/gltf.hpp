// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// glTF 2.0 input (.gltf with its buffers, or binary .glb) through tinygltf, kept out of the
// header-only core. Built when tinygltf is found (EBGEOM_WITH_TINYGLTF); otherwise reading a glTF
// file is an error saying how to get it.

#include <string>

#include "ebgeom/mesh/polygon_soup.hpp"

namespace ebgeom::scene {

/// True when this build reads glTF.
bool gltf_available();

/// True when `path` ends in `.gltf` or `.glb` (case-insensitive).
bool is_gltf_path(const std::string& path);

/// Reads the triangles of every mesh instance of a glTF 2.0 file's scene (the default scene, else
/// the first, else every root node) with each node's transform (matrix, or translation * rotation
/// * scale, composed from the root) applied in double precision. Primitives of mode TRIANGLES,
/// TRIANGLE_STRIP and TRIANGLE_FAN are read (points and lines are skipped); a node whose
/// transform mirrors (negative determinant) gets its triangles reversed so they stay outward.
/// POSITION must be float VEC3; indices unsigned byte, short or int (or none). Every accessor is
/// checked against its buffer. Throws ToolError (input) naming the file and the element at fault.
PolygonSoup<double> read_gltf(const std::string& path);

} // namespace ebgeom::scene
