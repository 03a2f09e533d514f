// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// Checks shared by the reader fuzz targets: an error has a code and a message; a mesh has
// consistent offsets, faces of at least 3 corners, indices in range and finite coordinates.
// Any violation aborts, which libFuzzer and the replayer report.

#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "ebgeom/io.hpp"

namespace ebgeom::fuzz {

inline void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz check failed: %s\n", what);
    std::abort();
  }
}

template <class T> void check_result(const Result<PolygonSoup<T>, ParseError>& r) {
  if (!r.has_value()) {
    check(r.error().code != ErrorCode::ok, "an error has a code");
    check(!r.error().message.empty(), "an error has a message");
    (void)r.error().what();
    return;
  }
  const PolygonSoup<T>& s = *r;
  check(!s.offsets.empty() && s.offsets[0] == 0, "offsets start at 0");
  check(s.offsets.back() == s.indices.size(), "offsets end at the index count");
  check(s.face_count() > 0, "a mesh has faces");
  for (std::size_t f = 0; f < s.face_count(); ++f)
    check(s.offsets[f + 1] >= s.offsets[f] + 3, "faces have at least 3 corners");
  for (Index i : s.indices) check(i < s.vertex_count(), "indices are in range");
  for (const Vec3<T>& v : s.vertices) check(all_finite(v), "coordinates are finite");
}

/// Limits that keep a fuzz run's memory small (the readers' own checks are what is tested).
inline io::ReadOptions fuzz_options() {
  io::ReadOptions opt;
  opt.path = "fuzz";
  opt.max_triangles = std::uint64_t(1) << 22;
  return opt;
}

inline io::ByteView view(const std::uint8_t* data, std::size_t size) {
  return io::ByteView(reinterpret_cast<const char*>(data), size);
}

} // namespace ebgeom::fuzz
