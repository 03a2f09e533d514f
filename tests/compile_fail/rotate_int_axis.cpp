// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Must NOT compile: ebgeom's own order with the axis as a number.
#include "ebgeom/sdf/shapes.hpp"
#include "ebgeom/sdf/transforms.hpp"

int main() {
  const ebgeom::Box<double> box{{0.3, 2, 0.5}};
  const auto turned = ebgeom::rotate(box, 0, 90.0);
  return turned({0, 1.5, 0}) < 0 ? 0 : 1;
}
