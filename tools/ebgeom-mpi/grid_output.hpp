// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// Distributed grid output of ebgeom-mpi:
//  - `.pvti`: one VTK ImageData piece per rank (`OUT_<rank>.vti` beside `OUT.pvti`), each piece
//    holding its box plus one layer of samples on its upper faces (VTK pieces share their
//    boundary points, otherwise ParaView shows a gap of one cell between pieces); the bytes come
//    from the library's `write_vti_piece` and `write_pvti`;
//  - `.npy` / `.raw`: one file written collectively with MPI-IO; rank 0 writes the header, every
//    rank writes its box through a subarray file view (`npy_header` of the library). The bytes
//    equal the serial writers'.
// Every output is written under a temporary name and renamed when all ranks succeeded.

#include <mpi.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "ebgeom/eval/decompose.hpp"
#include "ebgeom/eval/write_grid.hpp"
#include "mpi_support.hpp"

namespace ebgeom::mpi {

/// Output kinds of ebgeom-mpi, by extension.
enum class OutputKind { pvti, npy, raw };

/// The samples a .pvti piece of `owned` holds: `owned` plus one layer on each upper face that is
/// not the grid's.
inline GridRange piece_range(const GridRange& owned, const std::array<std::size_t, 3>& dims) {
  GridRange r = owned;
  for (int a = 0; a < 3; ++a) r.hi[a] = std::min(r.hi[a] + 1, dims[a]);
  return r;
}

/// `OUT.pvti` -> `OUT_<rank>.vti` (full path) and its name relative to the .pvti.
inline std::string piece_path(const std::string& pvti, int rank) {
  const std::filesystem::path p(pvti);
  return (p.parent_path() / (p.stem().string() + "_" + std::to_string(rank) + ".vti")).string();
}

/// The `.pvti` entries of the parts' pieces (`piece_range` of each non-empty part `r`, stored as
/// `OUT_<r>.vti`).
inline std::vector<PvtiPiece> pvti_pieces(const std::string& pvti, const Decomposition& dec,
                                          const std::array<std::size_t, 3>& dims) {
  std::vector<PvtiPiece> pieces;
  for (std::size_t r = 0; r < dec.parts.size(); ++r) {
    if (dec.parts[r].empty()) continue;
    pieces.push_back({piece_range(dec.parts[r].range, dims),
                      std::filesystem::path(piece_path(pvti, int(r))).filename().string()});
  }
  return pieces;
}

template <class T> MPI_Datatype mpi_type() { return sizeof(T) == 4 ? MPI_FLOAT : MPI_DOUBLE; }

/// Collective: writes `header` then the grid `spec` (x fastest) to `path` through MPI-IO, each
/// rank giving the values of its box `mine` (x fastest within it; may be empty). Written to a
/// temporary name that rank 0 renames onto `path` once every rank succeeded. Throws `Abort` on
/// every rank on failure (and removes the temporary).
template <class T>
void write_collective(const std::string& path, const std::string& header, const GridSpec<T>& spec,
                      const GridRange& mine, Span<const T> values, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  // A name unique to this run (rank 0's pid) beside the target, so a rename commits it.
  long pid = long(::getpid());
  MPI_Bcast(&pid, 1, MPI_LONG, 0, comm);
  const std::string tmp = path + ".ebgeom-mpi-" + std::to_string(pid);
  // A file left by an earlier run with the same pid would keep bytes past the end of this one.
  if (rank == 0) MPI_File_delete(tmp.c_str(), MPI_INFO_NULL);
  MPI_Barrier(comm);
  MPI_File fh = MPI_FILE_NULL;
  const int orc =
      MPI_File_open(comm, tmp.c_str(), MPI_MODE_CREATE | MPI_MODE_WRONLY, MPI_INFO_NULL, &fh);
  Status st;
  if (orc != MPI_SUCCESS)
    st = {scene::exit_output, path + ": cannot open for writing (" + error_string(orc) + ")"};
  st = agree(st, comm);
  if (!st) {
    if (fh != MPI_FILE_NULL) MPI_File_close(&fh);
    throw Abort{st};
  }
  const MPI_Datatype et = mpi_type<T>();
  const MPI_Offset total =
      MPI_Offset(header.size()) + MPI_Offset(spec.size()) * MPI_Offset(sizeof(T));
  // No MPI_File_set_size: it would give the file its full size as holes, hiding writes that never
  // happened (a full disk). The writes make the size; every one's count is checked, and the size
  // after closing.
  int rc = MPI_SUCCESS;
  std::uint64_t short_by = 0; // elements this rank asked to write but were not written
  if (rank == 0) {
    MPI_Status ws;
    rc = MPI_File_write_at(fh, 0, header.data(), int(header.size()), MPI_BYTE, &ws);
    int n = 0;
    if (rc == MPI_SUCCESS &&
        (MPI_Get_count(&ws, MPI_BYTE, &n) != MPI_SUCCESS || std::uint64_t(n) != header.size()))
      short_by += header.size() - std::uint64_t(n > 0 ? n : 0);
  }
  MPI_Datatype file_type = MPI_DATATYPE_NULL, row = MPI_DATATYPE_NULL;
  const auto d = mine.dims();
  const bool empty = mine.size() == 0;
  const std::size_t rows = empty ? 0 : d[1] * d[2];
  if (rows > std::size_t(INT32_MAX)) {
    st = {scene::exit_resource, path + ": a rank's part has over 2^31 rows; use more ranks"};
    rc = MPI_SUCCESS;
  }
  if (!empty) {
    const int sizes[3] = {int(spec.nz()), int(spec.ny()), int(spec.nx())};
    const int sub[3] = {int(d[2]), int(d[1]), int(d[0])};
    const int start[3] = {int(mine.lo[2]), int(mine.lo[1]), int(mine.lo[0])};
    MPI_Type_create_subarray(3, sizes, sub, start, MPI_ORDER_C, et, &file_type);
    MPI_Type_commit(&file_type);
    MPI_Type_contiguous(int(d[0]), et, &row);
    MPI_Type_commit(&row);
  }
  if (rc == MPI_SUCCESS)
    rc = MPI_File_set_view(fh, MPI_Offset(header.size()), et, empty ? et : file_type, "native",
                           MPI_INFO_NULL);
  if (rc == MPI_SUCCESS) {
    MPI_Status ws;
    const int count = st && !empty ? int(rows) : 0;
    rc = MPI_File_write_all(fh, values.data(), count, empty ? et : row, &ws);
    // OMPIO reports success on a short write (ENOSPC): the count of elements written tells.
    MPI_Count n = 0;
    const std::uint64_t want = std::uint64_t(count) * (empty ? 1 : d[0]);
    if (rc == MPI_SUCCESS && want > 0 &&
        (MPI_Get_elements_x(&ws, et, &n) != MPI_SUCCESS || n < 0 || std::uint64_t(n) != want))
      short_by += want - (n > 0 ? std::min(std::uint64_t(n), want) : 0);
  }
  const int crc = MPI_File_close(&fh);
  if (rc == MPI_SUCCESS) rc = crc;
  if (!empty) {
    MPI_Type_free(&file_type);
    MPI_Type_free(&row);
  }
  if (st && rc != MPI_SUCCESS)
    st = {scene::exit_output, path + ": write failed (" + error_string(rc) + ")"};
  if (st && short_by > 0)
    st = {scene::exit_output, path + ": write failed: " + std::to_string(short_by) +
                                  " values or bytes were not written (disk full?)"};
  if (st && rank == 0) { // every byte must have arrived: the size, and no hole where data belongs
    struct stat fs;
    if (::stat(tmp.c_str(), &fs) != 0)
      st = {scene::exit_output,
            path + ": the written file vanished (" + std::string(std::strerror(errno)) + ")"};
    else if (MPI_Offset(fs.st_size) != total)
      st = {scene::exit_output, path + ": write failed: the file holds " +
                                    std::to_string(fs.st_size) + " of its " +
                                    std::to_string(total) + " bytes (disk full?)"};
  }
  st = agree(st, comm);
  if (st && rank == 0 && std::rename(tmp.c_str(), path.c_str()) != 0)
    st = {scene::exit_output, path + ": cannot rename the temporary file onto it (" +
                                  std::string(std::strerror(errno)) + ")"};
  st = agree(st, comm);
  if (!st) {
    if (rank == 0) MPI_File_delete(tmp.c_str(), MPI_INFO_NULL);
    throw Abort{st};
  }
}

} // namespace ebgeom::mpi
