// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Mesh structures on the real meshes of ../shared/meshes (skipped when absent): every file
// validates without crashing and builds both meshes; on the meshes whose signed distance is well
// defined, the DCEL and triangle-mesh oracles agree and their signs match a winding-number oracle.
// On every mesh file there, raw and welded, in float and double, the triangle mesh's edge links
// give back the per-side edge pseudonormal table bit for bit.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>

#include "ebgeom/geom/solid_angle.hpp"
#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/mesh/half_edge_mesh.hpp"
#include "ebgeom/mesh/validate.hpp"
#include "ebgeom/mesh/weld.hpp"
#include "ebgeom/sdf/brute_force_dcel_sdf.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"
#include "edge_normal_reference.hpp"
#include "test_support.hpp"

using namespace ebgeom;

namespace {

PolygonSoup<double> load(const std::string& name) {
  auto r = io::read_mesh<double>(test::mesh_path(name));
  if (!r) ADD_FAILURE() << r.error().what();
  return r ? std::move(*r) : PolygonSoup<double>{};
}

double winding(const TriangleMesh<double>& m, const Vec3<double>& p) {
  double w = 0;
  for (std::size_t t = 0; t < m.triangle_count(); ++t)
    w += solid_angle(p, m.corner(t, 0), m.corner(t, 1), m.corner(t, 2));
  return w / (4 * 3.14159265358979323846);
}

class RealMesh : public ::testing::TestWithParam<const char*> {};

TEST_P(RealMesh, ValidatesBuildsAndAgrees) {
  const std::string name = GetParam();
  EBGEOM_REQUIRE_MESH(name);
  PolygonSoup<double> soup = load(name);
  ASSERT_GT(soup.face_count(), 0u);
  soup = weld(soup).value().soup;
  const auto report = validate(soup);
  RecordProperty("verdict", report.verdict);
  std::printf("%s: %s\n", name.c_str(), report.verdict.c_str());
  EXPECT_EQ(report.face_count, soup.face_count());
  EXPECT_EQ(report.bad_index_faces.count + report.short_faces.count, 0u);
  const auto dcel = make_half_edge_mesh(soup).value();
  const auto tri = make_triangle_mesh(soup).value();
  EXPECT_EQ(dcel.face_count(), soup.face_count());
  EXPECT_EQ(tri.triangle_count(), soup.triangle_count());
  EXPECT_EQ(dcel.is_closed_manifold(),
            report.closed() && report.non_manifold_edges.empty() && report.consistently_oriented());
  if (!report.sdf_well_defined || soup.face_count() > 20000) return;

  const BruteForceMeshSdf<double> sdf(tri);
  const BruteForceDcelSdf<double> dsdf(dcel);
  const Aabb<double> box = soup.bounds();
  const double scale = norm(box.extent());
  int inside = 0;
  for (const auto& p : test::random_points(box.grown(0.1 * scale), 60, 99)) {
    const double a = sdf(p), b = dsdf(p);
    EXPECT_NEAR(a, b, 1e-9 * scale) << p;
    if (std::abs(a) > 1e-6 * scale) {
      const bool in = winding(tri, p) > 0.5;
      EXPECT_EQ(a < 0, in) << p << " sdf " << a;
      inside += in;
    }
  }
  EXPECT_GT(inside, 0);
}

INSTANTIATE_TEST_SUITE_P(Shared, RealMesh,
                         ::testing::Values("formats/dodecahedron.obj", "formats/dodecahedron.stl",
                                           "formats/dodecahedron.ply", "formats/dodecahedron.vtk",
                                           "formats/tetrahedron.stl", "cow.obj", "spot.obj",
                                           "fandisk.obj", "teapot.obj", "suzanne.obj",
                                           "stanford-bunny.obj", "igea.ply"));

} // namespace

template <class T> class RealMeshEdgeLinks : public ::testing::Test {};
TYPED_TEST_SUITE(RealMeshEdgeLinks, test::FloatTypes);

TYPED_TEST(RealMeshEdgeLinks, EqualTheEdgeNormalTableBitForBit) {
  using T = TypeParam;
  namespace fs = std::filesystem;
  const fs::path dir(EBGEOM_TEST_MESH_DIR);
  if (!fs::is_directory(dir)) GTEST_SKIP() << "shared meshes " << dir << " are absent";
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string ext = e.path().extension().string();
    if (e.is_regular_file() && (ext == ".obj" || ext == ".ply" || ext == ".stl" || ext == ".vtk"))
      files.push_back(e.path());
  }
  if (files.empty())
    GTEST_SKIP() << "no .obj/.ply/.stl/.vtk mesh under " << dir << " (nothing to compare)";
  std::sort(files.begin(), files.end());
  std::size_t sides = 0;
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.string());
    auto soup = io::read_mesh<T>(f.string());
    ASSERT_TRUE(soup.has_value()) << soup.error().what();
    sides += test::expect_edge_normals_match(*soup);
    sides += test::expect_edge_normals_match(weld(*soup).value().soup);
  }
  std::printf("%zu files, %zu triangle sides compared\n", files.size(), sides);
}
