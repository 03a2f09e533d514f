// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// A downstream project: includes the umbrella header and evaluates something.
#include <ebgeom/ebgeom.hpp>

#include <cstdio>
#include <cstring>

int main() {
#ifdef EXPECTED_VERSION
  if (std::strcmp(ebgeom::version_string, EXPECTED_VERSION) != 0) {
    std::fprintf(stderr, "header version %s, package version %s\n", ebgeom::version_string,
                 EXPECTED_VERSION);
    return 1;
  }
#endif
  const ebgeom::Aabb<double> box = ebgeom::Aabb<double>::of({0, 0, 0}, {1, 1, 1});
  return box.distance({2, 0.5, 0.5}) == 1.0 ? 0 : 1;
}
