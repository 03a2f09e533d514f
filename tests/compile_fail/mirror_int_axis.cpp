// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Must NOT compile: mirror with the axis as a number.
#include "ebgeom/sdf/shapes.hpp"
#include "ebgeom/sdf/transforms.hpp"

int main() {
  const ebgeom::Sphere<double> ball{{2, 0, 0}, 0.5};
  const auto twins = ebgeom::mirror(ball, 0);
  return twins({-2, 0, 0}) < 0 ? 0 : 1;
}
