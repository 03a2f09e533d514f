// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// One `MeshSdf` passed between translation units compiled for different instruction sets: this
// file with the build's baseline flags, part_wide.cpp with AVX2/FMA (or AVX-512). A type whose
// layout followed the compile flags (as the default block width once did) would give the two
// files different `Part` layouts, an ODR violation that links cleanly and reads garbage.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"
#include "part.hpp"

using namespace ebgeom;

namespace {
std::vector<Vec3<double>> points(std::size_t n) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.6, 1.6);
  std::vector<Vec3<double>> p(n);
  for (auto& q : p) q = {u(rng), u(rng), u(rng) * 0.5};
  return p;
}
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
} // namespace

TEST(IsaLayout, DefaultTypesHaveOneLayoutWhateverTheFlags) {
  EXPECT_EQ(isa_test::wide_block_width_float(), MeshSdf<float>::block_width);
  EXPECT_EQ(isa_test::wide_block_width_double(), MeshSdf<double>::block_width);
  EXPECT_EQ(isa_test::wide_sizeof_part(), sizeof(isa_test::Part));
}

TEST(IsaLayout, MeshSdfBuiltInOneUnitAnswersInTheOther) {
  const auto brute = BruteForceMeshSdf<double>::build(isa_test::test_soup<double>()).value();
  const auto pts = points(2000);

  // Built with wide flags, queried here.
  const isa_test::Part wide = isa_test::make_part_wide();
  // Built here, queried with wide flags.
  const isa_test::Part here{MeshSdf<float>::build(isa_test::test_soup<float>()).value(),
                            MeshSdf<double>::build(isa_test::test_soup<double>()).value()};
  const std::vector<double> there = isa_test::query_wide(here, pts);
  ASSERT_EQ(there.size(), pts.size());

  std::size_t bad_here = 0, bad_there = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double ref = brute(pts[i]);
    bad_here += !same_bits(wide.d(pts[i]), ref);
    bad_there += !same_bits(there[i], ref);
  }
  EXPECT_EQ(bad_here, 0u) << "a MeshSdf built with wide flags answers wrongly here";
  EXPECT_EQ(bad_there, 0u) << "a MeshSdf built here answers wrongly with wide flags";
}
