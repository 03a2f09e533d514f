// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// The error the scene component throws, with the exit status the command-line tools give it.
// The tools (`ebgeom`, `ebgeom-mpi`) print `what()` and exit with `code`; the Python package maps
// the code to an exception type.

#include <stdexcept>
#include <string>

namespace ebgeom::scene {

/// Exit statuses of the command-line tools (documented in docs/cli.md).
enum Exit : int {
  exit_ok = 0,
  exit_failure = 1,  ///< unexpected internal failure
  exit_usage = 2,    ///< bad command line (unknown option, bad value, missing argument)
  exit_input = 3,    ///< an input file is missing, unreadable or malformed
  exit_output = 4,   ///< an output file cannot be written
  exit_resource = 5, ///< the job needs more memory than the machine has
};

/// A failure with its exit status: one line naming the file and what is wrong with it.
struct ToolError : std::runtime_error {
  ToolError(int code_, const std::string& what) : std::runtime_error(what), code(code_) {}
  int code;
};

/// Throws `ToolError(code, what)`.
[[noreturn]] inline void fail(int code, const std::string& what) { throw ToolError(code, what); }

} // namespace ebgeom::scene
