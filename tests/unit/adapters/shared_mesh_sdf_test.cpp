// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/adapters/shared_mesh_sdf.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "eb_test_scenes.hpp"
#include "ebgeom/adapters/eb_function.hpp"
#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/io/write_mesh.hpp"
#include "test_support.hpp"

using namespace ebgeom;

namespace {
// `s` without the triangles whose vertices all have z > zmin: an open mesh (a hole at the top).
PolygonSoup<double> without_cap(const PolygonSoup<double>& s, double zmin) {
  PolygonSoup<double> out;
  out.vertices = s.vertices;
  for (std::size_t f = 0; f < s.face_count(); ++f) {
    const Index* c = s.indices.data() + s.offsets[f];
    bool above = true;
    for (std::size_t i = 0; i < s.face_size(f); ++i) above = above && s.vertices[c[i]].z > zmin;
    if (!above) out.add_face(std::vector<Index>(c, c + s.face_size(f)));
  }
  return out;
}
} // namespace

TEST(SharedMeshSdf, ClosedMeshEqualsTheMeshSdf) {
  // The library's default sign (automatic) picks the pseudonormal sign on a closed mesh, so the
  // shared SDF is MeshSdf bit for bit.
  const auto soup = make_icosphere<double>(2, 0.8).value();
  const auto shared = make_shared_mesh_sdf(soup);
  ASSERT_TRUE(shared.has_value());
  EXPECT_EQ((*shared)->resolved_mode(), SignMode::pseudonormal) << (*shared)->reason();
  const auto direct = MeshSdf<double>::build(soup).value();
  for (const auto& p : test::random_points(Aabb<double>::of({-1, -1, -1}, {1, 1, 1}), 300))
    EXPECT_EQ((**shared)(p), direct(p));
  EXPECT_EQ(shared->use_count(), 1);
  EXPECT_GT((*shared)->memory_bytes(), 0u);
}

TEST(SharedMeshSdf, DefaultSignIsTheLibrarysAutomaticSign) {
  // An icosphere with a cap removed is open: the default (automatic) takes the winding sign, as
  // SignedMeshSdf::build and the command line's --sign auto do, and the centre stays inside.
  const auto open = without_cap(make_icosphere<double>(3, 0.8).value(), 0.6);
  const auto shared = make_shared_mesh_sdf(open).value();
  const auto reference = SignedMeshSdf<double>::build(open).value();
  EXPECT_EQ(shared->resolved_mode(), SignMode::fast_winding) << shared->reason();
  EXPECT_EQ(shared->resolved_mode(), reference.resolved_mode());
  for (const auto& p : test::random_points(Aabb<double>::of({-1, -1, -1}, {1, 1, 1}), 300))
    EXPECT_EQ((*shared)(p), reference(p));
  EXPECT_LT((*shared)({0, 0, 0}), -0.5);
  // Asking for the pseudonormal sign is still possible.
  SignOptions pn;
  pn.mode = SignMode::pseudonormal;
  EXPECT_EQ(make_shared_mesh_sdf(open, pn).value()->resolved_mode(), SignMode::pseudonormal);
}

TEST(SharedMeshSdf, FromAFileReadByTheLibrarysReader) {
  const auto soup = make_icosphere<float>(2, 0.8f).value();
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "ebgeom_shared_mesh_sdf_test.stl";
  ASSERT_TRUE(io::write_mesh(path.string(), soup).has_value());
  const auto read = io::read_mesh<float>(path.string());
  std::filesystem::remove(path);
  ASSERT_TRUE(read.has_value()) << read.error().what();
  const auto shared = make_shared_mesh_sdf(*read);
  ASSERT_TRUE(shared.has_value()) << shared.error().what();
  EXPECT_LT((**shared)({0, 0, 0}), -0.7f); // inside: negative (ebgeom's convention)
  EXPECT_GT((**shared)({1.5f, 0, 0}), 0.6f);
  const auto f = make_eb_function(*shared); // the EB adapter shares it
  EXPECT_EQ(&f.sdf(), shared->get());
  EXPECT_GT(f(0.0, 0.0, 0.0), 0.7);
}

TEST(SharedMeshSdf, ReportsErrorsAsValues) {
  const auto empty = make_shared_mesh_sdf(PolygonSoup<double>{});
  ASSERT_FALSE(empty.has_value());
  SignOptions bad;
  bad.mode = static_cast<SignMode>(42);
  EXPECT_FALSE(make_shared_mesh_sdf(make_icosphere<double>(1, 0.8).value(), bad).has_value());
}
