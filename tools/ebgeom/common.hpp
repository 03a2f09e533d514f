// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// Shared pieces of the ebgeom command-line tool: exit codes, the error type every subcommand
// throws, and small utilities.

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "ebgeom/core/error.hpp"

namespace ebgeom::cli {

/// Exit statuses (documented in docs/cli.md).
enum Exit : int {
  exit_ok = 0,
  exit_failure = 1,  ///< unexpected internal failure
  exit_usage = 2,    ///< bad command line (unknown option, bad value, missing argument)
  exit_input = 3,    ///< an input file is missing, unreadable or malformed
  exit_output = 4,   ///< an output file cannot be written
  exit_resource = 5, ///< the job needs more memory than the machine has
};

/// Thrown by subcommands; main() prints `ebgeom: error: <what>` and exits with `code`.
struct CliError : std::runtime_error {
  CliError(int code_, const std::string& what) : std::runtime_error(what), code(code_) {}
  int code;
};

[[noreturn]] inline void fail(int code, const std::string& what) { throw CliError(code, what); }

/// Bytes of memory the machine can still give (MemAvailable in /proc/meminfo); 0 if unknown.
std::uint64_t available_memory_bytes();

/// Throws `exit_resource` when `bytes` exceed the available memory, naming the size needed and
/// ending with `hint` (what the user can do instead).
void require_memory(std::uint64_t bytes, const std::string& what,
                    const std::string& hint = "lower the resolution (--res/--dx) or shrink --box");

/// Throws CliError (input) unless `path` names an existing regular file (following links):
/// `FILE: no such file`, `FILE: is a directory, not a file`, `FILE: is a FIFO (named pipe), not
/// a regular file; ...` (FIFOs, devices and sockets would block or never end).
void require_input_file(const std::string& path);

/// Throws CliError (output) unless `path` is something an output may be written to
/// (`ebgeom::check_output_target`): checked before the work, so a refused target costs nothing.
void require_output_target(const std::string& path);

/// "1.5 GiB" style size.
std::string human_bytes(std::uint64_t bytes);

/// True when stderr is a terminal.
bool stderr_is_terminal();

/// Seconds since `t0` (steady clock, in seconds since an arbitrary epoch from `now_s()`).
double now_s();

} // namespace ebgeom::cli
