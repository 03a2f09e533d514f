// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// `is_gltf_path`, the same with or without tinygltf.
#include <cctype>

#include "ebgeom/scene/gltf.hpp"

namespace ebgeom::scene {

bool is_gltf_path(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || path.find('/', dot) != std::string::npos) return false;
  std::string ext = path.substr(dot + 1);
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == "gltf" || ext == "glb";
}

} // namespace ebgeom::scene
