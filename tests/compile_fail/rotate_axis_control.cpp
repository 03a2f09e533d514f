// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Must compile (the control for the compile-fail sources beside it): the same calls written with
// ebgeom::Axis.
#include "ebgeom/sdf/shapes.hpp"
#include "ebgeom/sdf/transforms.hpp"

int main() {
  const ebgeom::Box<double> box{{0.3, 2, 0.5}};
  const auto turned = ebgeom::rotate(box, ebgeom::Axis::x, 90); // EBGeometry's rotate(90, 0)
  const auto turned2 = ebgeom::rotate(box, ebgeom::Axis::x, 90.0);
  const ebgeom::Sphere<double> ball{{2, 0, 0}, 0.5};
  const auto twins = ebgeom::mirror(ball, ebgeom::Axis::x);
  return turned({0, 0, 1.5}) < 0 && turned2({0, 0, 1.5}) < 0 && twins({-2, 0, 0}) < 0 ? 0 : 1;
}
