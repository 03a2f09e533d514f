// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// `write_vdb` in a build without OpenVDB: a clear error saying how to get it.
#include "ebgeom/jobs/vdb_output.hpp"

namespace ebgeom::jobs {

namespace {
Result<std::uint64_t> no_openvdb(const std::string& path) {
  return make_error(ErrorCode::unsupported, path,
                    ": this ebgeom was built without OpenVDB, so it cannot write .vdb files; "
                    "install OpenVDB (Debian/Ubuntu: apt install libopenvdb-dev) and rebuild "
                    "(CMake finds it, or pass -DEBGEOM_WITH_OPENVDB=ON), or write the band as "
                    ".npz (-o OUT.npz --band W)");
}
} // namespace

bool vdb_available() { return false; }
Result<std::uint64_t> write_vdb(const std::string& path, const SparseGrid<float>&) {
  return no_openvdb(path);
}
Result<std::uint64_t> write_vdb(const std::string& path, const SparseGrid<double>&) {
  return no_openvdb(path);
}

} // namespace ebgeom::jobs
