// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Compiled with wider instruction-set flags than the rest of the test (see tests/CMakeLists.txt).
#include "part.hpp"

namespace isa_test {

Part make_part_wide() {
  return Part{ebgeom::MeshSdf<float>::build(test_soup<float>()).value(),
              ebgeom::MeshSdf<double>::build(test_soup<double>()).value()};
}

std::vector<double> query_wide(const Part& part, const std::vector<ebgeom::Vec3<double>>& points) {
  std::vector<double> out;
  for (const auto& p : points) out.push_back(part.d(p));
  return out;
}

int wide_block_width_float() { return ebgeom::MeshSdf<float>::block_width; }
int wide_block_width_double() { return ebgeom::MeshSdf<double>::block_width; }
std::size_t wide_sizeof_part() { return sizeof(Part); }

} // namespace isa_test
