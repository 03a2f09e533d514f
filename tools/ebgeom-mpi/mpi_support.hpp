// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// MPI plumbing of ebgeom-mpi: collective error agreement (every rank ends with the same code and
// one message, never a hang) and small typed collectives.

#include <mpi.h>

#include <exception>
#include <new>
#include <string>
#include <vector>

#include "ebgeom/core/error.hpp"
#include "ebgeom/scene/error.hpp"
#include "ebgeom/scene/system.hpp"

namespace ebgeom::mpi {

/// Outcome of one rank's phase: 0 or an `ebgeom::scene::Exit` code, with its message.
struct Status {
  int code = 0;
  std::string message;
  explicit operator bool() const noexcept { return code == 0; }
};

/// Thrown once every rank agrees that a phase failed; main() prints `message` on rank 0 only.
struct Abort {
  Status status;
};

/// Runs `f` and turns the exceptions the CLI code throws into a `Status`.
template <class F> Status guarded(F&& f) {
  try {
    f();
    return {};
  } catch (const scene::ToolError& e) {
    return {e.code, e.what()};
  } catch (const ebgeom::Exception& e) {
    return {scene::exit_failure, e.what()};
  } catch (const std::bad_alloc&) {
    return {scene::exit_resource, "out of memory"};
  } catch (const std::exception& e) {
    return {scene::exit_failure, e.what()};
  }
}

/// Collective: the status of the lowest failing rank, on every rank (ok if none failed).
inline Status agree(const Status& mine, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int me = mine.code != 0 ? rank : size;
  int first = size;
  MPI_Allreduce(&me, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == size) return {};
  Status s = mine;
  int len = int(s.message.size());
  MPI_Bcast(&s.code, 1, MPI_INT, first, comm);
  MPI_Bcast(&len, 1, MPI_INT, first, comm);
  s.message.resize(std::size_t(len));
  if (len > 0) MPI_Bcast(s.message.data(), len, MPI_CHAR, first, comm);
  if (first != 0) s.message = "rank " + std::to_string(first) + ": " + s.message;
  return s;
}

/// Collective: runs `f` on every rank (guarded) and throws `Abort` on every rank if any failed.
template <class F> void phase(MPI_Comm comm, F&& f) {
  const Status s = agree(guarded(f), comm);
  if (!s) throw Abort{s};
}

/// Collective: `v` from every rank, in rank order.
inline std::vector<double> allgather(double v, MPI_Comm comm) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  std::vector<double> all(std::size_t(size), 0.0);
  MPI_Allgather(&v, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, comm);
  return all;
}

inline std::string error_string(int rc) {
  char text[MPI_MAX_ERROR_STRING];
  int len = 0;
  MPI_Error_string(rc, text, &len);
  return std::string(text, std::size_t(len));
}

} // namespace ebgeom::mpi
