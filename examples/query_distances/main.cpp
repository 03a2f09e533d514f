// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Signed distances from C++: read a mesh (or generate a sphere), check it, build the SDF once,
// then query single points, closest points and a batch. Checks every value against the O(n)
// brute force and exits 1 on any difference. docs/tasks/query-distances-from-cpp.md walks
// through it.
//
//   ebgeom_example_query_distances [MESH]   (STL, PLY, OBJ or VTK; default: a generated sphere)
#include <cstdio>
#include <string>
#include <vector>

#include "ebgeom/eval/evaluate.hpp"
#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/mesh/validate.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"
#include "ebgeom/sdf/signed_mesh_sdf.hpp"

using namespace ebgeom;

int main(int argc, char** argv) {
  using T = double;
  // 1. A polygon soup: from a file (errors say file, line or byte, and what was expected) ...
  PolygonSoup<T> soup;
  if (argc > 1) {
    auto read = io::read_mesh<T>(argv[1]);
    if (!read) {
      std::fprintf(stderr, "%s\n", read.error().what().c_str());
      return 2;
    }
    soup = std::move(*read);
  } else { // ... or generated: a unit sphere of 1,280 triangles
    soup = make_icosphere<T>(3, T(1)).value();
  }

  // 2. Is the signed distance well defined? (closed, manifold, consistently oriented)
  const ValidationReport<T> report = validate(soup);
  std::printf("%s\n", report.verdict.c_str());

  // 3. Build once (BVH over the triangles). The automatic sign uses pseudonormals on a clean
  //    mesh and the fast winding number otherwise; the magnitude is always exact.
  auto built = SignedMeshSdf<T>::build(soup);
  if (!built) {
    std::fprintf(stderr, "%s\n", built.error().what().c_str());
    return 2;
  }
  const SignedMeshSdf<T>& sdf = *built;
  std::printf("sign: %s (%s)\n", to_string(sdf.resolved_mode()), sdf.reason().c_str());

  // 4. Query: S < 0 inside, > 0 outside, |S| = distance to the surface. Const and thread-safe.
  const Aabb<T> box = sdf.bounds();
  const Vec3<T> centre = (box.lo + box.hi) * T(0.5);
  const Vec3<T> outside = box.hi + (box.hi - box.lo) * T(0.25);
  std::printf("S(centre of box) = %.6f\nS(outside corner) = %.6f\n", sdf(centre), sdf(outside));
  const MeshClosestPoint<T> c = sdf.closest(outside);
  std::printf("closest point to the outside corner: (%.6f, %.6f, %.6f), triangle %u\n", c.point[0],
              c.point[1], c.point[2], unsigned(c.triangle));

  // 5. Many points at once (threaded): evaluate(sdf, points, out).
  std::vector<Vec3<T>> points;
  for (int i = 0; i <= 100; ++i) points.push_back(box.lo + (box.hi - box.lo) * (T(i) / T(100)));
  std::vector<T> values(points.size());
  if (!evaluate(sdf, Span<const Vec3<T>>(points), Span<T>(values))) return 2;

  // Check against the brute force (every triangle for every point), bit for bit on the
  // distance; the sign only where the automatic mode chose pseudonormals.
  const auto brute = BruteForceMeshSdf<T>::build(soup).value();
  const bool same_sign_rule = sdf.resolved_mode() == SignMode::pseudonormal;
  std::size_t bad = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const T b = brute(points[i]);
    const bool ok = same_sign_rule ? values[i] == b : std::abs(values[i]) == std::abs(b);
    bad += ok ? 0 : 1;
  }
  std::printf("%zu points evaluated, %zu differ from the brute force\n", points.size(), bad);
  return bad == 0 ? 0 : 1;
}
