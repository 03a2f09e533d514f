// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Must NOT compile: EBGeometry's rotate(angle, axis) ported with the numbers unchanged. Before
// ebgeom had a strong axis type this compiled and rotated by 0 degrees about "axis 90", i.e. did
// nothing.
#include "ebgeom/sdf/shapes.hpp"
#include "ebgeom/sdf/transforms.hpp"

int main() {
  const ebgeom::Box<double> box{{0.3, 2, 0.5}};
  const auto turned = ebgeom::rotate(box, 90, 0); // 90 degrees about x, in EBGeometry's order
  return turned({0, 1.5, 0}) < 0 ? 0 : 1;
}
