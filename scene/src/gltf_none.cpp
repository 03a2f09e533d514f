// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// glTF input in a build without tinygltf: a clear error saying how to get it.
#include <cctype>

#include "ebgeom/scene/error.hpp"
#include "ebgeom/scene/gltf.hpp"

namespace ebgeom::scene {

bool gltf_available() { return false; }

PolygonSoup<double> read_gltf(const std::string& path) {
  fail(exit_input, path +
                       ": this ebgeom was built without tinygltf, so it cannot read glTF; install "
                       "tinygltf (Debian/Ubuntu: apt install libtinygltf-dev) and rebuild (CMake "
                       "finds it, or pass -DEBGEOM_WITH_TINYGLTF=ON), or convert the file to OBJ, "
                       "PLY or STL first");
}

} // namespace ebgeom::scene
