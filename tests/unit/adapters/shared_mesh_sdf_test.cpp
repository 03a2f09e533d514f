// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/adapters/shared_mesh_sdf.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "eb_test_scenes.hpp"
#include "ebgeom/adapters/eb_function.hpp"
#include "ebgeom/io/write_mesh.hpp"
#include "test_support.hpp"

using namespace ebgeom;

TEST(SharedMeshSdf, EqualsTheMeshSdfItWraps) {
  const auto soup = make_icosphere<double>(2, 0.8).value();
  const auto shared = make_shared_mesh_sdf(soup);
  ASSERT_TRUE(shared.has_value());
  const auto direct = MeshSdf<double>::build(soup).value();
  for (const auto& p : test::random_points(Aabb<double>::of({-1, -1, -1}, {1, 1, 1}), 300))
    EXPECT_EQ((**shared)(p), direct(p));
  EXPECT_EQ(shared->use_count(), 1);
  EXPECT_GT((*shared)->memory_bytes(), 0u);
}

TEST(SharedMeshSdf, ReadsAFileAndBuildsOnce) {
  const auto soup = make_icosphere<float>(2, 0.8f).value();
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "ebgeom_shared_mesh_sdf_test.stl";
  ASSERT_TRUE(io::write_mesh(path.string(), soup).has_value());
  const auto shared = read_shared_mesh_sdf<float>(path.string());
  std::filesystem::remove(path);
  ASSERT_TRUE(shared.has_value()) << shared.error().what();
  EXPECT_LT((**shared)({0, 0, 0}), -0.7f); // inside: negative (ebgeom's convention)
  EXPECT_GT((**shared)({1.5f, 0, 0}), 0.6f);
  const auto f = make_eb_function(*shared); // the EB adapter shares it
  EXPECT_EQ(&f.sdf(), shared->get());
  EXPECT_GT(f(0.0, 0.0, 0.0), 0.7);
}

TEST(SharedMeshSdf, ReportsErrorsAsValues) {
  const std::string missing = "/nonexistent/ebgeom/no_such_mesh.stl";
  const auto r = read_shared_mesh_sdf<double>(missing);
  ASSERT_FALSE(r.has_value());
  EXPECT_NE(r.error().what().find("no_such_mesh.stl"), std::string::npos) << r.error().what();
  const auto empty = make_shared_mesh_sdf(PolygonSoup<double>{});
  ASSERT_FALSE(empty.has_value());
}
