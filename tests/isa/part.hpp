// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// A user's aggregate holding default `MeshSdf` types, shared by two translation units compiled
// for different instruction sets (part_wide.cpp with AVX2/FMA or AVX-512, the test without).
// The layout of `Part` must not depend on the flags of the translation unit that sees it.

#include <vector>

#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"

namespace isa_test {

struct Part {
  ebgeom::MeshSdf<float> f;
  ebgeom::MeshSdf<double> d;
};

/// Built and queried in the wider translation unit.
Part make_part_wide();
std::vector<double> query_wide(const Part& part, const std::vector<ebgeom::Vec3<double>>& points);
int wide_block_width_float();
int wide_block_width_double();
std::size_t wide_sizeof_part();

/// The mesh both translation units use: a torus of 1,600 triangles.
template <class T> ebgeom::PolygonSoup<T> test_soup() {
  return ebgeom::make_torus<T>(T(1), T(0.35), 40, 20).value();
}

} // namespace isa_test
