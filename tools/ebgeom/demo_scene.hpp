// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// The demo scene: analytic shapes, CSG (sharp and smooth) and a procedurally generated mesh,
// written in the scene format (docs/scene-format.md) and compiled like any scene file.

namespace ebgeom::cli {

/// The demo scene as scene-format JSON.
inline const char* demo_scene_json() {
  return R"({
  "version": 1,
  "description": "icosphere mesh minus a box, a torus ring, and a smooth capsule-and-sphere mast",
  "root": {
    "type": "union",
    "children": [
      {"type": "difference", "children": [
        {"type": "mesh", "generate": "icosphere", "subdivisions": 2, "radius": 1.0},
        {"type": "box", "center": [0.6, 0.6, 0.6], "half_size": [0.5, 0.5, 0.5]}
      ]},
      {"type": "torus", "major_radius": 1.5, "minor_radius": 0.2,
       "rotate": {"axis": [1, 0, 0], "degrees": 20}},
      {"type": "union", "smooth": 0.25, "children": [
        {"type": "capsule", "a": [0, 0, 0.9], "b": [0, 0, 1.7], "radius": 0.12},
        {"type": "sphere", "center": [0, 0, 1.9], "radius": 0.3}
      ]}
    ]
  }
})";
}

inline const char* demo_scene_description() {
  return "icosphere mesh (320 triangles) minus a box, a rotated torus, a smooth capsule + sphere";
}

} // namespace ebgeom::cli
